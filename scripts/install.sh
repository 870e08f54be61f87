#!/usr/bin/env bash
# Installs the release build (scripts/build.sh release) into PREFIX: the glintlab executable, the
# headers and CMake package for plug-ins (find_package(glintlab)), and the Python package into
# PREFIX's site-packages. The default PREFIX, /usr/local, is where Debian's /usr/bin/python3
# imports `glintlab` from without PYTHONPATH (/usr/local/lib/python3.11/dist-packages).
# Usage (as root on Debian 12, after the build): bash scripts/install.sh
# GLINTLAB_PREFIX=DIR installs into DIR instead.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="${GLINTLAB_PREFIX:-/usr/local}"
cmake --install build/release --prefix "$prefix" >/dev/null
site="$(cmake -L -N build/release 2>/dev/null | sed -n 's/^GLINTLAB_PYTHON_INSTALL_DIR:[A-Z]*=//p')"
echo "install: glintlab in $prefix/bin${site:+, the Python package in $prefix/$site/glintlab}"
