/* The small-strain element kernels at one quadrature point, on the cell's closure values in global axes
 * (node-major: u[a dim + i] is component i of scalar basis a; fe_problem_setup checks that PETSc's vector
 * Lagrange space is laid out so):
 *   strain     eps = B u             (Voigt, engineering shear: 11 22 33 12 13 23 in 3D; 11 22 33 12 in 2D,
 *                                     eps_33 = 0 in plane strain and u_r / r in axisymmetry)
 *   force      f  += w B^T sig
 *   tangent    K  += w B^T D B       (column by column: B e_col has at most three non-zeros)
 * B is never formed: g holds the physical gradients of the scalar basis (ns x dim) and nr (axisymmetry, else
 * NULL) the basis values over the radius. D is the UMAT's DDSDDE, column-major ntens x ntens. The weak form is
 * that of theory.md §4 (virtual work, f_int = int B^T sigma dV). */
#ifndef FE_KERNEL_H
#define FE_KERNEL_H

#include <petscsys.h>

typedef struct {
  PetscInt         dim, ns;  /* space dimension, scalar basis functions */
  const PetscReal *g, *nr;   /* gradients (ns x dim); N_a / r (axisymmetric) or NULL */
} KernelPoint;

static inline void kernel_strain(const KernelPoint *k, const PetscScalar *u, PetscReal eps[6]) {
  const PetscReal *g = k->g;
  for (int i = 0; i < 6; i++) eps[i] = 0;
  if (k->dim == 3)
    for (PetscInt a = 0; a < k->ns; a++, g += 3) {
      const PetscReal ux = PetscRealPart(u[3 * a]), uy = PetscRealPart(u[3 * a + 1]), uz = PetscRealPart(u[3 * a + 2]);
      eps[0] += g[0] * ux, eps[1] += g[1] * uy, eps[2] += g[2] * uz;
      eps[3] += g[1] * ux + g[0] * uy, eps[4] += g[2] * ux + g[0] * uz, eps[5] += g[2] * uy + g[1] * uz;
    }
  else
    for (PetscInt a = 0; a < k->ns; a++, g += 2) {
      const PetscReal ux = PetscRealPart(u[2 * a]), uy = PetscRealPart(u[2 * a + 1]);
      eps[0] += g[0] * ux, eps[1] += g[1] * uy, eps[3] += g[1] * ux + g[0] * uy;
      if (k->nr) eps[2] += k->nr[a] * ux;
    }
}

static inline void kernel_force(const KernelPoint *k, const PetscReal s[6], PetscReal w, PetscScalar *f) {
  const PetscReal *g = k->g;
  if (k->dim == 3)
    for (PetscInt a = 0; a < k->ns; a++, g += 3) {
      f[3 * a] += w * (g[0] * s[0] + g[1] * s[3] + g[2] * s[4]);
      f[3 * a + 1] += w * (g[1] * s[1] + g[0] * s[3] + g[2] * s[5]);
      f[3 * a + 2] += w * (g[2] * s[2] + g[0] * s[4] + g[1] * s[5]);
    }
  else
    for (PetscInt a = 0; a < k->ns; a++, g += 2) {
      f[2 * a] += w * (g[0] * s[0] + g[1] * s[3] + (k->nr ? k->nr[a] * s[2] : 0));
      f[2 * a + 1] += w * (g[1] * s[1] + g[0] * s[3]);
    }
}

/* sig = D eps (D column-major n x n). */
static inline void kernel_stress(PetscInt n, const PetscReal *D, const PetscReal eps[6], PetscReal sig[6]) {
  for (PetscInt r = 0; r < n; r++) {
    PetscReal s = 0;
    for (PetscInt J = 0; J < n; J++) s += D[r + n * J] * eps[J];
    sig[r] = s;
  }
}

/* K (nb x nb, row-major, nb = ns dim) += w B^T D B: column (b, j) is w B^T D (B e_(b, j)). */
static inline void kernel_tangent(const KernelPoint *k, PetscInt n, const PetscReal *D, PetscReal w, PetscScalar *K) {
  const PetscInt nb = k->ns * k->dim;
  PetscScalar    col[90];
  for (PetscInt c = 0; c < nb; c++) {
    PetscReal eps[6] = {0, 0, 0, 0, 0, 0}, sig[6];
    const PetscReal *g = &k->g[(c / k->dim) * k->dim];
    const PetscInt   j = c % k->dim;
    if (k->dim == 3) {
      static const int shear[3][2] = {{3, 4}, {3, 5}, {4, 5}}; /* the shear strains of component j, and the */
      static const int other[3][2] = {{1, 2}, {0, 2}, {0, 1}}; /* gradient directions that go with them */
      eps[j] = g[j], eps[shear[j][0]] = g[other[j][0]], eps[shear[j][1]] = g[other[j][1]];
    } else {
      eps[j] = g[j], eps[3] = g[1 - j];
      if (j == 0 && k->nr) eps[2] = k->nr[c / 2];
    }
    kernel_stress(n, D, eps, sig);
    for (PetscInt r = 0; r < nb; r++) col[r] = 0;
    kernel_force(k, sig, w, col);
    for (PetscInt r = 0; r < nb; r++) K[r * nb + c] += col[r];
  }
}

#endif
