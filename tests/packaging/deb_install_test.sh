#!/bin/bash
# deb_install_test.sh BUILD_DIR SOURCE_DIR CPACK CMAKE GENERATOR MAKE_PROGRAM CC CXX
#
# What a studio gets from the Debian package: build it (cpack -G DEB), check what it holds (stripped
# binaries and plugins whose debug information, matched by build id, is in the -dbgsym package; the
# copyright and changelog; a man page for nimbus, each subcommand and nimbus-slurm-submit, made from the
# --help texts; bash completion; the Slurm scripts), install it with dpkg into an empty root, render the
# default scene there with <root>/usr/bin/nimbus finding its plugins, OCIO config and scene by itself,
# build the SDK examples (plugins/examples) against the SDK in that root and load them, and check that the
# installed nimbus-slurm-submit submits the installed sbatch scripts.
set -euo pipefail
build=$1 src=$2 cpack=$3 cmake=$4 generator=$5 make_program=$6 cc=$7 cxx=$8

source "$src/tests/support/shell_support.sh"
make_scratch "$build" deb
for tool in dpkg dpkg-deb file readelf help2man; do
  command -v $tool >/dev/null || fail "$tool is missing (bash packaging/setup.sh installs it)"
done

step "cpack -G DEB"
"$cpack" --config "$build/CPackConfig.cmake" -G DEB -B "$work/pkg" >"$work/cpack.log" 2>&1 ||
  fail "cpack: $(cat "$work/cpack.log")"
deb=$(ls "$work"/pkg/nimbus_*.deb 2>/dev/null | head -1)
ddeb=$(ls "$work"/pkg/nimbus-dbgsym_*.ddeb 2>/dev/null | head -1)
[[ -f $deb ]] || fail "no nimbus_*.deb: $(ls "$work/pkg")"
[[ -f $ddeb ]] || fail "no debug-symbols package nimbus-dbgsym_*.ddeb: $(ls "$work/pkg")"

step "contents of $(basename "$deb")"
contents=$(dpkg-deb --contents "$deb" | awk '{print $6}')
for f in usr/bin/nimbus usr/bin/nimbus-slurm-submit usr/share/doc/nimbus/copyright \
  usr/share/doc/nimbus/changelog.Debian.gz usr/share/bash-completion/completions/nimbus \
  usr/share/nimbus/slurm/nimbus-render-task.sbatch usr/share/nimbus/slurm/nimbus-merge.sbatch \
  usr/share/nimbus/slurm/README.md usr/share/nimbus/scenes/default.yaml usr/share/nimbus/ocio/config.ocio \
  usr/include/nimbus/nimbus.h; do
  grep -qx "\./$f" <<<"$contents" || fail "the package lacks /$f"
done
for page in nimbus nimbus-render nimbus-merge nimbus-plugins nimbus-lightmix nimbus-compare nimbus-slurm-submit; do
  grep -qx "\./usr/share/man/man1/$page.1.gz" <<<"$contents" || fail "the package lacks the man page $page(1)"
done

step "install into an empty root with dpkg --root"
root=$work/root
mkdir -p "$root/var/lib/dpkg/info" "$root/var/lib/dpkg/updates" "$root/var/log"
: >"$root/var/lib/dpkg/status"
# The root has no packages at all, so the dependencies (the same libraries this machine has) are not
# registered there: --force-depends. The package has no maintainer scripts to run.
dpkg --root="$root" --force-depends --force-not-root -i "$deb" >"$work/dpkg.log" 2>&1 ||
  fail "dpkg -i: $(cat "$work/dpkg.log")"
dpkg --root="$root" -s nimbus | grep -q "^Status: install ok installed" || fail "dpkg does not list nimbus as installed"
nimbus=$root/usr/bin/nimbus

