#!/usr/bin/env bash
# What CI does, here and now: clones HEAD (committed work only) into a temporary folder, runs
# `CI=true bash .ci/run` there, prints the wall time of each step and the compiler cache's hits
# and misses for the run, and removes the clone. Run it before committing (docs/building.md).
# Usage: bash scripts/check.sh            (exit status: .ci/run's)
# Environment: CHECK_KEEP=1 keeps the clone and prints its path; CHECK_LOG=FILE keeps the log;
# CHECK_TOUCH=PATH appends an unused C++ declaration to the source file PATH (relative to the
# repository) in the clone before the run: what editing that one file costs (docs/building.md).
set -euo pipefail

# All in one function, which bash reads whole before running it: editing this file while a check
# runs cannot change the running check.
main() {
  root=$(cd "$(dirname "$0")/.." && pwd)
  work=$(mktemp -d "${TMPDIR:-/tmp}/glintlab-check.XXXXXX")
  log=${CHECK_LOG:-$work/ci.log}
  if [[ ${CHECK_KEEP:-0} != 1 ]]; then
    trap 'rm -rf "$work"' EXIT
  fi

  ccache_count() {  # hits or misses so far, from ccache's machine-readable statistics
    command -v ccache >/dev/null || { echo 0; return; }
    ccache --print-stats | awk -v want="$1" '
      want == "hits" && ($1 == "direct_cache_hit" || $1 == "preprocessed_cache_hit") { n += $2 }
      want == "misses" && $1 == "cache_miss" { n += $2 }
      END { print n + 0 }'
  }

  start=$SECONDS
  hits0=$(ccache_count hits)
  misses0=$(ccache_count misses)
  git clone -q --no-hardlinks "$root" "$work/glintlab"
  echo "check: cloned $(git -C "$work/glintlab" rev-parse --short HEAD) into $work/glintlab"
  if [[ -n ${CHECK_TOUCH:-} ]]; then
    [[ -f $work/glintlab/$CHECK_TOUCH ]] || { echo "check: CHECK_TOUCH: no file $CHECK_TOUCH" >&2; exit 2; }
    # A declaration, not a comment: the preprocessor drops comments, so the cache would still hit.
    echo "inline constexpr int glintlab_check_touch_${RANDOM}${RANDOM} = 0;  // scripts/check.sh" \
      >>"$work/glintlab/$CHECK_TOUCH"
    echo "check: appended an unused declaration to $CHECK_TOUCH"
  fi
  set +e
  (cd "$work/glintlab" && CI=true bash .ci/run) >"$log" 2>&1
  status=$?
  set -e

  echo "check: .ci/run exited $status (log: $log)"
  grep -E '^glintlab: step ' "$log" | sed 's/^glintlab: /check: /' || true
  grep -E '(tests passed|tests failed out of)' "$log" | sed 's/^/check: /' || true
  echo "check: compiler cache: $(($(ccache_count hits) - hits0)) hits," \
    "$(($(ccache_count misses) - misses0)) misses"
  echo "check: total $((SECONDS - start)) s"
  if [[ $status -ne 0 ]]; then
    echo "check: FAILED; the last lines of the log:"
    tail -n 40 "$log"
  fi
  [[ ${CHECK_KEEP:-0} == 1 ]] && echo "check: kept $work"
  exit "$status"
}

main "$@"
