#!/usr/bin/env bash
# Behaviour check for refactorings: builds BASE_REF (in a temporary git worktree) and the working
# tree, runs the same fixed set of glintlab commands with both and compares every output byte for
# byte, apart from timing fields (wall-clock seconds, ns per call, dates) that no two runs share.
# Prints the outputs that differ; exit 0 when none does, 1 when one does, 2 on bad usage.
#
# Usage: scripts/check_outputs.sh BASE_REF
#        scripts/check_outputs.sh --run GLINTLAB_BIN DIR   (only runs the command set into DIR)
# Environment:
#   CHECK_OUT          where the outputs go: CHECK_OUT/base, CHECK_OUT/head (default /tmp/check_outputs)
#   GLINTLAB_BASE_BIN  an already built glintlab of BASE_REF (skips that build)
#   GLINTLAB_HEAD_BIN  an already built glintlab of the working tree (skips that build)
#   CHECK_BASE_READY   1: CHECK_OUT/base already holds BASE_REF's outputs (from an earlier run or
#                      from --run); neither build nor rerun the base
#   GLINTLAB_JOBS      build jobs (default 1)
#   CHECK_THREADS      --threads of the runs (default 2; the outputs do not depend on it)
#   CHECK_SKIP         space-separated parts to leave out: eval sample sweep verify figures
set -euo pipefail

