#!/usr/bin/env python3
"""Which kernels OpenBLAS runs here, and the core to name where it did not recognise the CPU (camclay9.blas says why).

    tools/blas_core.py                      the core OpenBLAS picks here, and the one to name if it fell back
    eval "$(tools/blas_core.py --export)"   set OPENBLAS_CORETYPE in this shell where OpenBLAS fell back (and it is unset)

The core to name: SkylakeX on a CPU with AVX-512 (F, DQ, BW, VL), Haswell on one with AVX2 and FMA; nothing where
OpenBLAS recognised the CPU, where OPENBLAS_CORETYPE is already set, or where libblas.so.3 is not OpenBLAS."""
import argparse
import os
import sys

from camclay9.blas import core_to_name


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--export", action="store_true", help="print the shell line that sets OPENBLAS_CORETYPE, if one is needed")
    a = ap.parse_args()
    core, want = core_to_name()
    if a.export:
        if want:
            print(f"blas_core: OpenBLAS did not recognise this CPU (it picked {core}): OPENBLAS_CORETYPE={want}",
                  file=sys.stderr)
            print(f"export OPENBLAS_CORETYPE={want}")
        return
    print(f"OpenBLAS core: {core or 'libblas.so.3 is not OpenBLAS'}"
          + (f" (OPENBLAS_CORETYPE={os.environ['OPENBLAS_CORETYPE']})" if os.environ.get("OPENBLAS_CORETYPE") else ""))
    if want:
        print(f"a fallback: this CPU runs {want}'s kernels; set OPENBLAS_CORETYPE={want} "
              "(eval \"$(tools/blas_core.py --export)\")")


if __name__ == "__main__":
    main()
