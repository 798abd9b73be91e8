#!/bin/bash
# sdk_plugins_test.sh BUILD_DIR SOURCE_DIR CMAKE GENERATOR MAKE_PROGRAM CC CXX SANITIZE [NM]
#
# The first-party plugins are built exactly as a third party builds one: install the `sdk` component into
# a fresh prefix, configure plugins/ on its own against that prefix alone (find_package(Nimbus); no host
# sources, no host include path), build and install every plugin, check each exports only the entry, and
# render the default scene with the out-of-tree nimbus.pt and nimbus.caustics (NIMBUS_PLUGIN_PATH comes
# first, so they win over the build's own copies). A configuration that cannot run it fails it.
set -euo pipefail

build=$1 src=$2 cmake=$3 generator=$4 make_program=$5 cc=$6 cxx=$7 sanitize=${8:-OFF} nm=${9:-nm}
nimbus=$build/bin/nimbus
if [[ ! -x $nimbus ]]; then
  echo "FAIL: $nimbus is not built" >&2
  exit 1
fi
if [[ ${sanitize^^} == ON || ${sanitize^^} == TRUE || $sanitize == 1 ]] && ! "$nimbus" plugins --help >/dev/null 2>&1; then
  echo "FAIL: the sanitized nimbus executable does not start here, so no plugin can be loaded" >&2
  exit 1
fi

source "$src/tests/support/shell_support.sh"
make_scratch "$build" sdk_plugins

prefix=$work/sdk
step "install the sdk component into $prefix"
"$cmake" --install "$build" --component sdk --prefix "$prefix" >"$work/install.log" ||
  fail "SDK install: $(cat "$work/install.log")"

step "configure plugins/ against $prefix alone"
configure_plugins "$src/plugins" "$work/build" "$work/configure.log" -DCMAKE_PREFIX_PATH="$prefix"
grep -q "^Nimbus_DIR:PATH=$prefix/lib/cmake/Nimbus$" "$work/build/CMakeCache.txt" ||
  fail "plugins/ found Nimbus elsewhere: $(grep ^Nimbus_DIR "$work/build/CMakeCache.txt")"
# Nothing of the host may be on any include path of the out-of-tree build.
if grep -rq -- "-I$src/host\|$src/host" "$work/build/build.ninja" "$work/build/CMakeFiles" 2>/dev/null; then
  fail "the out-of-tree plugin build names host sources"
fi

step "build and install plugins/"
"$cmake" --build "$work/build" >"$work/build.log" 2>&1 || fail "build plugins/: $(cat "$work/build.log")"
"$cmake" --install "$work/build" --prefix "$work/installed" >/dev/null || fail "install plugins/"
dir=$work/installed/lib/nimbus/plugins
libs=()
for lib in "$build"/lib/nimbus/plugins/*.so; do
  name=$(basename "$lib")
  [[ -f $dir/$name ]] || fail "the out-of-tree build lacks $name (the in-tree build has it)"
  libs+=("$dir/$name")
done
(IFS='|'; "$cmake" "-DNM=$nm" "-DLIBS=${libs[*]}" -P "$src/tests/loader/check_exports.cmake") ||
  fail "an out-of-tree plugin exports more than the entry"

export NIMBUS_PLUGIN_PATH=$dir
listing=$("$nimbus" plugins 2>&1 || true)
for id in nimbus.pt nimbus.caustics; do
  grep -Eq "^$id +integrator +[0-9.]+ +loaded +$dir/" <<<"$listing" || fail "$id is not loaded from $dir: $listing"
  step "render the default scene with the out-of-tree $id"
  "$nimbus" render "$src/tests/scenes/abi-cornell.yaml" --integrator "$id" --iterations 2 -q -o "$work/$id.exr" ||
    fail "render with $id"
done
ok=1
echo "plugins/ built against the installed SDK alone: ${#libs[@]} plugins, loaded and rendered"
