#!/usr/bin/env bash
# Fuzzes the input readers (docs/reliability.md, "Fuzzing"): configures and builds build-fuzz (clang-14,
# libFuzzer, ASan, UBSan) if needed, runs each target for MINUTES minutes, one at a time under nice, and
# prints what libFuzzer reports per target.
#
#   tests/fuzz/run.sh MINUTES [TARGET...]   targets: scene obj gltf subdivision checkpoint image descriptor
#
# The working corpus of a target is build-fuzz/fuzz/corpus/<target>, seeded from tests/fuzz/<target> (which
# the run never writes to); findings (crash-*, timeout-*, oom-*, leak-*) go to build-fuzz/fuzz/findings/
# <target>, the log to build-fuzz/fuzz/<target>.log. A run stops at its first finding: copy the input
# into tests/fuzz/<target>/regressions/, fix the host, run again.
set -euo pipefail

minutes=${1:?usage: tests/fuzz/run.sh MINUTES [TARGET...]}
shift
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$src/build-fuzz
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene obj gltf subdivision checkpoint image descriptor)

if [ ! -f "$build/build.ninja" ]; then
  CC=clang CXX=clang++ cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DNIMBUS_FUZZ=ON -DNIMBUS_BUILD_TESTS=OFF -DNIMBUS_BUILD_BENCHMARKS=OFF
fi
nice ninja -C "$build" -j1 "${targets[@]/#/fuzz_}"

out=$build/fuzz
found=0
export LSAN_OPTIONS=suppressions=$src/tests/fuzz/lsan.supp
rows=()
for t in "${targets[@]}"; do
  corpus=$out/corpus/$t findings=$out/findings/$t log=$out/$t.log
  mkdir -p "$corpus" "$findings"
  touch "$out/$t.start"  # findings of this run are the files newer than this
  cp -r "$src/tests/fuzz/$t/." "$corpus/"
  echo "fuzzing $t for $minutes min: $log"
  # -timeout: one input running this long is a hang; -rss_limit_mb: an allocation this big is an OOM
  # (ASan's shadow memory included). stdin is closed so a path like /dev/stdin cannot block.
  status=0
  nice "$build/tests/fuzz/fuzz_$t" "$corpus" -max_total_time=$((minutes * 60)) -timeout=10 \
    -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$findings/" </dev/null >"$log" 2>&1 || status=$?
  stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
  count() { find "$findings" -name "$1-*" -newer "$out/$t.start" | wc -l; }
  reports=$(grep -cE 'ERROR: (Address|Leak)Sanitizer|runtime error:' "$log" || true)
  rows+=("$t $(stat number_of_executed_units) $(stat average_exec_per_sec) $(count crash) $(count timeout) \
$(count oom) $(count leak) $reports $status")
  [ "$status" -eq 0 ] || found=1
done

printf '\n%-12s %12s %8s %8s %9s %6s %6s %10s %5s\n' target executions exec/s crashes timeouts OOMs leaks \
  sanitizer exit
for row in "${rows[@]}"; do
  # shellcheck disable=SC2086
  printf '%-12s %12s %8s %8s %9s %6s %6s %10s %5s\n' $row
done
exit $found  # non-zero when any target stopped at a finding
