#!/usr/bin/env bash
# Install the Debian 12 packages fluidem needs, only those missing (needs root or sudo).
set -euo pipefail
packages=(cmake ninja-build g++ libomp-dev libtomlplusplus-dev libcli11-dev libfmt-dev
          libhdf5-dev hdf5-tools libhypre-dev libopenmpi-dev openmpi-bin libfftw3-dev libgtest-dev libgmock-dev libbenchmark-dev
          python3-matplotlib python3-h5py python3-numpy
          # tools/ci-fuzz.sh: clang 14, libFuzzer + sanitizer runtimes, llvm-symbolizer
          clang libclang-rt-14-dev llvm)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