step "stripped binaries, debug information in the dbgsym package"
debug_files=$(dpkg-deb --contents "$ddeb" | awk '{print $6}')
# The plugins and the image I/O module (OpenImageIO, loaded when the first image is read or written).
plugins=("$root"/usr/lib/nimbus/plugins/*.so "$root"/usr/lib/*/nimbus/plugins/*.so "$root"/usr/lib/nimbus/host/*.so
  "$root"/usr/lib/*/nimbus/host/*.so)
for bin in "$nimbus" "${plugins[@]}"; do
  [[ -e $bin ]] || continue
  file -b "$bin" | grep -q ", stripped" || fail "$bin is not stripped: $(file -b "$bin")"
  id=$(readelf -n "$bin" | sed -n 's/^ *Build ID: \([0-9a-f]*\)$/\1/p')
  [[ -n $id ]] || fail "$bin has no build id"
  grep -qx "\./usr/lib/debug/\.build-id/${id:0:2}/${id:2}\.debug" <<<"$debug_files" ||
    fail "the dbgsym package has no debug information for $bin (build id $id)"
done

step "man pages and completion come from the --help texts"
zcat "$root/usr/share/man/man1/nimbus-render.1.gz" | grep -q -- 'task K' || fail "nimbus-render(1) lacks --task"
zcat "$root/usr/share/man/man1/nimbus-merge.1.gz" | grep -q -- 'allow' || fail "nimbus-merge(1) lacks --allow-incomplete"
completion=$(NIMBUS=$nimbus bash -c "source /usr/share/bash-completion/bash_completion 2>/dev/null || true
  source '$root/usr/share/bash-completion/completions/nimbus'; complete -p nimbus; _nimbus_options \"\$NIMBUS\" merge")
grep -q "complete -F _nimbus nimbus" <<<"$completion" || fail "the completion does not register: $completion"
grep -qx -- "--allow-incomplete" <<<"$completion" || fail "the completion does not offer merge's options: $completion"

step "render the installed default scene with $nimbus"
"$nimbus" --version | grep -Eq "^nimbus [0-9.]+ \(SDK ABI [0-9]+\.[0-9]+\.[0-9]+\)$" || fail "nimbus --version: $("$nimbus" --version)"
listing=$(env -u NIMBUS_PLUGIN_PATH "$nimbus" plugins 2>&1)
grep -Eq "^nimbus\.caustics +integrator .* loaded +$root/usr/lib/" <<<"$listing" ||
  fail "the installed nimbus does not load its own caustics plugin: $listing"
(cd "$work" && env -u NIMBUS_PLUGIN_PATH -u NIMBUS_OCIO_CONFIG "$nimbus" render default.yaml -o "$work/out/default.exr" \
  --iterations 2 --threads 2 -q) || fail "render default.yaml"
[[ -s $work/out/default.exr && -s $work/out/default.png ]] || fail "no EXR and PNG from the installed nimbus"

step "build the SDK examples against $root/usr"
for dir in c-minimal cpp-minimal cpp-camera-path c-guide; do
  configure_plugins "$src/plugins/examples/$dir" "$work/ex-$dir" "$work/configure-$dir.log" -DCMAKE_PREFIX_PATH="$root/usr"
  grep -q "^Nimbus_DIR:PATH=$root/usr/lib/.*cmake/Nimbus$" "$work/ex-$dir/CMakeCache.txt" ||
    fail "$dir found Nimbus elsewhere: $(grep ^Nimbus_DIR "$work/ex-$dir/CMakeCache.txt")"
  "$cmake" --build "$work/ex-$dir" >"$work/build-$dir.log" 2>&1 || fail "build $dir: $(cat "$work/build-$dir.log")"
  "$cmake" --install "$work/ex-$dir" --prefix "$work/examples" >/dev/null || fail "install $dir"
done
listing=$(NIMBUS_PLUGIN_PATH="$work/examples/lib/nimbus/plugins" "$nimbus" plugins 2>&1)
grep -Eq "^org\.example\.normals +integrator .* loaded" <<<"$listing" || fail "example not loaded: $listing"
grep -Eq "^org\.example\.balance +integrator .* loaded" <<<"$listing" || fail "example not loaded: $listing"
grep -Eq "^org\.example\.eyelight +integrator .* loaded" <<<"$listing" || fail "example not loaded: $listing"
grep -Eq "^org\.example\.independence +guiding .* loaded" <<<"$listing" || fail "example not loaded: $listing"

step "the installed nimbus-slurm-submit finds its sbatch scripts"
plan=$("$root/usr/bin/nimbus-slurm-submit" "$root/usr/share/nimbus/scenes/default.yaml" -o "$work/farm/out.exr" \
  --tasks 3 --nimbus "$nimbus" --dry-run -- --iterations 6 2>&1) || fail "nimbus-slurm-submit --dry-run: $plan"
grep -q -- "--array 0-2 .*$root/usr/share/nimbus/slurm/nimbus-render-task.sbatch" <<<"$plan" ||
  fail "the array is not submitted with the installed script: $plan"
grep -q -- "--dependency afterok:.*$root/usr/share/nimbus/slurm/nimbus-merge.sbatch" <<<"$plan" ||
  fail "the merge is not submitted with the installed script: $plan"
ok=1
echo "the package installed into an empty root, rendered its default scene, and the SDK examples built against it"
