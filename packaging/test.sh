#!/usr/bin/env bash
# Set-up, build and run the whole test suite (README command 2; CI runs this).
set -euo pipefail
cd "$(dirname "$0")/.."
bash packaging/build.sh "$@"
build_dir=${NIMBUS_BUILD_DIR:-build}
# NIMBUS_CTEST_EXCLUDE_LABEL and NIMBUS_CTEST_EXCLUDE: regular expressions of ctest labels and of test
# names to leave out (CI's sanitizer pass, .ci/run).
ctest --test-dir "$build_dir" --output-on-failure -j "$(nproc)" --timeout 900 \
  ${NIMBUS_CTEST_EXCLUDE_LABEL:+-LE "$NIMBUS_CTEST_EXCLUDE_LABEL"} ${NIMBUS_CTEST_EXCLUDE:+-E "$NIMBUS_CTEST_EXCLUDE"}
