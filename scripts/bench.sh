#!/usr/bin/env bash
# Runs the kernel, model and uarch benchmarks (experiments/bench/) into one JSON,
# out/bench/bench.json, annotated by scripts/simd_tables.py (roofline fractions against the FLOP
# peak measured in the same run, the same-FLOPs check, the targets), and its tables
# out/bench/speedups.md (docs/simd.md's "Speed-ups" block). Extra arguments go to Google Benchmark,
# e.g. --benchmark_filter=ggx.d or --benchmark_repetitions=9. BENCH_REPETITIONS (default 3) and
# BENCH_MIN_TIME (seconds per repetition, default 0.03) keep a full run to minutes; timings on a
# shared machine are noisy: medians of the repetitions.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release >/dev/null
cmake --build --preset release --target glintlab_bench_kernels glintlab_bench_models \
  glintlab_bench_uarch >/dev/null
mkdir -p out/bench
reps="${BENCH_REPETITIONS:-3}"
min_time="${BENCH_MIN_TIME:-0.03}"
tmp="out/bench/.bench.json.tmp"
./build/release/experiments/bench/glintlab_bench_kernels \
  --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$tmp" --benchmark_out_format=json "$@"
# Every registered model through the registry-level batch API (model/<name>/<isa>/<op>), merged
# into the same JSON.
./build/release/experiments/bench/glintlab_bench_models \
  --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$tmp.models" --benchmark_out_format=json "$@"
# This CPU's division and multiplication throughput per width (uarch/<op>/<width>) and FLOP peak
# per ISA and precision (uarch/peak/<isa>/<precision>): the ceilings the kernel rows are read
# against (bench_uarch.cpp); no filter arguments apply to it.
./build/release/experiments/bench/glintlab_bench_uarch \
  --benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true \
  --benchmark_min_time="$min_time" \
  --benchmark_out="$tmp.uarch" --benchmark_out_format=json >/dev/null
/usr/bin/python3 - "$tmp" "$tmp.models" "$tmp.uarch" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
for extra in sys.argv[2:]:
    d["benchmarks"] += json.load(open(extra))["benchmarks"]
json.dump(d, open(sys.argv[1], "w"), indent=1)
PY
rm -f "$tmp.models" "$tmp.uarch"
# Instructions and loads per item of the targets' rows (experiments/bench/uarch_counts.py: this
# VM has no PMU counters, so valgrind's callgrind counts them; it emulates no AVX-512).
counts=()
if command -v valgrind >/dev/null; then
  /usr/bin/python3 experiments/bench/uarch_counts.py --out out/bench/uarch_counts.json
  counts=(--uarch-counts out/bench/uarch_counts.json)
else
  echo "bench: no valgrind: the targets carry no instruction counts" >&2
fi
# Roofline fractions from the peaks of this run, the same-FLOPs check and the targets
# (scripts/simd_tables.py), then the tables docs/simd.md carries.
/usr/bin/python3 scripts/simd_tables.py annotate "$tmp" "${counts[@]}"
mv "$tmp" out/bench/bench.json
/usr/bin/python3 scripts/simd_tables.py tables out/bench/bench.json > out/bench/speedups.md
cat out/bench/speedups.md
echo "bench: wrote out/bench/bench.json and out/bench/speedups.md" \
  "(docs/simd.md: scripts/simd_tables.py tables out/bench/bench.json --update docs/simd.md)"
