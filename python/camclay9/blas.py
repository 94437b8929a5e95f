"""Which kernels OpenBLAS runs here, and the core to name where it did not recognise the CPU (tools/blas_core.py,
tools/reproduce.py, bench/blas_kernels_bench.py; the driver's note, driver/src/app/blas_check.c, is the same rule in C,
and tests/driver/test_blas_note.py holds the two together).

Debian bookworm's OpenBLAS (0.3.21, the libblas.so.3 that MUMPS and UMFPACK call) picks its kernels by the CPU when it
is loaded. A CPU newer than the library is not recognised, and it falls back to a core without AVX2 ("Prescott" on an
Intel Xeon of family 6, model 207), which made the 3D contact solve's factorisations about 2.6 times as long as its
AVX-512 kernels on the same machine (docs/performance.md, "BLAS kernels"). The variable OPENBLAS_CORETYPE names the
core instead (OpenBLAS' README, "Support for multiple targets in a single library"); it must be set before the
program starts."""
import ctypes
import os

FALLBACKS = ("Prescott", "Core2", "Nehalem", "Katmai", "Northwood", "Banias")   # cores without AVX2: a fallback on a newer CPU


def openblas_core():
    """The core OpenBLAS (as libblas.so.3) runs in this process, or None where libblas.so.3 is not OpenBLAS."""
    try:
        name = ctypes.CDLL("libblas.so.3").openblas_get_corename
    except (OSError, AttributeError):
        return None
    name.restype = ctypes.c_char_p
    return name().decode()


def cpu_flags():
    """The CPU's instruction-set flags (/proc/cpuinfo); empty where it cannot be read."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("flags"):
                    return set(line.split(":", 1)[1].split())
    except OSError:
        pass
    return set()


def core_for(flags):
    """The best OpenBLAS core these instruction sets run: SkylakeX (AVX-512 F, DQ, BW, VL), Haswell (AVX2, FMA), else None."""
    if {"avx512f", "avx512dq", "avx512bw", "avx512vl"} <= flags:
        return "SkylakeX"
    if {"avx2", "fma"} <= flags:
        return "Haswell"
    return None


def core_to_name(env=None):
    """(OpenBLAS' pick, the core to name or None): a core is named only where OpenBLAS fell back, the CPU runs a better
    one, and OPENBLAS_CORETYPE is unset (or empty) in env (default: this process's environment)."""
    env = os.environ if env is None else env
    core, want = openblas_core(), core_for(cpu_flags())
    return core, (want if core in FALLBACKS and want and not env.get("OPENBLAS_CORETYPE") else None)
