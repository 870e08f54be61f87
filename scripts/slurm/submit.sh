#!/usr/bin/env bash
# Submits a sharded glintlab run to Slurm: a job array of SHARDS tasks (shard_array.sbatch, one
# shard of `glintlab SUBCOMMAND --shard K/SHARDS` per SLURM_ARRAY_TASK_ID) and the merge job
# (merge.sbatch) held with --dependency=afterok:<array job id>. SUBCOMMAND is verify, figure,
# compare, sweep or adequacy. Prints the two job ids, one line each:
#   array <id>
#   merge <id>
# The merged files are in OUT/SUBCOMMAND (verify: claims.{json,csv,md}; figure: a folder per
# figure; compare: the page and its tables; sweep: stability.json and the models' maps;
# adequacy: adequacy.{csv,json} and the maps); each
# job's output goes to OUT/logs. Examples (docs/scale-out.md "A Slurm cluster"):
#   GLINTLAB=$PWD/build/release/cli/glintlab BUDGET=full SHARDS=32 OUT=$PWD/run scripts/slurm/submit.sh
#   SUBCOMMAND=figure FIGURES='kemppinen2025-*' BUDGET=full SHARDS=8 OUT=$PWD/figs scripts/slurm/submit.sh

# The options a user sets: environment variables override these defaults; they reach the jobs
# through sbatch's --export.
GLINTLAB=${GLINTLAB:-glintlab}   # the glintlab executable, on a file system every node sees
SUBCOMMAND=${SUBCOMMAND:-verify} # verify, figure, compare, sweep or adequacy
BUDGET=${BUDGET:-quick}          # --budget: quick or full
CLAIMS=${CLAIMS:-}               # verify --claims GLOBS; empty: every claim
FIGURES=${FIGURES:-*}            # figure IDS (ids and globs, commas allowed); '*': every figure
MODELS=${MODELS:-}               # compare, sweep and adequacy --models GLOBS; empty: the subcommand's default
EXTRA_ARGS=${EXTRA_ARGS:-}       # further options of each task, split at spaces
SHARDS=${SHARDS:-4}              # how many shards (array tasks)
OUT=${OUT:-$PWD/glintlab-run}    # the run's folder, on a file system every node sees
THREADS=${THREADS:-1}            # --threads, and --cpus-per-task, of each task
PARTITION=${PARTITION:-}         # sbatch --partition; empty: the cluster's default
TIME_LIMIT=${TIME_LIMIT:-}       # sbatch --time of each job; empty: the partition's default

set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
case "$SUBCOMMAND" in
  verify | figure | compare | sweep | adequacy) ;;
  *) echo "submit.sh: error: SUBCOMMAND must be verify, figure, compare, sweep or adequacy, not '$SUBCOMMAND'" >&2; exit 2 ;;
esac
case "$SHARDS" in
  '' | *[!0-9]* | 0*) echo "submit.sh: error: SHARDS must be a whole number >= 1, not '$SHARDS'" >&2; exit 2 ;;
esac
case "$THREADS" in
  '' | *[!0-9]* | 0*) echo "submit.sh: error: THREADS must be a whole number >= 1, not '$THREADS'" >&2; exit 2 ;;
esac
OUT=$(mkdir -p "$OUT" && cd "$OUT" && pwd)   # absolute: the jobs may start in another folder
mkdir -p "$OUT/logs"

common=(--parsable --chdir "$OUT")
if [ -n "$PARTITION" ]; then common+=(--partition "$PARTITION"); fi
if [ -n "$TIME_LIMIT" ]; then common+=(--time "$TIME_LIMIT"); fi
# The options reach the jobs in the environment (--export=ALL), not as --export=NAME=VALUE
# pairs, which would split a CLAIMS list at its commas.
export GLINTLAB SUBCOMMAND BUDGET CLAIMS FIGURES MODELS EXTRA_ARGS SHARDS OUT THREADS

# --parsable prints "id" or "id;cluster".
array_id=$(sbatch "${common[@]}" --export=ALL --array="1-$SHARDS" --cpus-per-task="$THREADS" \
             --job-name="glintlab-$SUBCOMMAND" --output="$OUT/logs/$SUBCOMMAND-%A_%a.out" \
             "$here/shard_array.sbatch")
array_id=${array_id%%;*}
merge_id=$(sbatch "${common[@]}" --export=ALL --dependency="afterok:$array_id" \
             --kill-on-invalid-dep=yes --output="$OUT/logs/merge-%j.out" "$here/merge.sbatch")
merge_id=${merge_id%%;*}
echo "array $array_id"
echo "merge $merge_id"
