#!/usr/bin/env bash
# Reproduce Yin, Liu & Borja (2021): run every scene of the paper (two at a time), draw the figures, write
# docs/paper.md. --quick: coarse variants in out/paper_quick, checks the paper's trends (exit 1 if one fails).
# Needs tools/setup.sh once (Debian packages, post/requirements.txt); builds the driver if needed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if [ -z "${DRIVER:-}" ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
  cmake --build build -j 2 --target driver > /dev/null
  export DRIVER=$PWD/build/bin/driver
fi
# An OpenBLAS that does not recognise this CPU runs its SSE3 kernels, 2.6 times as slow in the 3D factorisations
# (docs/performance.md, "BLAS kernels"): name the core the CPU has, unless OPENBLAS_CORETYPE is set.
eval "$(python3 tools/blas_core.py --export)"
exec python3 tools/reproduce.py "$@"
