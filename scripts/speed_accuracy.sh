#!/usr/bin/env bash
# Speed vs accuracy of every batched kernel × ISA × math flavour and of every
# method and setting: runs glintlab_accuracy into out/bench/accuracy.csv, joins it with
# out/bench/bench.json (run scripts/bench.sh first, or pass --bench to run it here), runs the
# method benchmarks of METHOD_BENCHES (experiments/bench/METHOD_BENCHMARKS.md) into
# out/bench/methods/<binary>.json, and writes out/bench/speed_accuracy.csv, speed_accuracy.png
# (kernels) and speed_accuracy_methods.png (every method family, fronts marked).
# Options: --bench (run scripts/bench.sh first), --quick (GLINTLAB_BENCH_QUICK=1: small query sets
# and references, short timings; for ctest, numbers not to report), --build-dir DIR (use built
# binaries there, do not build), --out-dir DIR (default out/bench), --bench-json FILE (kernel
# timings, default OUT/bench.json); other arguments go to reports/speed_accuracy.py (e.g.
# --metric rms). GLINTLAB_ACCURACY_N sets the rows per kernel (default 200000, quick 2000).
set -euo pipefail
cd "$(dirname "$0")/.."

# One line per binary with method/ rows (a binary without any gives an empty list).
METHOD_BENCHES=(
  glintlab_bench_glints
  glintlab_bench_chermain
  glintlab_bench_podee
  glintlab_bench_kemppinen
)

run_bench=0 quick=0 build_dir="" out_dir="out/bench" bench_json=""
args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --bench) run_bench=1 ;;
    --quick) quick=1 ;;
    --build-dir | --out-dir | --bench-json)
      if [[ $# -lt 2 ]]; then
        echo "glintlab: error: $1 needs a value" >&2
        exit 2
      fi
      case "$1" in
        --build-dir) build_dir="$2" ;;
        --out-dir) out_dir="$2" ;;
        --bench-json) bench_json="$2" ;;
      esac
      shift ;;
    *) args+=("$1") ;;
  esac
  shift
done
bench_json="${bench_json:-$out_dir/bench.json}"

if [[ -z "$build_dir" ]]; then
  export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-}"
  cmake --preset release >/dev/null
  cmake --build --preset release --target glintlab_accuracy "${METHOD_BENCHES[@]}" >/dev/null
  build_dir=build/release
fi
bin="$build_dir/experiments/bench"
for b in glintlab_accuracy "${METHOD_BENCHES[@]}"; do
  if [[ ! -x "$bin/$b" ]]; then
    echo "glintlab: error: $bin/$b missing (build it, or check --build-dir)" >&2
    exit 2
  fi
done
if [[ "$run_bench" == 1 ]]; then
  bash scripts/bench.sh
elif [[ ! -f "$bench_json" ]]; then
  echo "glintlab: error: $bench_json missing (run scripts/bench.sh, or pass --bench)" >&2
  exit 2
fi

mkdir -p "$out_dir/methods"
if [[ "$quick" == 1 ]]; then
  export GLINTLAB_BENCH_QUICK=1
  timing=(--benchmark_min_time=0.002)
  n_default=2000
else
  unset GLINTLAB_BENCH_QUICK
  timing=(--benchmark_min_time=0.2 --benchmark_repetitions=3
          --benchmark_report_aggregates_only=true)
  n_default=200000
fi
"$bin/glintlab_accuracy" --n "${GLINTLAB_ACCURACY_N:-$n_default}" --out "$out_dir/accuracy.csv"

method_json=()
for b in "${METHOD_BENCHES[@]}"; do
  out="$out_dir/methods/$b.json"
  tmp="$out_dir/methods/.$b.json.tmp"
  echo "speed_accuracy: $b" >&2
  "$bin/$b" --benchmark_filter='^method/' "${timing[@]}" --benchmark_out="$tmp" \
    --benchmark_out_format=json >/dev/null
  # Google Benchmark 1.7 leaves an empty file when no row matches: an empty list.
  if [[ ! -s "$tmp" ]]; then echo '{"context": {}, "benchmarks": []}' >"$tmp"; fi
  mv "$tmp" "$out"
  method_json+=("$out")
done

/usr/bin/python3 reports/speed_accuracy.py --accuracy "$out_dir/accuracy.csv" \
  --bench "$bench_json" --out-dir "$out_dir" --methods "${method_json[@]}" \
  "${args[@]+"${args[@]}"}"
