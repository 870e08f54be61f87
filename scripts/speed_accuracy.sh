#!/usr/bin/env bash
# Speed vs accuracy of every batched kernel × ISA × math flavour (issue 9 item 5): runs
# glintlab_accuracy into out/bench/accuracy.csv, joins it with out/bench/bench.json (run
# scripts/bench.sh first, or pass --bench to run it here) and writes out/bench/speed_accuracy.csv
# and out/bench/speed_accuracy.png. Other arguments go to reports/speed_accuracy.py
# (e.g. --metric rms). GLINTLAB_ACCURACY_N sets the rows per kernel (default 200000).
set -euo pipefail
cd "$(dirname "$0")/.."
run_bench=0
args=()
for a in "$@"; do
  if [[ "$a" == "--bench" ]]; then run_bench=1; else args+=("$a"); fi
done
export CMAKE_CXX_COMPILER_LAUNCHER="${CMAKE_CXX_COMPILER_LAUNCHER:-}"
cmake --preset release >/dev/null
cmake --build --preset release --target glintlab_accuracy >/dev/null
if [[ "$run_bench" == 1 ]]; then
  bash scripts/bench.sh
elif [[ ! -f out/bench/bench.json ]]; then
  echo "glintlab: error: out/bench/bench.json missing (run scripts/bench.sh, or pass --bench)" >&2
  exit 2
fi
mkdir -p out/bench
./build/release/experiments/bench/glintlab_accuracy --n "${GLINTLAB_ACCURACY_N:-200000}" \
  --out out/bench/accuracy.csv
/usr/bin/python3 reports/speed_accuracy.py --accuracy out/bench/accuracy.csv \
  --bench out/bench/bench.json --out-dir out/bench "${args[@]+"${args[@]}"}"
