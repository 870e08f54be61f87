#!/usr/bin/env bash
# The device check, for a GPU machine that has CMake, a C++20 compiler and the CUDA toolkit and
# nothing else (no Debian packages, no network): builds gpu/ on its own (glintlab_gpu_check) and
# runs it on the first CUDA device, writing OUT (docs/gpu.md says what is in it and what to do
# with it). Takes a few minutes: a build of under a minute, then every device-capable model's
# eval, pdf and sample in float and double.
#   scripts/device_check.sh OUT [glintlab_gpu_check options: --rows N --timing-rows M --repetitions R]
# Options from the environment: CMAKE_CUDA_COMPILER (default: nvcc on PATH, else
# /usr/local/cuda/bin/nvcc), GLINTLAB_CUDA_ARCHITECTURES (default 90: H100, H200),
# GLINTLAB_GPU_BUILD (the build folder; default build/device-check).
# Exit 0: OUT written; 3: no CUDA device (nothing written); 2: bad arguments; 1: a failure.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
if [[ $# -lt 1 || $1 == -* ]]; then
  echo "device_check.sh: error: OUT is required (the folder to write): device_check.sh OUT [options]" >&2
  exit 2
fi
out=$1
shift
build=${GLINTLAB_GPU_BUILD:-$root/build/device-check}
nvcc=${CMAKE_CUDA_COMPILER:-$(command -v nvcc || echo /usr/local/cuda/bin/nvcc)}
if [[ ! -x $nvcc ]]; then
  echo "device_check.sh: error: no CUDA compiler at '$nvcc' (set CMAKE_CUDA_COMPILER)" >&2
  exit 1
fi
generator=()
if command -v ninja > /dev/null; then generator=(-G Ninja); fi
start=$(date +%s)
cmake -S "$root/gpu" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CUDA_COMPILER="$nvcc" \
  -DGLINTLAB_CUDA_ARCHITECTURES="${GLINTLAB_CUDA_ARCHITECTURES:-90}" > "$build.configure.log" 2>&1 ||
  { cat "$build.configure.log" >&2; exit 1; }
cmake --build "$build" --target glintlab_gpu_check -j "$(nproc)" > "$build.build.log" 2>&1 ||
  { cat "$build.build.log" >&2; exit 1; }
echo "device_check.sh: built glintlab_gpu_check in $(( $(date +%s) - start )) s"
"$build/glintlab_gpu_check" --out "$out" "$@"
