"""Tests of reports/speed_accuracy.py: the Pareto front on synthetic sets (with negative cases),
then the join + chart end to end on a synthetic accuracy CSV and benchmark JSON.
Exit 0 pass, 1 fail, 77 skip (ctest SKIP_RETURN_CODE) when /usr/bin/python3 lacks matplotlib
after the front tests passed."""
import csv
import importlib.util
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "reports"))
import speed_accuracy as sa  # noqa: E402

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


# (time, error): 0 and 1 are on the front; 2 is dominated by 1 (slower and less accurate);
# 3 ties 1 in time with a larger error (dominated); 4 equals 0 exactly (kept); 5 is the slow but
# exact end of the front; 6 is dominated by 5 at the same error.
pts = [(1.0, 1e-3), (2.0, 1e-6), (3.0, 1e-5), (2.0, 1e-4), (1.0, 1e-3), (10.0, 0.0), (11.0, 0.0)]
front = sa.pareto_front(pts)
check(front == [0, 1, 4, 5], f"front of the synthetic set is [0, 1, 4, 5] (got {front})")
check(sa.is_pareto_front(pts, front), "brute-force check accepts the computed front")
# Negative cases: the checker rejects a front that keeps a dominated point or drops a front point,
# and the sweep never keeps point 2 (dominated on both axes).
check(not sa.is_pareto_front(pts, [0, 1, 2, 4, 5]), "checker rejects a front with dominated 2")
check(not sa.is_pareto_front(pts, [0, 4, 5]), "checker rejects a front missing point 1")
check(2 not in front and 3 not in front and 6 not in front, "dominated points are not on front")
check(sa.pareto_front([]) == [] and sa.pareto_front([(5.0, 1.0)]) == [0], "empty and single")
# A set with a strictly increasing trade-off: every point is on the front.
chain = [(float(t), 10.0 ** -t) for t in range(1, 8)]
check(sa.pareto_front(chain) == list(range(7)), "a pure trade-off chain is all front")
# Random sets against the brute-force definition.
import random
rng = random.Random(20261201)
for trial in range(200):
    p = [(rng.choice([1.0, 2.0, 3.0, 4.0]), rng.choice([0.0, 1e-7, 1e-3, 1.0]))
         for _ in range(rng.randint(1, 12))]
    f = sa.pareto_front(p)
    if not sa.is_pareto_front(p, f):
        check(False, f"random set {p}: front {f} disagrees with the brute-force definition")
        break

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("pareto front tests passed")

if importlib.util.find_spec("matplotlib") is None:
    print(f"SKIP: {sys.executable} lacks matplotlib; the chart test needs it "
          "(Debian: apt-get install python3-matplotlib, see scripts/setup.sh)")
    sys.exit(77)

with tempfile.TemporaryDirectory() as d:
    acc = os.path.join(d, "accuracy.csv")
    cols = ["method", "kernel", "isa", "math", "reference", "n", "compared", "nonfinite_mismatch",
            "max_abs_error", "max_rel_error", "rms_rel_error", "p99_rel_error"]
    rows = [("k", "k", "scalar", "double_exact", 0.0, 10.0), ("k", "k", "avx2", "float_exact",
            1e-7, 1.0), ("k", "k", "avx2", "float_fast", 1e-4, 1.5),
            ("k", "k_printed", "avx2", "float_exact", 0.2, 0.5), ("k", "k", "avx512", "float_fast",
            1e-4, None)]
    with open(acc, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for m, k, i, fl, e, _ in rows:
            w.writerow([m, k, i, fl, f"{m}/scalar/double_exact", 100, 100, 0, e, e, e / 2, e])
    bench = {"context": {"cpu_model": "Synthetic CPU", "date": "2026-12-01T00:00:00"},
             "benchmarks": []}
    for _, k, i, fl, _, ns in rows:
        if ns is None:
            continue
        bench["benchmarks"].append({"name": f"{k}/{i}/{fl}_median", "run_name": f"{k}/{i}/{fl}",
                                    "run_type": "aggregate", "aggregate_name": "median",
                                    "items_per_second": 1e9 / ns})
        bench["benchmarks"].append({"name": f"{k}/{i}/{fl}_stddev", "run_name": f"{k}/{i}/{fl}",
                                    "run_type": "aggregate", "aggregate_name": "stddev",
                                    "items_per_second": 1.0})
    bj = os.path.join(d, "bench.json")
    with open(bj, "w") as f:
        json.dump(bench, f)
    sa.main(["--accuracy", acc, "--bench", bj, "--out-dir", d])
    with open(os.path.join(d, "speed_accuracy.csv"), newline="") as f:
        out = list(csv.DictReader(f))
    check(list(out[0].keys()) == sa.OUT_COLUMNS, "output columns")
    flags = {(r["kernel"], r["isa"], r["math"]): r["on_pareto_front"] for r in out}
    # double exact (10 ns, 0) and avx2 float exact (1 ns, 1e-7) and the printed formula
    # (0.5 ns, 0.2) are the front; float fast (1.5 ns, 1e-4) is dominated by float exact; the
    # avx512 row has no benchmark, so no time and no flag.
    check(flags[("k", "scalar", "double_exact")] == "1", "exact slow point on the front")
    check(flags[("k", "avx2", "float_exact")] == "1", "fast accurate point on the front")
    check(flags[("k_printed", "avx2", "float_exact")] == "1", "fastest point on the front")
    check(flags[("k", "avx2", "float_fast")] == "0", "dominated fast-math point not on front")
    untimed = [r for r in out if r["isa"] == "avx512"][0]
    check(untimed["ns_per_eval"] == "" and untimed["on_pareto_front"] == "0", "untimed row")
    ns = float([r for r in out if r["math"] == "float_fast" and r["isa"] == "avx2"][0]
               ["ns_per_eval"])
    check(abs(ns - 1.5) < 1e-9, f"ns_per_eval = 1e9 / items_per_second (got {ns})")
    png = os.path.join(d, "speed_accuracy.png")
    with open(png, "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "chart is a PNG")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("speed_accuracy end-to-end test passed")
