/* blas_check.h: which OpenBLAS core the driver tells a user to name, from OpenBLAS' pick, whether OPENBLAS_CORETYPE
 * is set and the CPU's instruction sets. Expected: a pre-AVX2 core picked on an AVX2 or AVX-512 CPU is a fallback
 * (OpenBLAS picks such a core there only when it did not recognise the CPU), named as the best core the CPU runs;
 * nothing where OpenBLAS recognised the CPU, where the user named a core, where the BLAS is not OpenBLAS, or where
 * the CPU has no AVX2 (Prescott is then the right pick). */
#include <stdio.h>
#include <string.h>

#include "app/blas_check.h"

static int failures;

static void expect(const char *core, int named, int avx512, int avx2, const char *want) {
  const char *got = blas_core_to_name(core, named, avx512, avx2);
  if ((got == NULL) != (want == NULL) || (got && strcmp(got, want))) {
    printf("FAIL: core %s, named %d, avx512 %d, avx2 %d: got %s, expected %s\n", core ? core : "(not OpenBLAS)", named, avx512,
           avx2, got ? got : "nothing", want ? want : "nothing");
    failures++;
  }
}

int main(void) {
  expect("Prescott", 0, 1, 1, "SkylakeX"); /* the 2026-12-02 machines: family 6 model 207, not known to 0.3.21 */
  expect("Prescott", 0, 0, 1, "Haswell");
  expect("Nehalem", 0, 0, 1, "Haswell");
  expect("Prescott", 0, 0, 0, NULL);       /* an SSE3 CPU: Prescott is right */
  expect("Prescott", 1, 1, 1, NULL);       /* the user named a core */
  expect("SkylakeX", 0, 1, 1, NULL);       /* recognised */
  expect("Haswell", 0, 1, 1, NULL);        /* recognised (or named): AVX2 kernels on an AVX-512 CPU are not a fallback */
  expect("Zen", 0, 0, 1, NULL);
  expect(NULL, 0, 1, 1, NULL);             /* not OpenBLAS */
  printf("%s\n", failures ? "blas_check: FAILED" : "blas_check: all cases pass");
  return failures != 0;
}
