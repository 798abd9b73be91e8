#!/bin/bash
# sdk_examples_test.sh BUILD_DIR SOURCE_DIR CMAKE GENERATOR MAKE_PROGRAM CC CXX SANITIZE [NM]
#
# What a third party does with Nimbus, end to end: install the `sdk` component into a fresh prefix, check
# the package's version rule (find_package(Nimbus 1.0) works, a newer minor or another major does not),
# build the out-of-tree examples (plugins/examples/, find_package(Nimbus 1.x REQUIRED)) against that
# prefix and against the build tree (-DNimbus_DIR=<build>), install them, check they export only the
# entry, load them with `nimbus plugins` (each listed with its kind) and render a scene with each
# integrator (a guide renders only when an integrator binds it). Any step failing fails the test; exit 1
# means "cannot run in this configuration" (ctest: skipped).
set -euo pipefail

build=$1 src=$2 cmake=$3 generator=$4 make_program=$5 cc=$6 cxx=$7 sanitize=${8:-OFF} nm=${9:-nm}
nimbus=$build/bin/nimbus
# directory:plugin id:library target:kind as `nimbus plugins` lists it
examples=(c-minimal:org.example.normals:example_normals:integrator
  cpp-minimal:org.example.eyelight:example_eyelight:integrator
  cpp-camera-path:org.example.balance:example_balance:integrator
  c-guide:org.example.independence:example_independence:guiding)

if [[ ! -x $nimbus ]]; then
  echo "FAIL: $nimbus is not built" >&2
  exit 1
fi
# A sanitized host runs unsanitized plugins fine (the runtime comes with the executable), so the
# examples build plainly in that configuration too; the only thing that cannot work is a sanitizer
# runtime that refuses to start (e.g. ASan under a ptrace-restricted sandbox).
if [[ ${sanitize^^} == ON || ${sanitize^^} == TRUE || $sanitize == 1 ]]; then
  if ! "$nimbus" plugins --help >/dev/null 2>&1; then
    echo "FAIL: the sanitized nimbus executable does not start here, so no plugin can be loaded" >&2
    exit 1
  fi
fi

source "$src/tests/support/shell_support.sh"
make_scratch "$build" sdk_examples

# Only the `sdk` install component: the test must not depend on every other target of the project being
# built, and the SDK is what a plugin author installs. It must not drag in the runtime either.
prefix=$work/nimbus-prefix
step "install the sdk component into $prefix"
"$cmake" --install "$build" --component sdk --prefix "$prefix" >"$work/install.log" ||
  fail "SDK install: $(cat "$work/install.log")"
for f in include/nimbus/nimbus.h include/nimbus/nimbus.hpp lib/cmake/Nimbus/NimbusConfig.cmake \
  lib/cmake/Nimbus/NimbusConfigVersion.cmake lib/cmake/Nimbus/NimbusTargets.cmake \
  lib/cmake/Nimbus/NimbusPlugin.cmake lib/cmake/Nimbus/nimbus_plugin.map; do
  [[ -f $prefix/$f ]] || fail "the SDK install lacks $f"
done
[[ ! -e $prefix/bin && ! -e $prefix/share ]] || fail "the sdk component installed runtime files: $(ls "$prefix")"

# The package version is the headers' ABI version, and SameMajorVersion answers like the plugin loader.
version_h=$src/sdk/include/nimbus/version.h
major=$(sed -n 's/^#define NIMBUS_ABI_MAJOR \([0-9]*\)$/\1/p' "$version_h")
minor=$(sed -n 's/^#define NIMBUS_ABI_MINOR \([0-9]*\)$/\1/p' "$version_h")
probe=$work/version-probe
mkdir -p "$probe"
cat >"$probe/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.17)
project(nimbus_version_probe NONE)
find_package(Nimbus ${WANT} REQUIRED)
message(STATUS "Nimbus_VERSION=${Nimbus_VERSION}")
CMAKE
# find_package(Nimbus <want>) against <where> (a -D option) must succeed (1) or fail (0).
expect_find() {
  local want=$1 where=$2 ok=$3 log=$work/probe-$1.log
  rm -rf "$probe/build"
  if env -u CMAKE_PREFIX_PATH -u Nimbus_DIR "$cmake" -S "$probe" -B "$probe/build" -DWANT="$want" "$where" \
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$log" 2>&1; then
    [[ $ok == 1 ]] || fail "find_package(Nimbus $want) accepted SDK $major.$minor ($where)"
    grep -q "Nimbus_VERSION=$major\.$minor\.[0-9]*$" "$log" || fail "wrong Nimbus_VERSION: $(cat "$log")"
  else
    [[ $ok == 0 ]] || fail "find_package(Nimbus $want) failed ($where): $(cat "$log")"
  fi
}
for where in "-DCMAKE_PREFIX_PATH=$prefix" "-DNimbus_DIR=$build"; do
  step "find_package version rule ($where)"
  expect_find 1.0 "$where" 1
  expect_find "$major.$minor" "$where" 1
  expect_find "$major.$((minor + 1))" "$where" 0
  expect_find "$((major + 1)).0" "$where" 0
