/* Whether the BLAS runs kernels below what this CPU can run (blas_check.h; camclay9.blas is the same rule). */
#define _GNU_SOURCE
#include "blas_check.h"

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

/* OpenBLAS' cores without AVX2: its pick on a CPU with AVX2 only where it did not recognise the CPU */
static const char *const fallbacks[] = {"Prescott", "Core2", "Nehalem", "Katmai", "Northwood", "Banias"};

const char *blas_core_to_name(const char *core, int named, int avx512, int avx2) {
  int fallback = 0;
  if (!core || named) return NULL;
  for (size_t k = 0; k < sizeof fallbacks / sizeof *fallbacks; k++) fallback |= !strcmp(core, fallbacks[k]);
  if (!fallback) return NULL;
  return avx512 ? "SkylakeX" : avx2 ? "Haswell" : NULL;
}

PetscErrorCode blas_check_note(MPI_Comm comm) {
  /* looked up, not linked: libblas.so.3 may be another BLAS, which has no such function */
  char *(*corename)(void) = (char *(*)(void))dlsym(RTLD_DEFAULT, "openblas_get_corename");
  const char *core = corename ? corename() : NULL, *named = getenv("OPENBLAS_CORETYPE"), *want;
  PetscFunctionBeginUser;
  __builtin_cpu_init();
  want = blas_core_to_name(core, named && *named, /* set and not empty, as camclay9.blas reads it */
                           __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                               __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl"),
                           __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"));
  if (want)
    PetscCall(PetscPrintf(comm, "note: OpenBLAS did not recognise this CPU and ran its %s kernels (without AVX2), which made the 3D "
                                "factorisations about 2.6 times as long where measured; export OPENBLAS_CORETYPE=%s before "
                                "the driver starts (tools/blas_core.py; docs/performance.md, \"BLAS kernels\")\n",
                          core, want));
  PetscFunctionReturn(0);
}
