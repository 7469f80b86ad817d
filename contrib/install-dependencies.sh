#!/usr/bin/env bash
# Installs what talus needs to build and test on Debian 12, from Debian's
# packages only. Safe to run again: apt-get skips what is already installed.
set -euo pipefail

packages=(
  libdeal.ii-dev   # meshes, finite elements, parameter files, PETSc/Trilinos/MPI through deal.II
  libeigen3-dev    # small dense algebra: inertia tensors, local frames
  libcgal-dev      # exact geometric predicates
  libgmsh-dev      # gmsh's C++ API: tetrahedral meshes of the deformable blocks
  zlib1g-dev       # compresses the binary arrays of the VTU output
  libopenmpi-dev openmpi-bin  # MPI
  numdiff          # compares test output with tolerances (deal.II's test macros need it)
  cmake g++ make
  ccache           # makes rebuilds in CI and at home cheap
)

# Optional: the accuracy study's plots (contrib/verification/run_study.py
# draws error against run time with matplotlib; the study itself needs only
# python3). Not installed by default nor in CI.
if [ "${1:-}" = "--study" ]; then
  packages+=(python3 python3-matplotlib)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-dependencies: everything is already installed"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