if [[ $# -ne 1 && ! ($# -eq 3 && $1 == --run) ]]; then
  echo "usage: $0 BASE_REF | $0 --run GLINTLAB_BIN DIR" >&2
  exit 2
fi
root=$(cd "$(dirname "$0")/.." && pwd)
out=${CHECK_OUT:-/tmp/check_outputs}
jobs=${GLINTLAB_JOBS:-1}
threads=${CHECK_THREADS:-2}
skip=" ${CHECK_SKIP:-} "

build_glintlab() {  # source dir -> prints the binary's path
  local src=$1
  (cd "$src" && cmake --preset release >/dev/null &&
    cmake --build --preset release -j "$jobs" --target glintlab >&2)
  echo "$src/build/release/cli/glintlab"
}

# Query files for `eval --model --in`: every query column (footprint, light), and for the models
# that need them the four pixel-corner reflection vectors (unit; around wo so the disk is lit).
write_queries() {
  local dir=$1
  cat >"$dir/queries.csv" <<'EOF'
wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy,light_cos_half_angle,light_intensity
0.6,0,0.8,-0.48,0.36,0.8,0.3,0.7,0.001,0.0002,-0.0003,0.002,1,1
0,0,1,0,0,1,0.25,0.5,0.0005,0,0,0.0005,0.9999,2
0,0.6,0.8,0,-0.6,0.8,0.9,0.1,0.01,0.001,0.002,0.02,0.99,0.5
0.28,0,0.96,-0.96,0,0.28,12.5,-3.25,0.0001,0,0,0.0004,0.999,1
-0.36,0.48,0.8,0.36,-0.48,0.8,0.5,0.5,0.004,-0.001,0.001,0.003,1,1
0.6,0,0.8,0.6,0,-0.8,0.1,0.2,0.001,0,0,0.001,1,1
EOF
  cat >"$dir/queries_corners.csv" <<'EOF'
wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy,light_cos_half_angle,light_intensity,r0_x,r0_y,r0_z,r1_x,r1_y,r1_z,r2_x,r2_y,r2_z,r3_x,r3_y,r3_z
0,0,1,0,0,1,0.25,0.5,0.0005,0,0,0.0005,0.99,1,-0.28,0,0.96,0,-0.28,0.96,0,0.28,0.96,0.28,0,0.96
0.6,0,0.8,-0.6,0,0.8,0.3,0.7,0.001,0,0,0.001,0.999,2,-0.6,0,0.8,-0.48,0.36,0.8,-0.48,-0.36,0.8,-0.36,0.48,0.8
0,0.6,0.8,0,-0.6,0.8,0.9,0.1,0.01,0.001,0.002,0.02,0.9,0.5,0,-0.6,0.8,0,-0.28,0.96,0.28,0,0.96,0,0,1
0.28,0,0.96,-0.28,0,0.96,0.5,0.5,0.004,0,0,0.003,0.9999,1,0,0,1,0.28,0,0.96,0,0.28,0.96,0,-0.28,0.96
EOF
}

run_commands() {  # binary, output dir
  local bin=$1 dir=$2
  rm -rf "$dir"
  mkdir -p "$dir"
  write_queries "$dir"
  local models
  models=$("$bin" models | sed -n 's/^\([a-z_0-9]*\): .*/\1/p')
  local grid='theta_i=0:85:4,phi_i=0:90:2,theta_o=0:89:5,phi_o=0:180:4'
  local isas="scalar default" m p isa isa_arg needs_corners needs q query
  for m in $models; do
    needs_corners=0
    needs=$("$bin" models | grep -A3 "^$m: " | grep -m1 "needs:")
    [[ $needs == *"pixel corner"* ]] && needs_corners=1
    # The columns besides the directions the model needs, for --grid and sample (--query).
    q=""
    [[ $needs == *footprint* ]] && q="u=0.5,v=0.5,dudx=0.004,dvdx=-0.001,dudy=0.001,dvdy=0.003"
    [[ $needs == *light* ]] && q="${q:+$q,}light_cos_half_angle=0.99,light_intensity=1"
    ((needs_corners)) &&
      q="$q,r0_x=-0.28,r0_y=0,r0_z=0.96,r1_x=0,r1_y=-0.28,r1_z=0.96,r2_x=0,r2_y=0.28,r2_z=0.96"
    ((needs_corners)) && q="$q,r3_x=0.28,r3_y=0,r3_z=0.96"
    query=()
    [[ -n $q ]] && query=(--query "$q")
    for p in double float; do
      for isa in $isas; do
        isa_arg=()
        [[ $isa != default ]] && isa_arg=(--isa "$isa")
        local tag="$m.$p.$isa" args=(--model "$m" --precision "$p" "${isa_arg[@]}"
          --threads "$threads")
        if [[ $skip != *" eval "* ]]; then
          if ((needs_corners)); then
            "$bin" eval "${args[@]}" --in "$dir/queries_corners.csv" --out "$dir/eval_in.$tag.csv"
          else
            "$bin" eval "${args[@]}" --grid "$grid" "${query[@]}" --out "$dir/eval_grid.$tag.csv"
            "$bin" eval "${args[@]}" --in "$dir/queries.csv" --out "$dir/eval_in.$tag.csv"
          fi
        fi
        if [[ $skip != *" sample "* ]]; then
          "$bin" sample "${args[@]}" --wi 0.6,0,0.8 "${query[@]}" --n 2000 --seed 7 \
            --out "$dir/sample.$tag.csv"
        fi
      done
    done
  done
  if [[ $skip != *" sweep "* ]]; then
    "$bin" sweep --budget quick --threads "$threads" --out "$dir/sweep" >"$dir/sweep.log" 2>&1
  fi
  if [[ $skip != *" verify "* ]]; then
    # Exit 1 (a verdict differs from the recorded one) is an output to compare, not a failure.
    "$bin" verify --budget quick --threads "$threads" --out "$dir/verify" >"$dir/verify.log" 2>&1 ||
      [[ $? -eq 1 ]]
  fi
  if [[ $skip != *" figures "* ]]; then
    local id
    for id in $("$bin" figure --list | awk '{print $1}'); do
      "$bin" figure "$id" --budget quick --threads "$threads" --out "$dir/figures" >"$dir/figure.$id.log" 2>&1
    done
  fi
  rm -f "$dir"/*.log  # progress and timings
}

# Timing fields, blanked before comparing: JSON keys and CSV columns that hold seconds, ns per
# call, throughputs or dates.
normalise() {  # file -> stdout
  local f=$1
  case $f in
    *.json)
      sed -E 's/"([A-Za-z_]*(seconds|_s|_ns|ns_per[A-Za-z_]*|time[A-Za-z_]*|date|timestamp|elapsed|wall[A-Za-z_]*|per_second|throughput[A-Za-z_]*))": *[^,}]*/"\1": T/g' "$f"
      ;;
    */verify/claims.csv)  # drop the last column, seconds
      python3 -c 'import csv,sys; w=csv.writer(sys.stdout); [w.writerow(r[:-1]) for r in csv.reader(open(sys.argv[1]))]' "$f"
      ;;
    */verify/claims.md) sed -E 's/[0-9]+(\.[0-9]+)? ?s\b/T/g' "$f" ;;
    # Figures whose numbers are measured times (ns per evaluation, time per pixel): not comparable.
    */kemppinen2025-table3/* | */kemppinen2025-speed-accuracy/*) echo timing ;;
    *) cat "$f" ;;
  esac
}

if [[ $1 == --run ]]; then
  run_commands "$2" "$3"
  exit 0
fi
base_ref=$1
base_bin=${GLINTLAB_BASE_BIN:-}
base_ready=${CHECK_BASE_READY:-0}
if [[ $base_ready != 1 && -z $base_bin ]]; then
  base_src=$(mktemp -d /tmp/check_outputs_base.XXXXXX)
  trap 'git -C "$root" worktree remove --force "$base_src" >/dev/null 2>&1 || true' EXIT
  git -C "$root" worktree add --detach "$base_src" "$base_ref" >&2
  base_bin=$(build_glintlab "$base_src")
fi
head_bin=${GLINTLAB_HEAD_BIN:-$(build_glintlab "$root")}

if [[ $base_ready != 1 ]]; then
  echo "== running with base ($base_ref): $base_bin" >&2
  run_commands "$base_bin" "$out/base"
fi
echo "== running with head: $head_bin" >&2
run_commands "$head_bin" "$out/head"

status=0
while IFS= read -r rel; do
  b="$out/base/$rel" h="$out/head/$rel"
  if [[ ! -f $h ]]; then
    echo "only in base: $rel"
    status=1
  elif ! cmp -s <(normalise "$b") <(normalise "$h"); then
    echo "differs: $rel"
    status=1
  fi
done < <(cd "$out/base" && find . -type f | sed 's|^\./||' | sort)
while IFS= read -r rel; do
  [[ -f $out/base/$rel ]] || { echo "only in head: $rel"; status=1; }
done < <(cd "$out/head" && find . -type f | sed 's|^\./||' | sort)
if ((status == 0)); then echo "outputs identical (timing fields aside)"; fi
exit $status
