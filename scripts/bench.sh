#!/usr/bin/env bash
# Runs every glintlab benchmark (experiments/bench/) into one JSON, out/bench/bench.json, and a
# speed-up table (median items/s over scalar float exact, per kernel and ISA) out/bench/speedups.md.
# Extra arguments go to Google Benchmark, e.g. --benchmark_filter=ggx.d or
# --benchmark_repetitions=9. Timings on a shared machine are noisy: medians of repetitions.
set -euo pipefail
cd "$(dirname "$0")/.."
export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-}"
cmake --preset release >/dev/null
cmake --build --preset release --target glintlab_bench_kernels glintlab_bench_models \
  glintlab_bench_uarch >/dev/null
mkdir -p out/bench
tmp="out/bench/.bench.json.tmp"
./build/release/experiments/bench/glintlab_bench_kernels \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.05 \
  --benchmark_out="$tmp" --benchmark_out_format=json "$@"
# Every registered model through the registry-level batch API (model/<name>/<isa>/<op>), merged
# into the same JSON.
./build/release/experiments/bench/glintlab_bench_models \
  --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.05 \
  --benchmark_out="$tmp.models" --benchmark_out_format=json "$@"
# This CPU's division and multiplication throughput per width (uarch/<op>/<width>), the ceilings
# the kernel speed-ups are read against (bench_uarch.cpp); no filter arguments apply to it.
./build/release/experiments/bench/glintlab_bench_uarch \
  --benchmark_repetitions=9 --benchmark_report_aggregates_only=true \
  --benchmark_min_time=0.05 \
  --benchmark_out="$tmp.uarch" --benchmark_out_format=json >/dev/null
/usr/bin/python3 - "$tmp" "$tmp.models" "$tmp.uarch" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for extra in sys.argv[2:]:
    d["benchmarks"] += json.load(open(extra))["benchmarks"]
json.dump(d, open(sys.argv[1], "w"), indent=1)
PY
rm -f "$tmp.models" "$tmp.uarch"
mv "$tmp" out/bench/bench.json
/usr/bin/python3 - <<'PY'
import json, collections
d = json.load(open("out/bench/bench.json"))
med = {}
for b in d["benchmarks"]:
    if b.get("aggregate_name") != "median":
        continue
    med[b["run_name"]] = b
rows = collections.OrderedDict()
for name, b in med.items():
    if name.startswith(("chi_square", "model/", "l1/", "stream/", "uarch/")):
        continue
    kernel, isa, flavour = name.rsplit("/", 2)
    rows.setdefault(kernel, {})[(isa, flavour)] = b
isas = [i for i in ["sse4.2", "avx2", "avx512"] if any((i, "float_exact") in r for r in rows.values())]
ctx = d["context"]
lines = [f"CPU: {ctx.get('cpu_model')} ({ctx.get('cpu_mhz_proc_cpuinfo')} MHz per /proc/cpuinfo), "
         f"median of the repetitions, single thread, CPU time.", "",
         "| kernel | scalar Mitem/s | " + " | ".join(f"{i} ×" for i in isas) +
         " | " + " | ".join(f"{i} fast ×" for i in isas) + " | " +
         " | ".join(f"{i} double ×" for i in isas) + " | FLOP/item | best roofline |",
         "|" + "---|" * (3 + 3 * len(isas) + 1)]
for kernel, r in rows.items():
    base = r.get(("scalar", "float_exact"))
    based = r.get(("scalar", "double_exact"))
    if not base:
        continue
    s = base["items_per_second"]
    cells = [f"{r[(i,'float_exact')]['items_per_second']/s:.1f}" for i in isas]
    cells += [f"{r[(i,'float_fast')]['items_per_second']/s:.1f}" for i in isas]
    cells += [f"{r[(i,'double_exact')]['items_per_second']/based['items_per_second']:.1f}" for i in isas]
    best = max(v.get("roofline_fraction", 0) for v in r.values())
    lines.append(f"| {kernel} | {s/1e6:.1f} | " + " | ".join(cells) +
                 f" | {base['flops_per_item']:.0f} | {100*best:.1f} % |")
