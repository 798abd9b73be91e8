# Sourced by the shell tests that build and install things (tests/abi/sdk_examples_test.sh,
# sdk_plugins_test.sh, tests/packaging/deb_install_test.sh): a scratch directory kept when the test fails,
# its step and failure lines, and configuring an out-of-tree plugin project against one Nimbus only.
# Expects $cmake, $generator, $make_program, $cc and $cxx to be set.

# make_scratch BUILD NAME: sets $work to a fresh directory under BUILD/tests, removed at exit once the
# test sets ok=1, kept (and named) otherwise.
make_scratch() {
  work=$(mktemp -d "$1/tests/$2.XXXXXX")
  ok=0
  trap 'if [[ $ok == 1 ]]; then rm -rf "$work"; else echo "files kept in $work" >&2; fi' EXIT
}
step() { echo "== $*"; }
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# configure_plugins SOURCE BUILD LOG WHERE: configures the CMake project SOURCE into BUILD (Release), with
# WHERE (-DCMAKE_PREFIX_PATH=... or -DNimbus_DIR=...) the only place it may find Nimbus: neither the
# environment nor the package registry may supply another. Fails the test with the log if it fails.
configure_plugins() {
  local source=$1 dir=$2 log=$3 where=$4
  env -u CMAKE_PREFIX_PATH -u Nimbus_DIR "$cmake" -S "$source" -B "$dir" -G "$generator" \
    -DCMAKE_MAKE_PROGRAM="$make_program" -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_BUILD_TYPE=Release "$where" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF \
    --no-warn-unused-cli >"$log" 2>&1 || fail "configure $source: $(cat "$log")"
}
