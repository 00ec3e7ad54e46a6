#!/usr/bin/env bash
# Install the Debian packages shockgas needs. Idempotent and non-interactive:
# when everything is already installed it only runs dpkg-query and exits.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail

packages=(
  build-essential cmake pkg-config git
  libhdf5-dev hdf5-tools libgsl-dev gnuplot-nox
  libcli11-dev libfmt-dev libgtest-dev libgmock-dev libbenchmark-dev
  # OpenSSL: the SHA-256 that records which --init file made a run.
  libssl-dev
  python3 python3-numpy python3-scipy python3-h5py
  # Man pages from --help at build time; dpkg-dev for `cpack -G DEB`
  # (dpkg-shlibdeps computes the package's library dependencies).
  help2man dpkg-dev
  # The MPI build is optional (cmake -DSHOCKGAS_MPI=ON), but the ci preset
  # builds it so that the mpirun -np 2 test really runs: install it always.
  libopenmpi-dev openmpi-bin
  # pgrep, with which the tests of stopping a build find its processes
  # (not in a minimal Debian; setsid is, in the essential util-linux).
  procps
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} Debian packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