done

plugins=$work/plugins-prefix
for ex in "${examples[@]}"; do
  IFS=: read -r dir id target kind <<<"$ex"
  # The build tree's package (Nimbus_DIR=<build>): configure and build, headers from the source tree.
  step "configure and build $dir against the build tree"
  configure_plugins "$src/plugins/examples/$dir" "$work/buildtree-$dir" "$work/configure-bt-$dir.log" -DNimbus_DIR="$build"
  "$cmake" --build "$work/buildtree-$dir" >"$work/build-bt-$dir.log" 2>&1 ||
    fail "build $dir against the build tree: $(cat "$work/build-bt-$dir.log")"
  "$cmake" "-DNM=$nm" "-DLIBS=$work/buildtree-$dir/lib$target.so" -P "$src/tests/loader/check_exports.cmake" ||
    fail "$dir built against the build tree exports more than the entry"

  step "configure, build and install $dir against $prefix"
  # The package registry and the environment must not supply another Nimbus: only $prefix may.
  configure_plugins "$src/plugins/examples/$dir" "$work/build-$dir" "$work/configure-$dir.log" -DCMAKE_PREFIX_PATH="$prefix"
  grep -q "^Nimbus_DIR:PATH=$prefix/lib/cmake/Nimbus$" "$work/build-$dir/CMakeCache.txt" ||
    fail "$dir found Nimbus elsewhere: $(grep ^Nimbus_DIR "$work/build-$dir/CMakeCache.txt")"
  "$cmake" --build "$work/build-$dir" >"$work/build-$dir.log" 2>&1 || fail "build $dir: $(cat "$work/build-$dir.log")"
  "$cmake" --install "$work/build-$dir" --prefix "$plugins" >/dev/null || fail "install $dir"
  lib=$plugins/lib/nimbus/plugins/lib$target.so
  [[ -f $lib ]] || fail "nimbus_add_plugin() did not install $lib"
  "$cmake" "-DNM=$nm" "-DLIBS=$lib" -P "$src/tests/loader/check_exports.cmake" || fail "$lib exports more than the entry"
done

step "nimbus plugins"
export NIMBUS_PLUGIN_PATH=$plugins/lib/nimbus/plugins
listing=$("$nimbus" plugins 2>&1 || true)
echo "$listing"
for ex in "${examples[@]}"; do
  IFS=: read -r dir id target kind <<<"$ex"
  grep -Eq "^$id +$kind +[0-9.]+ +loaded +$NIMBUS_PLUGIN_PATH/lib$target.so$" <<<"$listing" ||
    fail "$id is not listed as a loaded $kind from $NIMBUS_PLUGIN_PATH"
done

for ex in "${examples[@]}"; do
  IFS=: read -r dir id target kind <<<"$ex"
  [[ $kind == integrator ]] || continue
  step "render with $id"
  out=$work/$target.exr
  "$nimbus" render "$src/tests/scenes/abi-cornell.yaml" --integrator "$id" --iterations 1 -q -o "$out" ||
    fail "render with $id"
  # The EXR header is stored uncompressed: the integrator that produced the pixels is named in it.
  grep -aq "$id" "$out" || fail "$out does not record $id as its integrator"
done
ok=1
echo "the examples built against the installed SDK and the build tree, loaded, and the integrators rendered"
