#!/usr/bin/env bash
# scripts/device_check.sh from scratch (its own build folder): with a CUDA device it writes the
# results folder; without one it must exit 3 with one error line and write nothing.
# The third argument is the script's build folder, a sibling of the build tree (build/<preset>-...):
# at the same depth below the source tree, so the paths ccache hashes relative to its base_dir
# (cmake/glintlabCcache.cmake) are the build tree's own, and the device objects the build tree has
# just compiled are read from the cache instead of compiled again (about 90 s of nvcc on 2 cores
# after a kernel header changes; a folder deeper in the tree missed every time).
# An optional fourth argument is the build tree's compiler launcher (the compiler cache), its words
# joined by |: the script's own configure then compiles through it (CMake reads
# CMAKE_<LANG>_COMPILER_LAUNCHER from the environment on a first configure), so the same nvcc and
# C++ commands run from scratch in an empty build folder.
set -uo pipefail
script=$1
work=$2
build=$3
if [[ -n ${4:-} ]]; then
  export CMAKE_CXX_COMPILER_LAUNCHER=${4//|/;} CMAKE_CUDA_COMPILER_LAUNCHER=${4//|/;}
fi
rm -rf "$work" "$build"
mkdir -p "$work"
GLINTLAB_GPU_BUILD="$build" "$script" "$work/out" --rows 64 --timing-rows 4096 --repetitions 2 \
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
