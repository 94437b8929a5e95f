#!/usr/bin/env bash
# Install what this project needs on a Debian bookworm machine, and nothing that is already there.
# Safe to run twice: each step checks before it installs.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# Debian packages: compilers, CMake, PETSc (with MPI, HDF5, MUMPS, YAML), gmsh; an optimised BLAS (the
# reference BLAS that petsc-dev pulls in makes MUMPS' dense frontal kernels about 3x slower; OpenBLAS
# takes over libblas.so.3 through Debian's alternatives when installed).
debs=(gfortran gcc g++ make cmake pkg-config dpkg-dev petsc-dev gmsh libgmsh-dev libyaml-dev libhdf5-dev
      openmpi-bin libopenmpi-dev libopenblas0-serial)
missing=()
for p in "${debs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: Debian packages present"
fi

# Python packages for post/ and the independent reference integrations in tests/.
py=${PYTHON:-python3}
if ! "$py" -c "import numpy, scipy, matplotlib, h5py, yaml, pytest, meshio" 2>/dev/null; then
  echo "setup: installing Python packages from post/requirements.txt"
  "$py" -m pip install --quiet --disable-pip-version-check -r "$here/post/requirements.txt"
else
  echo "setup: Python packages present"
fi
