#!/usr/bin/env bash
# scripts/device_check.sh from scratch (its own build folder): with a CUDA device it writes the
# results folder; without one it must exit 3 with one error line and write nothing.
# An optional third argument is the build tree's compiler launcher (the compiler cache,
# cmake/glintlabCcache.cmake), its words joined by |: the script's own configure then compiles
# through it (CMake reads CMAKE_<LANG>_COMPILER_LAUNCHER from the environment on a first
# configure), so the same nvcc and C++ commands run from scratch in an empty build folder, and a
# run after an earlier one with the same sources reads their objects from the cache instead of
# compiling them again (about 100 s of nvcc on 2 cores).
set -uo pipefail
script=$1
work=$2
if [[ -n ${3:-} ]]; then
  export CMAKE_CXX_COMPILER_LAUNCHER=${3//|/;} CMAKE_CUDA_COMPILER_LAUNCHER=${3//|/;}
fi
rm -rf "$work"
mkdir -p "$work"
GLINTLAB_GPU_BUILD="$work/build" "$script" "$work/out" --rows 64 --timing-rows 4096 --repetitions 2 \
  > "$work/stdout" 2> "$work/stderr"
rc=$?
cat "$work/stdout"
cat "$work/stderr"
case $rc in
  0)
    for f in results.json queries.csv smooth_ggx.float.eval.csv smooth_beckmann.double.sample.csv; do
      [[ -s $work/out/$f ]] || { echo "FAIL: exit 0 but $f missing"; exit 1; }
    done
    echo "a CUDA device ran the check" ;;
  3)
    [[ $(wc -l < "$work/stderr") -eq 1 ]] || { echo "FAIL: not one error line"; exit 1; }
    grep -q '^glintlab_gpu_check: error: no CUDA device (.*); nothing written$' "$work/stderr" ||
      { echo "FAIL: the message does not say there is no CUDA device"; exit 1; }
    [[ ! -e $work/out ]] || { echo "FAIL: $work/out written without a device"; exit 1; }
    [[ -z $(find "$work" -maxdepth 1 -name '.out.partial*') ]] || { echo "FAIL: staging folder left"; exit 1; }
    echo "no CUDA device here: the script said so and wrote nothing" ;;
  *)
    echo "FAIL: exit $rc"; exit 1 ;;
esac
"$script" > /dev/null 2>&1
[[ $? -eq 2 ]] || { echo "FAIL: no OUT argument did not exit 2"; exit 1; }
exit 0
