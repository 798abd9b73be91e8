#!/usr/bin/env bash
# ThreadSanitizer run of the threaded parts (docs/reliability.md). Configures and
# builds build-tsan (or $NIMBUS_BUILD_DIR) with -DNIMBUS_TSAN=ON, only the targets the selected tests
# need; builds TBB itself with ThreadSanitizer, from the Debian source of the installed libtbb12; runs
# a canary race that must be reported, then the selected tests with halt_on_error, so that any report
# fails its test and this script exits non-zero.
#   NIMBUS_TSAN_JOBS  build jobs (default 1: the machine is shared)
# Extra arguments go to ctest, e.g. -V.
set -euo pipefail
cd "$(dirname "$0")/../.."
bash packaging/setup.sh
build_dir=${NIMBUS_BUILD_DIR:-build-tsan}
jobs=${NIMBUS_TSAN_JOBS:-1}
here=$PWD/tests/tsan
mkdir -p "$build_dir"
build_dir=$(cd "$build_dir" && pwd)

# TBB's scheduler orders every task after its spawn and before the wait that joins it, in libtbb.so,
# which Debian builds without ThreadSanitizer: the sanitizer would see none of that ordering, and report
# every buffer a task and the main thread share. The same version built with it replaces the library at
# run time (same soname and ABI, so Embree and OpenImageIO load it too).
tbb_version=$(dpkg-query -W -f='${source:Version}' libtbb12)
tbb_package=$(dpkg-query -W -f='${source:Package}' libtbb12)
tbb_dir=$build_dir/tbb-tsan
tbb_lib=$tbb_dir/lib
if [[ "$(cat "$tbb_lib/version" 2>/dev/null)" != "$tbb_version" ]]; then
  rm -rf "$tbb_dir"
  mkdir -p "$tbb_dir/apt/lists/partial" "$tbb_dir/apt/sources.list.d" "$tbb_lib"
  # The machine's own Debian sources, for source packages, in a private apt state (the system's is left
  # alone).
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f ]] && grep -q 'debian-archive-keyring' "$f" &&
      sed 's/^Types:.*/Types: deb-src/' "$f" >"$tbb_dir/apt/sources.list.d/$(basename "$f")"
  done
  if [[ -f /etc/apt/sources.list ]]; then
    sed -n 's/^deb /deb-src /p' /etc/apt/sources.list >"$tbb_dir/apt/sources.list"
  else
    : >"$tbb_dir/apt/sources.list"
  fi
  apt_options=(-o "Dir::Etc::SourceList=$tbb_dir/apt/sources.list"
    -o "Dir::Etc::SourceParts=$tbb_dir/apt/sources.list.d" -o "Dir::State::Lists=$tbb_dir/apt/lists"
    -o Debug::NoLocking=1 -o APT::Sandbox::User=root)
  apt-get "${apt_options[@]}" -qq update
  # apt checks the files against the signed release; dpkg-source has no key for the upload's own
  # signature and would only warn about it, so its output is shown only if it fails.
  (cd "$tbb_dir" && apt-get "${apt_options[@]}" -qq source --download-only "$tbb_package=$tbb_version" &&
    { dpkg-source -x ./*.dsc src >dpkg-source.log 2>&1 || { cat dpkg-source.log >&2 && exit 1; }; })
  cmake -S "$tbb_dir/src" -B "$tbb_dir/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF -DTBBMALLOC_BUILD=OFF \
    -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON >/dev/null
  cmake --build "$tbb_dir/build" -j "$jobs" --target tbb >/dev/null
  cp -P "$(find "$tbb_dir/build" -name 'libtbb.so.12*' -type f)" "$tbb_lib/libtbb.so.12"
  echo "$tbb_version" >"$tbb_lib/version"
fi
export LD_LIBRARY_PATH=$tbb_lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}

cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DNIMBUS_TSAN=ON \
  -DNIMBUS_BUILD_BENCHMARKS=OFF >/dev/null
# test_e2e depends on the CLI and the plugins it loads, test_caustics on the solver and its references.
cmake --build "$build_dir" -j "$jobs" --target tsan_canary test_film test_caustics test_e2e
for binary in tests/tsan_canary tests/test_film tests/test_caustics tests/test_e2e bin/nimbus; do
  if ! ldd "$build_dir/$binary" | grep -q "$tbb_lib/libtbb.so.12"; then
    echo "tsan: $binary would not load the ThreadSanitizer build of TBB in $tbb_lib" >&2
    exit 1
  fi
done

# halt_on_error: the first report ends the process with exit status 66, so its test fails. Reports go
# to files in $reports, one per process, so that one in a subprocess the e2e tests start (the nimbus
# CLI, which inherits the options and the library path) fails the run even where its test would not.
reports=$build_dir/tsan-reports
rm -rf "$reports" && mkdir -p "$reports"
options="halt_on_error=1 second_deadlock_stack=1 exitcode=66 suppressions=$here/suppressions.txt"

# First the canary (canary.cpp): its race must be reported, or a clean run below would prove nothing.
canary_status=0
TSAN_OPTIONS="$options log_path=$reports/canary" "$build_dir/tests/tsan_canary" >/dev/null 2>&1 ||
  canary_status=$?
if [[ $canary_status -ne 66 ]] || ! grep -qs 'WARNING: ThreadSanitizer: data race' "$reports"/canary.* ||
  ! grep -qs 'tests/tsan/canary.cpp' "$reports"/canary.*; then
  cat "$reports"/canary.* >&2 || true
  echo "tsan: the canary's race was not reported (exit status $canary_status): the run cannot find races" >&2
  exit 1
fi
echo "tsan: the canary's race is reported"
rm -f "$reports"/canary.*

# What runs threads, and what each test drives:
# - FilmAccumulate.Concurrent*, FilmSplat.*: the film's accumulation from TBB workers, the splat merge.
# - CausticsPhotonMap.TreeIndependentOfThreads: the photon-map build (kd-tree, occupancy filter) on 8 threads.
# - CausticsRender.*ThreadCount*, ElementsAndLightMix*, CausticFreeScene*: tiles in parallel in the
#   host's arena, the photon passes on the host task service nimbus.host.tasks (paths, assembly, map
#   build), guided chains, LightMix splats and lookups from camera passes, 2 and 3 workers.
# - Determinism.*: the CLI end to end with 2 threads, the path tracer and the light tracer (splats from
#   every worker, merged between iterations).
# - Interrupt.*: Ctrl-C and SIGTERM while the workers render (path tracer, light tracer, caustics solver):
#   the cancel flag, the last iteration, the files written after it.
tests='^(FilmAccumulate\.|FilmSplat\.|CausticsPhotonMap\.TreeIndependentOfThreads$'
tests+='|CausticsRender\.(SameImageAtAnyThreadCount|GuidedSameImageAtAnyThreadCountAndUniformWithoutGuide'
tests+='|ElementsAndLightMixSumToBeauty|CausticFreeSceneIsThePathTracer)$|Determinism\.|Interrupt\.)'
status=0
TSAN_OPTIONS="$options log_path=$reports/tsan" ctest --test-dir "$build_dir" -R "$tests" --no-tests=error \
  -j 2 --timeout 1200 --output-on-failure "$@" || status=$?
if compgen -G "$reports/tsan.*" >/dev/null; then
  cat "$reports"/tsan.* >&2
  echo "tsan: ThreadSanitizer reported the races above" >&2
  exit 1
fi
exit "$status"
