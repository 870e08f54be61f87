#!/usr/bin/env bash
# Every test: install dependencies, build (release), install it (scripts/install.sh: glintlab and
# the Python package into /usr/local), run the whole ctest suite (the release preset, then the
# quick conformance suite against its recorded rows: the `suite` preset), then the core,
# verify and CLI tests again under AddressSanitizer + UBSan (scripts/test_asan.sh). Each step
# prints its wall time (scripts/steps.sh).
# Usage (as root on Debian 12): bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/steps.sh
step setup bash scripts/setup.sh
step build bash scripts/build.sh release
step install bash scripts/install.sh
export GLINTLAB_INSTALLED_PREFIX="${GLINTLAB_PREFIX:-/usr/local}"
step ctest ctest --preset release -j "${GLINTLAB_JOBS:-$(nproc)}"
# The whole conformance suite at quick, every row compared with its recorded row (label `suite`).
step suite ctest --preset suite
bash scripts/test_asan.sh
