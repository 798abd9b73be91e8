#!/usr/bin/env bash
# Installs the Debian 12 packages Nimbus needs to build, test and package (help2man writes the man pages;
# Slurm and MUNGE run the farm test, tests/slurm, on localhost). Idempotent: installs only what
# is missing and prints nothing when everything is already there. Needs root (or sudo) and apt-get.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache git file
  libembree-dev libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev libopencolorio-dev
  libyaml-cpp-dev libosd-dev libtbb-dev libgtest-dev libgmock-dev libbenchmark-dev
  libtinyobjloader-dev libtinygltf-dev
  python3 python3-numpy python3-matplotlib clang-format
  clang  # the sanitizer build (CI's second pass) and the fuzz targets
  help2man
  slurm-wlm munge
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup.sh: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=sudo
fi
echo "setup.sh: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup.sh: done"
