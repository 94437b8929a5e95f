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

# Python packages for post/ and the package camclay9's shared modules (its plots, the independent reference
# integration camclay9.reference, the benches' modules). A Python that is not a
# virtual environment but is marked externally managed (PEP 668: Debian bookworm's) takes them only with
# --break-system-packages; pip installs them under /usr/local, beside Debian's own.
py=${PYTHON:-python3}
pip_install() {
  local flags=(--quiet --disable-pip-version-check)
  if "$py" -c 'import os, sys, sysconfig
sys.exit(not (sys.prefix == sys.base_prefix
              and os.path.isfile(os.path.join(sysconfig.get_path("stdlib"), "EXTERNALLY-MANAGED"))))'; then
    flags+=(--break-system-packages)
  fi
  "$py" -m pip install "${flags[@]}" "$@"
}
if ! "$py" -c "import numpy, scipy, matplotlib, h5py, yaml, pytest, meshio" 2>/dev/null; then
  echo "setup: installing Python packages from post/requirements.txt"
  pip_install -r "$here/post/requirements.txt"
else
  echo "setup: Python packages present"
fi

# The project's own package, camclay9 (python/): reading runs and launching the driver, for post/, bench/,
# tools/ and tests/. Installed as a copy: reinstalled when the installed files differ from python/camclay9/.
if ! "$py" - "$here/python/camclay9" <<'CHECK' 2>/dev/null; then
import filecmp, pathlib, sys
import camclay9
src, got = pathlib.Path(sys.argv[1]), pathlib.Path(camclay9.__file__).parent
sys.exit(any(not filecmp.cmp(f, got / f.name, shallow=False) for f in src.glob("*.py")))
CHECK
  echo "setup: installing the Python package camclay9 from python/"
  isolation=(); "$py" -c "import setuptools, wheel" 2>/dev/null && isolation=(--no-build-isolation)
  pip_install "${isolation[@]}" --upgrade --force-reinstall --no-deps "$here/python"
else
  echo "setup: Python package camclay9 present (the same as python/camclay9)"
fi