lines.append("")
# Working sets (bench_kernels.cpp): the 4096-row chunk above (L2-resident), L1-resident calls,
# and 4096-row calls streaming through 2^20 rows; speed-ups over scalar float exact of the same set.
best = ctx.get("best_isa", isas[-1] if isas else "scalar")
sets = [("", "chunk"), ("l1/", "L1"), ("stream/", "stream")]
lines += ["Working sets: Mitem/s of scalar float exact, and the speed-up of " + best +
          " float exact and fast over it, per working set.", "",
          "| kernel | " + " | ".join(f"scalar {s} Mitem/s" for _, s in sets) + " | " +
          " | ".join(f"{best} {s} ×" for _, s in sets) + " | " +
          " | ".join(f"{best} fast {s} ×" for _, s in sets) + " |",
          "|" + "---|" * (1 + 3 * len(sets))]
for kernel in rows:
    got = [[med.get(f"{p}{kernel}/{i}/{f}") for p, _ in sets]
           for i, f in [("scalar", "float_exact"), (best, "float_exact"), (best, "float_fast")]]
    if any(b is None for b in got[0] + got[1] + got[2]):
        continue
    base = [b["items_per_second"] for b in got[0]]
    lines.append(f"| {kernel} | " + " | ".join(f"{v/1e6:.1f}" for v in base) + " | " +
                 " | ".join(f"{b['items_per_second']/v:.1f}" for b, v in zip(got[1], base)) + " | " +
                 " | ".join(f"{b['items_per_second']/v:.1f}" for b, v in zip(got[2], base)) + " |")
lines.append("")
# The ceilings: ns per instruction and per lane of division and multiplication at each width.
ua = [(n, b) for n, b in med.items() if n.startswith("uarch/")]
if ua:
    lines += ["This CPU (bench_uarch.cpp, 8 independent chains, CPU time): "
              + "; ".join(f"{n[6:]}: {1e9/b['items_per_second']:.2f} ns/instruction, "
                          f"{1e9/b['lane_ops_per_second']:.3f} ns/lane" for n, b in ua), ""]
for name, b in med.items():
    if name.startswith("chi_square"):
        lines.append(f"- {name}: {b['real_time']:.0f} ms wall for 10^7 samples "
                     f"(sampling + binning + expected counts + statistic)")
models = collections.OrderedDict()
for name, b in med.items():
    if name.startswith("model/"):
        _, model, isa, op = name.split("/", 3)
        models.setdefault(model, {})[(isa, op)] = b
if models:
    misas = [i for i in ["scalar", "sse4.2", "avx2", "avx512"]
             if any((i, "eval_double") in r for r in models.values())]
    lines += ["", "Models (registry-level batch API, 4096 queries, default parameters): "
              "Mitem/s of the entry's double thunk loop, and speed-up of each ISA's batch over it.", "",
              "| model | op | entry Mitem/s | " + " | ".join(f"{i} double × | {i} float ×" for i in misas) + " |",
              "|" + "---|" * (3 + 2 * len(misas))]
    for model, r in models.items():
        for op in ["eval", "sample"]:
            e = r.get(("entry", op))
            if not e:
                continue
            s = e["items_per_second"]
            cells = []
            for i in misas:
                for p in ["double", "float"]:
                    b = r.get((i, f"{op}_{p}"))
                    cells.append(f"{b['items_per_second']/s:.1f}" if b else "—")
            lines.append(f"| {model} | {op} | {s/1e6:.2f} | " + " | ".join(cells) + " |")
open("out/bench/speedups.md", "w").write("\n".join(lines) + "\n")
print("\n".join(lines))
PY
echo "bench: wrote out/bench/bench.json and out/bench/speedups.md"
