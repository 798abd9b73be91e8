#!/usr/bin/env bash
# Set-up, build and render the default scene to out/default.exr and out/default.png (README command 1).
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/build.sh
build/bin/nimbus render scenes/default.yaml -o out/default.exr
