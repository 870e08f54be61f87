#!/usr/bin/env bash
# The main job: install dependencies, build, run the claim suite (`glintlab verify`).
# Usage (as root on Debian 12): bash scripts/main.sh [--budget quick|full]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release
out="${GLINTLAB_OUT:-out}"
mkdir -p "$out"
./build/release/cli/glintlab verify --out "$out/verify" "$@"
echo "main: results in $out/verify (claims.md, claims.csv, claims.json)"
