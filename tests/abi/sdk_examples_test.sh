#!/bin/bash
# sdk_examples_test.sh BUILD_DIR SOURCE_DIR CMAKE GENERATOR MAKE_PROGRAM CC CXX SANITIZE [NM]
#
# What a third party does with Nimbus, end to end: install the SDK into a fresh prefix, build the two
# out-of-tree examples (plugins/examples/) against it with find_package(Nimbus), install them, check
# they export only the entry, load them with `nimbus plugins` and render a scene with each. Any step
# failing fails the test; exit 77 means "cannot run in this configuration" (ctest: skipped).
set -euo pipefail

build=$1 src=$2 cmake=$3 generator=$4 make_program=$5 cc=$6 cxx=$7 sanitize=${8:-OFF} nm=${9:-nm}
nimbus=$build/bin/nimbus
examples=(c-minimal:org.example.normals:example_normals cpp-minimal:org.example.eyelight:example_eyelight)

if [[ ! -x $nimbus ]]; then
  echo "SKIP: $nimbus is not built" >&2
  exit 77
fi
# A sanitized host runs unsanitized plugins fine (the runtime comes with the executable), so the
# examples build plainly in that configuration too; the only thing that cannot work is a sanitizer
# runtime that refuses to start (e.g. ASan under a ptrace-restricted sandbox).
if [[ ${sanitize^^} == ON || ${sanitize^^} == TRUE || $sanitize == 1 ]]; then
  if ! "$nimbus" plugins --help >/dev/null 2>&1; then
    echo "SKIP: the sanitized nimbus executable does not start here, so no plugin can be loaded" >&2
    exit 77
  fi
fi

work=$(mktemp -d "$build/tests/sdk_examples.XXXXXX")
ok=0
trap 'if [[ $ok == 1 ]]; then rm -rf "$work"; else echo "files kept in $work" >&2; fi' EXIT
step() { echo "== $*"; }
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# Only the SDK's install rules (sdk/ of the build tree): the test must not depend on every other target
# of the project being built, and the SDK is what a plugin author installs.
prefix=$work/nimbus-prefix
step "install the SDK into $prefix"
"$cmake" --install "$build/sdk" --prefix "$prefix" >"$work/install.log" || fail "SDK install: $(cat "$work/install.log")"
for f in include/nimbus/nimbus.h include/nimbus/nimbus.hpp lib/cmake/Nimbus/NimbusConfig.cmake \
  lib/cmake/Nimbus/NimbusPlugin.cmake lib/cmake/Nimbus/nimbus_plugin.map; do
  [[ -f $prefix/$f ]] || fail "the SDK install lacks $f"
done

plugins=$work/plugins-prefix
for ex in "${examples[@]}"; do
  IFS=: read -r dir id target <<<"$ex"
  step "configure, build and install $dir"
  # The package registry and the environment must not supply another Nimbus: only $prefix may.
  env -u CMAKE_PREFIX_PATH -u Nimbus_DIR "$cmake" -S "$src/plugins/examples/$dir" -B "$work/build-$dir" \
    -G "$generator" -DCMAKE_MAKE_PROGRAM="$make_program" -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
    --no-warn-unused-cli >"$work/configure-$dir.log" 2>&1 || fail "configure $dir: $(cat "$work/configure-$dir.log")"
  grep -q "^Nimbus_DIR:PATH=$prefix/lib/cmake/Nimbus$" "$work/build-$dir/CMakeCache.txt" ||
    fail "$dir found Nimbus elsewhere: $(grep ^Nimbus_DIR "$work/build-$dir/CMakeCache.txt")"
  "$cmake" --build "$work/build-$dir" >"$work/build-$dir.log" 2>&1 || fail "build $dir: $(cat "$work/build-$dir.log")"
  "$cmake" --install "$work/build-$dir" --prefix "$plugins" >/dev/null || fail "install $dir"
  lib=$plugins/lib/nimbus/plugins/lib$target.so
  [[ -f $lib ]] || fail "nimbus_add_plugin() did not install $lib"
  "$cmake" "-DNM=$nm" "-DLIBS=$lib" -P "$src/tests/plugins/check_exports.cmake" || fail "$lib exports more than the entry"
done

step "nimbus plugins"
export NIMBUS_PLUGIN_PATH=$plugins/lib/nimbus/plugins
listing=$("$nimbus" plugins 2>&1 || true)
echo "$listing"
for ex in "${examples[@]}"; do
  IFS=: read -r dir id target <<<"$ex"
  grep -Eq "^$id +integrator +[0-9.]+ +loaded +$NIMBUS_PLUGIN_PATH/lib$target.so$" <<<"$listing" ||
    fail "$id is not listed as loaded from $NIMBUS_PLUGIN_PATH"
done

for ex in "${examples[@]}"; do
  IFS=: read -r dir id target <<<"$ex"
  step "render with $id"
  out=$work/$target.exr
  "$nimbus" render "$src/tests/scenes/abi-cornell.yaml" --integrator "$id" --iterations 1 -q -o "$out" ||
    fail "render with $id"
  # The EXR header is stored uncompressed: the integrator that produced the pixels is named in it.
  grep -aq "$id" "$out" || fail "$out does not record $id as its integrator"
done
ok=1
echo "both examples built against the installed SDK, loaded and rendered"
