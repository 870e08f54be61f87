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
    check(all(r["source"] == "kernel" for r in out), "kernel rows have source=kernel")
    check(not os.path.exists(os.path.join(d, "speed_accuracy_methods.png")),
          "no methods chart without method rows")

    # --- Method rows (experiments/bench/METHOD_BENCHMARKS.md) joined with the kernel rows ----
    def entry(name, ns, err, agg=None, label="exact ref; rel. error", counters=True):
        e = {"name": name + (f"_{agg}" if agg else ""), "run_name": name,
             "run_type": "aggregate" if agg else "iteration", "items_per_second": 1e9 / ns,
             "label": label}
        if agg:
            e["aggregate_name"] = agg
        if counters:
            e.update(err_max=err, err_rms=err / 2, err_p99=err, err_n=100.0)
        return e
    # m.a: (ns, err_max): ref (50, 0) front; fast (1, 0.1) front; mid (5, 1e-3) front;
    # bad (6, 1e-2) dominated by mid. Median aggregate wins over its stddev (whose 'time' is
    # nonsense). m.b (another family) from repetitions without aggregates: median of runs.
    ma = [entry("method/fam_a.q_vs_ref/setting=ref", 50, 0.0, "median"),
          entry("method/fam_a.q_vs_ref/setting=ref", 1e-3, 0.0, "stddev"),
          entry("method/fam_a.q_vs_ref/setting=fast", 1, 0.1, "median"),
          entry("method/fam_a.q_vs_ref/setting=mid", 5, 1e-3, "median"),
          entry("method/fam_a.q_vs_ref/setting=bad", 6, 1e-2, "median"),
          entry("kernel_row/not/a_method", 1, 0.0)]
    mb = [entry("method/fam_b.x.n4/k=1,erf=fast", t, 1e-4) for t in (3.0, 1.0, 2.0)] + \
         [entry("method/fam_b.x.n4/k=2,erf=exact", 4, 1e-4)]
    paths = {}
    for name, b in (("bin_a", ma), ("bin_b", mb)):
        paths[name] = os.path.join(d, f"{name}.json")
        with open(paths[name], "w") as f:
            json.dump({"context": {}, "benchmarks": b}, f)
    empty = os.path.join(d, "bin_empty.json")
    open(empty, "w").close()  # Google Benchmark 1.7 with no matching row
    sa.main(["--accuracy", acc, "--bench", bj, "--out-dir", d, "--methods", paths["bin_a"],
             paths["bin_b"], empty])
    with open(os.path.join(d, "speed_accuracy.csv"), newline="") as f:
        out = list(csv.DictReader(f))
    meth = {(r["method"], r["setting"]): r for r in out if r["source"] == "method"}
    check(len(meth) == 6, f"6 method rows joined (got {sorted(meth)})")
    check(len([r for r in out if r["source"] == "kernel"]) == 5, "kernel rows kept beside them")
    a = lambda s: meth.get(("fam_a.q_vs_ref", f"setting={s}"), {})  # noqa: E731
    check([a(s).get("on_pareto_front") for s in ("ref", "fast", "mid", "bad")] ==
          ["1", "1", "1", "0"], "method front: ref, fast, mid on it; bad dominated")
    check(abs(float(a("ref").get("ns_per_eval", 0)) - 50) < 1e-9, "median aggregate's time")
    check(a("mid").get("binary") == "bin_a" and a("mid").get("reference") == "exact ref",
          "binary and reference (label before ';') columns")
    b1 = meth.get(("fam_b.x.n4", "k=1,erf=fast"), {})
    check(abs(float(b1.get("ns_per_eval", 0)) - 2.0) < 1e-9, "median of runs without aggregates")
    check(b1.get("on_pareto_front") == "1" and
          meth.get(("fam_b.x.n4", "k=2,erf=exact"), {}).get("on_pareto_front") == "0",
          "equal error, slower: dominated")
    # Each method's flags are exactly the brute-force front; a flipped flag is rejected.
    for m in {k[0] for k in meth}:
        g = [r for r in out if r["source"] == "method" and r["method"] == m]
        pts = [(float(r["ns_per_eval"]), float(r["rms_rel_error"])) for r in g]
        flags = [i for i, r in enumerate(g) if r["on_pareto_front"] == "1"]
        check(sa.is_pareto_front(pts, flags), f"{m}: CSV front is the brute-force front")
        wrong = sorted(set(flags) ^ {len(g) - 1})
        check(not sa.is_pareto_front(pts, wrong), f"{m}: a front with one flag flipped rejected")
    mpng = os.path.join(d, "speed_accuracy_methods.png")
    with open(mpng, "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "methods chart is a PNG")

    # Bad method JSONs: one-line error, exit 2, CSV untouched.
    def bad(benchmarks, what):
        path = os.path.join(d, "bad.json")
        with open(path, "w") as f:
            json.dump({"benchmarks": benchmarks}, f)
        before = open(os.path.join(d, "speed_accuracy.csv")).read()
        try:
            sa.main(["--accuracy", acc, "--bench", bj, "--out-dir", d, "--methods", path])
            check(False, f"{what}: accepted")
        except SystemExit as e:
            check(e.code == 2, f"{what}: exit 2 (got {e.code})")
        check(open(os.path.join(d, "speed_accuracy.csv")).read() == before,
              f"{what}: no partial output")
    bad([entry("method/no_setting", 1, 0.1)], "name without a setting")
    bad([entry("method/a b/k=1", 1, 0.1)], "space in the method id")
    bad([entry("method/a/k=1", 1, 0.1, counters=False)], "missing err_* counters")
    bad([entry("method/a/k=1", 1, -0.1)], "negative error")
    dup = os.path.join(d, "dup.json")
    with open(dup, "w") as f:
        json.dump({"benchmarks": [entry("method/fam_a.q_vs_ref/setting=ref", 1, 0.0)]}, f)
    try:
        sa.main(["--accuracy", acc, "--bench", bj, "--out-dir", d, "--methods", paths["bin_a"],
                 dup])
        check(False, "a row in two binaries accepted")
    except SystemExit as e:
        check(e.code == 2, "a row in two binaries: exit 2")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("speed_accuracy end-to-end test passed")
