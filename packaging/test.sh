#!/usr/bin/env bash
# Set-up, build and run the whole test suite (README command 2; CI runs this).
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/build.sh "$@"
build_dir=${NIMBUS_BUILD_DIR:-build}
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 900
