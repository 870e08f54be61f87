#!/usr/bin/env bash
# Every test: install dependencies, build (release), run the whole ctest suite.
# Usage (as root on Debian 12): bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release
ctest --preset release -j "${GLINTLAB_JOBS:-$(nproc)}"
