#!/usr/bin/env bash
# Installs glintlab's build and run dependencies from Debian 12 packages. Idempotent: when every
# package is already installed it touches nothing (and needs no network).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  libeigen3-dev libgtest-dev libgmock-dev libopenexr-dev libboost-math-dev libfmt-dev
  libcli11-dev nlohmann-json3-dev libxsimd-dev libbenchmark-dev libtbb-dev
  python3 python3-matplotlib python3-jinja2 python3-dev python3-pybind11 python3-numpy python3-pytest
  libpng-dev openexr
  chromium
  # A single-node Slurm cluster for scripts/slurm/'s test (tests/slurm/).
  slurm-wlm munge
  # GNU parallel, for docs/scale-out.md's shards-as-processes recipe and its test (tests/scale_out/).
  parallel
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -ne 0 ]; then
  echo "setup: missing packages (${missing[*]}); run as root to install them" >&2
  exit 1
fi

echo "setup: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update
apt-get install -y --no-install-recommends "${missing[@]}"
