# Sourced by the scale-out tests: a verify folder's claims.{json,csv,md} with their timing fields
# blanked, as tests/cli/shard_merge_test.cpp blanks them ("seconds" in claims.json, the last column
# of claims.csv, the time column of claims.md), so a merged folder can be byte-compared with one run.
without_timing() {
  case "$1" in
    *.json) sed -E 's/"seconds": [-0-9.e+]+/"seconds": T/' "$1" ;;
    *.csv) sed -E 's/,[0-9.]+$/,T/' "$1" ;;
    *) sed -E 's/\| [0-9.]+ s \|/| T |/' "$1" ;;
  esac
}
# same_claims_files A B: A's claims.{json,csv,md} are B's apart from timing?
same_claims_files() {
  for f in claims.json claims.csv claims.md; do
    [ -f "$1/$f" ] && [ -f "$2/$f" ] || return 1
    cmp -s <(without_timing "$1/$f") <(without_timing "$2/$f") || return 1
  done
}
