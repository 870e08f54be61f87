"""Smoke test of experiments/bench/python_eval.py (the speed of glintlab.eval from Python against
the C++ batch): run on 1000 rows, one repeat, and check the JSON's shape only (every case timed,
positive finite seconds, the ratios present). Never a speed assertion. Exit 0 pass, 1 fail.
Argument: the benchmark script; PYTHONPATH points at the build tree's glintlab package."""
import json
import math
import os
import subprocess
import sys
import tempfile

CASES = ["cpp_eval_batch", "python_eval_c_1thread", "python_eval_c", "python_eval_f_1thread",
         "python_eval_per_row_16_values_1thread", "python_eval_per_row_distinct_1thread",
         "numpy_model_direct", "numpy_model_direct_contiguous", "numpy_model_eval_1thread"]
RATIOS = ["python_eval_c_1thread_over_cpp", "python_eval_c_over_cpp",
          "python_eval_f_1thread_over_cpp", "per_row_16_values_over_cpp",
          "per_row_distinct_over_cpp", "numpy_model_chunked_over_direct",
          "numpy_model_chunked_over_direct_contiguous"]

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


def positive(x):
    return isinstance(x, (int, float)) and math.isfinite(x) and x > 0


with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "python_eval.json")
    run = subprocess.run([sys.executable, sys.argv[1], "--rows", "1000", "--repeats", "2",
                          "--out", out], capture_output=True, text=True, timeout=300)
    check(run.returncode == 0, f"the script exits 0 (got {run.returncode}: {run.stderr[-2000:]})")
    if run.returncode == 0:
        with open(out) as f:
            d = json.load(f)
        check(d.get("benchmark") == "python_eval", "benchmark is python_eval")
        check(d.get("rows") == 1000 and d.get("repeats") == 2, "rows and repeats as asked")
        check(d.get("isa") in ("scalar", "sse4.2", "avx2", "avx512"), f"an ISA name ({d.get('isa')})")
        check(isinstance(d.get("machine"), dict) and "cpu" in d["machine"], "machine described")
        cases = d.get("cases", {})
        check(sorted(cases) == sorted(CASES), f"the cases {sorted(cases)}")
        for name in CASES:
            c = cases.get(name, {})
            s = c.get("seconds", [])
            check(len(s) == 2 and all(positive(x) for x in s), f"{name}: two positive seconds")
            check(positive(c.get("median_s")) and positive(c.get("us_per_1e6_rows")),
                  f"{name}: median and µs per 10^6 rows")
        ratios = d.get("ratios", {})
        check(sorted(ratios) == sorted(RATIOS), f"the ratios {sorted(ratios)}")
        check(all(positive(ratios.get(r)) for r in RATIOS), "every ratio positive and finite")
    # Bad arguments: a one-line error and exit 2, nothing written.
    bad = subprocess.run([sys.executable, sys.argv[1], "--rows", "0", "--out", out + ".bad"],
                         capture_output=True, text=True, timeout=60)
    check(bad.returncode == 2 and not os.path.exists(out + ".bad"), "--rows 0 is refused (exit 2)")

print("FAIL" if failures else "PASS")
sys.exit(1 if failures else 0)
