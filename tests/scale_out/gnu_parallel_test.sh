#!/usr/bin/env bash
# docs/scale-out.md's workstation recipe with GNU parallel, run as written there (its verify line,
# read from the document, at the quick budget on six claims and 3 shards instead of full and 8):
# the merged claims.{json,csv,md} must be one unsharded run's bytes apart from the timing fields,
# and shard 1's own files must be told apart by the same comparison (the check is not blind).
# Usage: gnu_parallel_test.sh GLINTLAB SOURCE_DIR. Exit 0 pass, 1 fail, 77 skip (no parallel).
set -uo pipefail
GLINTLAB=$(readlink -f "$1")
SOURCE=$(readlink -f "$2")
. "$SOURCE/tests/scale_out/claims_without_timing.sh"
fail() { echo "FAIL: $*"; exit 1; }
command -v parallel > /dev/null ||
  { echo "SKIP: GNU parallel is not installed (Debian: apt-get install parallel; scripts/setup.sh)"; exit 77; }
# The six quick claims of tests/cli/shard_merge_test.cpp (three with p-values).
CLAIMS="kemppinen.furnace,kemppinen.roulette,kneiphof.subdivision,eto.backfacing-stable-pdf,kneiphof.cap-probability,podee.brightest-vector"
line=$(grep -E '^parallel -j 2 -q glintlab verify ' "$SOURCE/docs/scale-out.md")
[ -n "$line" ] || fail "docs/scale-out.md has no 'parallel -j 2 -q glintlab verify' line"
merge=$(grep -E '^glintlab merge shards/verify/\* --out out/verify$' "$SOURCE/docs/scale-out.md")
[ -n "$merge" ] || fail "docs/scale-out.md has no 'glintlab merge shards/verify/* --out out/verify' line"
# The document's line with this test's program, budget, claims and shard count.
line=${line/glintlab verify/\"\$GLINTLAB\" verify --claims \"\$CLAIMS\"}
line=${line/--budget full/--budget quick}
line=${line//\/8/\/3}
line=${line/\$(seq 8)/\$(seq 3)}
WORK=$(mktemp -d /tmp/glintlab-parallel.XXXXXX)
trap 'rm -rf "$WORK"' EXIT
cd "$WORK" || exit 1
echo "+ $line"
eval "timeout 240 $line" > parallel.log 2>&1 || { tail -n 5 parallel.log; fail "the shards failed"; }
timeout 60 "$GLINTLAB" merge shards/verify/* --out out/verify > merge.log 2>&1 ||
  { tail -n 5 merge.log; fail "the merge failed"; }
timeout 240 "$GLINTLAB" verify --claims "$CLAIMS" --budget quick --threads 1 --out one > one.log 2>&1
[ -f one/claims.json ] || { tail -n 5 one.log; fail "the single run wrote no claims.json"; }
same_claims_files out/verify one || fail "the merged claims files differ from the single run's"
same_claims_files shards/verify/1 one &&
  fail "negative control: shard 1's files pass as the single run's; the comparison is blind"
echo "PASS: 3 shards through GNU parallel merged to the single run's claims files"
