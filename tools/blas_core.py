#!/usr/bin/env python3
"""Which kernels OpenBLAS runs here, and the core to name where it did not recognise the CPU.

Debian bookworm's OpenBLAS (0.3.21, the libblas.so.3 that tools/setup.sh installs and MUMPS and UMFPACK call) picks its
kernels by the CPU when it is loaded. A CPU newer than the library (measured: an Intel Xeon of family 6, model 207) is
not recognised, and it falls back to its SSE3 kernels ("Prescott"), which made the 3D contact solve's factorisations
about 2.6 times as long as its AVX-512 kernels do on the same machine (docs/performance.md, "BLAS kernels"). The
variable OPENBLAS_CORETYPE names the core instead (OpenBLAS' README, "Support for multiple targets in a single
library"); it must be set before the program starts.

    tools/blas_core.py            the core OpenBLAS picks here, and the one to name if it fell back
    eval "$(tools/blas_core.py --export)"   set OPENBLAS_CORETYPE in this shell where OpenBLAS fell back (and it is unset)

The core to name: SkylakeX on a CPU with AVX-512 (F, DQ, BW, VL), Haswell on one with AVX2 and FMA; nothing where
OpenBLAS recognised the CPU, where OPENBLAS_CORETYPE is already set, or where libblas.so.3 is not OpenBLAS."""
import argparse
import ctypes
import os
import sys

FALLBACKS = ("Prescott", "Core2", "Nehalem", "Katmai", "Northwood", "Banias")   # pre-AVX2 cores: a fallback on a newer CPU


def openblas_core():
    """The core OpenBLAS (as libblas.so.3) runs here, or None where libblas.so.3 is not OpenBLAS."""
    try:
        name = ctypes.CDLL("libblas.so.3").openblas_get_corename
    except (OSError, AttributeError):
        return None
    name.restype = ctypes.c_char_p
    return name().decode()


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def core_to_name(flags):
    """The OpenBLAS core this CPU's instruction sets allow: SkylakeX (AVX-512), Haswell (AVX2), else None."""
    if {"avx512f", "avx512dq", "avx512bw", "avx512vl"} <= flags:
        return "SkylakeX"
    if {"avx2", "fma"} <= flags:
        return "Haswell"
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--export", action="store_true", help="print the shell line that sets OPENBLAS_CORETYPE, if one is needed")
    a = ap.parse_args()
    core, want = openblas_core(), core_to_name(cpu_flags())
    needed = core in FALLBACKS and want is not None and not os.environ.get("OPENBLAS_CORETYPE")
    if a.export:
        if needed:
            print(f"blas_core: OpenBLAS did not recognise this CPU (it picked {core}): OPENBLAS_CORETYPE={want}",
                  file=sys.stderr)
            print(f"export OPENBLAS_CORETYPE={want}")
        return
    print(f"OpenBLAS core: {core or 'libblas.so.3 is not OpenBLAS'}"
          + (f" (OPENBLAS_CORETYPE={os.environ['OPENBLAS_CORETYPE']})" if os.environ.get("OPENBLAS_CORETYPE") else ""))
    if needed:
        print(f"a fallback: this CPU runs {want}'s kernels; set OPENBLAS_CORETYPE={want} "
              "(eval \"$(tools/blas_core.py --export)\")")


if __name__ == "__main__":
    main()
