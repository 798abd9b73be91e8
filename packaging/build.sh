#!/usr/bin/env bash
# Installs missing Debian packages, then configures and builds Nimbus into build/ (or $NIMBUS_BUILD_DIR).
# Extra arguments go to the CMake configure step, e.g. -DNIMBUS_SANITIZE=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/setup.sh
build_dir=${NIMBUS_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE="${NIMBUS_BUILD_TYPE:-RelWithDebInfo}" "$@" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
