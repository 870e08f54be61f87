"""Runs glintlab_accuracy (argv[1]) on a few inputs and checks its CSV: shape, exact-vs-itself
error 0, fast math and printed formulas nonzero error, and the one-line error on a bad --n."""
import csv
import math
import os
import subprocess
import sys
import tempfile

exe = sys.argv[1]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


COLUMNS = ["method", "kernel", "isa", "math", "reference", "n", "compared", "nonfinite_mismatch",
           "max_abs_error", "max_rel_error", "rms_rel_error", "p99_rel_error"]
N = 4096
with tempfile.TemporaryDirectory() as d:
    out = os.path.join(d, "sub", "accuracy.csv")
    subprocess.run([exe, "--n", str(N), "--out", out], check=True)
    with open(out, newline="") as f:
        reader = csv.DictReader(f)
        check(reader.fieldnames == COLUMNS, f"header {reader.fieldnames}")
        rows = list(reader)
    # Every (method, kernel) pair has the same ISAs, each with the three math flavours.
    pairs = {}
    for r in rows:
        pairs.setdefault((r["method"], r["kernel"]), []).append((r["isa"], r["math"]))
    isas = sorted({r["isa"] for r in rows})
    check("scalar" in isas, "scalar rows present")
    expect = sorted((i, m) for i in isas for m in ["float_exact", "float_fast", "double_exact"])
    for key, got in pairs.items():
        check(sorted(got) == expect, f"{key}: variants {sorted(got)}")
    check(len(rows) == len(pairs) * len(expect), "row count = pairs x ISAs x flavours")
    check(len(pairs) >= 50, f"at least 50 kernel/reference pairs (got {len(pairs)})")
    for r in rows:
        check(r["n"] == str(N), f"n column {r['n']}")
        check(r["reference"] == r["method"] + "/scalar/double_exact", "reference names method")
        v = [float(r[c]) for c in ["max_abs_error", "max_rel_error", "rms_rel_error",
                                   "p99_rel_error"]]
        check(all(math.isfinite(x) and x >= 0 for x in v), f"errors finite, >= 0: {r}")
        check(v[2] <= v[1] and v[3] <= v[1], f"rms and p99 <= max: {r}")
        check(int(r["compared"]) + int(r["nonfinite_mismatch"]) >= N, "all values compared")

    def get(kernel, method, isa, flavour):
        for r in rows:
            if (r["kernel"], r["method"], r["isa"], r["math"]) == (kernel, method, isa, flavour):
                return float(r["max_rel_error"])
        check(False, f"row {kernel} {method} {isa} {flavour} missing")
        return math.nan

    # The exact reference compared with itself: exactly zero, for every kernel.
    for (m, k) in pairs:
        if m == k:
            check(get(k, m, "scalar", "double_exact") == 0.0, f"{k}: reference vs itself is 0")
    # Fast math (rational erf, fast exp) must show: Beckmann total area (Eq. 30 uses erf/exp).
    k = "beckmann.total_area_eq30"
    fast, exact = get(k, k, "scalar", "float_fast"), get(k, k, "scalar", "float_exact")
    check(fast > 1e-6 and fast > 10 * exact, f"{k}: fast {fast} vs exact {exact}")
    # The printed formula differs from the exact one even in double.
    e = get("beckmann.total_area_eq31_printed", k, "scalar", "double_exact")
    check(e > 1e-3, f"Eq. 31 printed vs Eq. 30: {e}")

    bad = os.path.join(d, "bad.csv")
    p = subprocess.run([exe, "--n", "5", "--out", bad], capture_output=True, text=True)
    check(p.returncode == 2, f"--n 5 exits 2 (got {p.returncode})")
    check(p.stderr.startswith("glintlab: error: --n") and p.stderr.count("\n") == 1,
          f"one-line error naming --n: {p.stderr!r}")
    check(not os.path.exists(bad), "no output on bad input")
    p = subprocess.run([exe, "--n", "64", "--out", "/proc/glintlab/accuracy.csv"],
                       capture_output=True, text=True)
    check(p.returncode == 2 and p.stderr.startswith("glintlab: error: --out"),
          f"unwritable --out: exit 2 naming --out (got {p.returncode}, {p.stderr!r})")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print(f"accuracy CSV test passed: {len(rows)} rows, {len(pairs)} kernel/reference pairs")
