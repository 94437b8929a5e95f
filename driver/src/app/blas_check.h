/* Whether the BLAS runs kernels below what this CPU can run: Debian bookworm's OpenBLAS (0.3.21) does not recognise
 * a CPU newer than itself and falls back to its SSE3 kernels ("Prescott"), which made the 3D contact solve's
 * factorisations 2.6 times as long as its AVX-512 kernels on the same machine (docs/performance.md, "BLAS kernels").
 * The variable OPENBLAS_CORETYPE names the core instead; it must be set before the program starts, so the driver can
 * only say so. camclay9.blas (tools/blas_core.py) is the same rule in Python. */
#ifndef BLAS_CHECK_H
#define BLAS_CHECK_H

#include <petscsys.h>

/* The OpenBLAS core to name, or NULL where none is needed: core is OpenBLAS' pick (NULL: the BLAS is not OpenBLAS),
   named whether OPENBLAS_CORETYPE is set (and not empty), and the CPU's instruction sets (AVX-512 F, DQ, BW and VL; AVX2 and FMA). */
const char *blas_core_to_name(const char *core, int named, int avx512, int avx2);

/* On rank 0 of comm, a note where OpenBLAS fell back (blas_core_to_name on this process and CPU). */
PetscErrorCode blas_check_note(MPI_Comm comm);

#endif
