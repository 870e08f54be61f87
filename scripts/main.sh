#!/usr/bin/env bash
# The main job: install dependencies, build and install (scripts/install.sh), run the claim suite (`glintlab verify`), then the
# report of everything (`glintlab report`: figures, benchmarks, stability maps when built in, and
# the verdicts just computed) as out/report/index.html and out/report/report.md.
# Usage (as root on Debian 12): bash scripts/main.sh [--budget quick|full]
# Exit status: glintlab verify's (0 = every verdict as recorded, 1 = one differs, 3 = a check could
# not run: verdict error; the report is made in all three cases), or 2 on an error.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release
bash scripts/install.sh
out="${GLINTLAB_OUT:-out}"
mkdir -p "$out"
verify_rc=0
./build/release/cli/glintlab verify --out "$out/verify" "$@" || verify_rc=$?
if [[ "$verify_rc" -ne 0 && "$verify_rc" -ne 1 && "$verify_rc" -ne 3 ]]; then exit "$verify_rc"; fi
echo "main: results in $out/verify (claims.md, claims.csv, claims.json)"
budget=quick
prev=""
for a in "$@"; do
  if [[ "$prev" == "--budget" ]]; then budget="$a"; fi
  if [[ "$a" == --budget=* ]]; then budget="${a#--budget=}"; fi
  prev="$a"
done
./build/release/cli/glintlab report --out "$out/report" --budget "$budget" \
  --claims-from "$out/verify"
echo "main: Markdown twin of the report in $out/report/report.md"
echo "main: report in $out/report/index.html"
exit "$verify_rc"
