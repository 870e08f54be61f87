"""End-to-end test of scripts/speed_accuracy.sh --quick on the built binaries: every binary of its
METHOD_BENCHES array runs its method/ rows (GLINTLAB_BENCH_QUICK=1), the rows follow
experiments/bench/METHOD_BENCHMARKS.md, are joined with real kernel rows into speed_accuracy.csv,
each method's front is the brute-force one (a flipped flag is rejected), references have error 0
and the approximations a nonzero error, and the methods chart is written.
Usage: speed_accuracy_methods_test.py REPO_ROOT BUILD_DIR. Exit 0 pass, 1 fail, 77 skip when
/usr/bin/python3 lacks matplotlib."""
import csv
import importlib.util
import json
import os
import re
import subprocess
import sys
import tempfile

repo, build = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(repo, "reports"))
import speed_accuracy as sa  # noqa: E402

if importlib.util.find_spec("matplotlib") is None:
    print(f"SKIP: {sys.executable} lacks matplotlib (scripts/setup.sh installs it)")
    sys.exit(77)

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)
        print(f"FAIL: {what}")


script = os.path.join(repo, "scripts", "speed_accuracy.sh")
with open(script) as f:
    text = f.read()
block = re.search(r"METHOD_BENCHES=\(\n(.*?)\n\)", text, re.S)
benches = [line.strip() for line in block.group(1).splitlines() if line.strip()] if block else []
check(len(benches) >= 4 and "glintlab_bench_kemppinen" in benches,
      f"METHOD_BENCHES lists the method binaries, Kemppinen's included (got {benches})")

# Families and methods checked here (others, e.g. kemppinen_*, exist as well).
expected = {
    "binomial.count_vs_exact.n16_p1e-1", "binomial.count_vs_exact.n1024_p1e-3",
    "binomial.count_vs_exact.n1024_p3e-1", "binomial.count_vs_exact.n1048576_p1e-6",
    "binomial.count_vs_exact.n1048576_p1e-4", "chermain.p22_vs_dict_ref.ggaa_projected_half",
    "chermain.p22_vs_dict_ref.ggaa_off", "chermain.p22_vs_levels_ref",
    "chermain.tube_pixel_vs_supersampled", "podee.value_vs_exact_area",
    "podee.pixel_vs_supersampled.d2", "podee.pixel_vs_supersampled.d4",
    "podee.pixel_vs_supersampled.d10"}
# Rows that are their method's reference (error exactly 0) and rows that must show an error.
references = {("binomial.count_vs_exact.n1024_p3e-1", "sampler=exact"),
              ("chermain.p22_vs_levels_ref", "L=10"),
              ("chermain.p22_vs_dict_ref.ggaa_off", "res=512"),
              ("podee.value_vs_exact_area", "precision=double,weighting=exact")}
approximate = {("binomial.count_vs_exact.n16_p1e-1", "sampler=realtime"),
               ("binomial.count_vs_exact.n1048576_p1e-4", "sampler=small_count"),
               ("chermain.p22_vs_dict_ref.ggaa_off", "res=16"),
               ("chermain.p22_vs_levels_ref", "L=4"),
               ("chermain.tube_pixel_vs_supersampled", "ggaa=off"),
               ("podee.value_vs_exact_area", "precision=double,weighting=none"),
               ("podee.pixel_vs_supersampled.d10", "method=centre")}

with tempfile.TemporaryDirectory() as d:
    bench_json = os.path.join(d, "bench.json")
    subprocess.run([os.path.join(build, "experiments", "bench", "glintlab_bench_kernels"),
                    r"--benchmark_filter=^ggx\.d/", "--benchmark_min_time=0.002",
                    f"--benchmark_out={bench_json}", "--benchmark_out_format=json"],
                   check=True, stdout=subprocess.DEVNULL)
    r = subprocess.run(["bash", script, "--quick", "--build-dir", build, "--out-dir", d,
                        "--bench-json", bench_json], capture_output=True, text=True)
    print(r.stdout.strip())
    check(r.returncode == 0, f"speed_accuracy.sh --quick exits 0 (got {r.returncode}: "
          f"{r.stderr.strip()[-400:]})")
    for b in benches:
        p = os.path.join(d, "methods", f"{b}.json")
        try:
            with open(p) as f:
                json.load(f)
        except (OSError, ValueError) as e:
            check(False, f"{p} is a JSON file ({e})")
    rows = []
    if os.path.exists(os.path.join(d, "speed_accuracy.csv")):
        with open(os.path.join(d, "speed_accuracy.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    meth = [x for x in rows if x["source"] == "method"]
    check(any(x["source"] == "kernel" and x["ns_per_eval"] for x in rows),
          "timed kernel rows joined beside the method rows")
    got = {x["method"] for x in meth}
    check(expected <= got, f"every method present (missing {sorted(expected - got)})")
    by = {(x["method"], x["setting"]): x for x in meth}
    for key in references:
        x = by.get(key)
        check(x is not None and float(x["max_rel_error"]) == 0 and x["on_pareto_front"] == "1",
              f"{key}: reference row, error 0, on its front")
    for key in approximate:
        x = by.get(key)
        check(x is not None and float(x["max_rel_error"]) > 0, f"{key}: nonzero error")
    for x in meth:
        check(float(x["ns_per_eval"]) > 0 and int(x["err_n"]) >= 1 and ";" in x["label"] and
              re.fullmatch(r"[a-z0-9_.\-]+", x["method"]) is not None and
              re.fullmatch(r"[A-Za-z0-9_]+=[A-Za-z0-9_.\-]+(,[A-Za-z0-9_]+=[A-Za-z0-9_.\-]+)*",
                           x["setting"]) is not None,
              f"{x['method']}/{x['setting']}: schema (time, err_n, label, name form)")
    for m in got:
        g = [x for x in meth if x["method"] == m]
        pts = [(float(x["ns_per_eval"]), float(x["rms_rel_error"])) for x in g]
        flags = [i for i, x in enumerate(g) if x["on_pareto_front"] == "1"]
        check(sa.is_pareto_front(pts, flags), f"{m}: CSV front is the brute-force front")
        if len(g) > 1:
            # Flip the flag of the slowest row: always a wrong front.
            i = max(range(len(g)), key=lambda k: pts[k][0])
            check(not sa.is_pareto_front(pts, sorted(set(flags) ^ {i})),
                  f"{m}: a flipped flag is rejected")
    with open(os.path.join(d, "speed_accuracy_methods.png"), "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "methods chart is a PNG")

if failures:
    print(f"{len(failures)} failure(s)")
    sys.exit(1)
print("speed_accuracy methods end-to-end test passed")
