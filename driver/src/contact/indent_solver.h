/* The linearised indentation system of eq. 15 (Yin, Liu & Borja 2021) as a PETSc MatNest over
 * (u, u_r, lambda), of fixed size and nonzero pattern across iterations, and its two solver paths:
 *   direct      the nest converted to AIJ, LU by MUMPS (pivoting copes with the zero diagonal of the
 *               indenter row under force control and of the active multiplier rows);
 *   fieldsplit  PCFIELDSPLIT on the nest itself: u | (u_r, lambda), Schur complement on the small block,
 *               the displacement block by GAMG (rigid-body near null space) inside GMRES, the Schur
 *               complement preconditioned by its "selfp" approximation assembled here and factored.
 * -indent_solver direct|fieldsplit selects; options with the prefixes fieldsplit_u_ and fieldsplit_contact_
 * reach the inner solvers. */
#ifndef INDENT_SOLVER_H
#define INDENT_SOLVER_H

#include <petscksp.h>

#include "contact.h"

typedef struct {
  PetscBool fieldsplit;
  Mat       K;           /* the displacement block (the FE Jacobian) */
  Mat       A, Aaij, Sp; /* the nest; its AIJ copy (direct); the Schur preconditioning matrix */
  IS        is[3], isrl; /* u, u_r, lambda in the flat layout; u_r and lambda together */
  Vec       X, F;        /* flat work vectors */
  KSP       ksp;
  PetscInt  linear_its;  /* Krylov iterations over the run (fieldsplit) */
  double    seconds;     /* wall time in set-up and solve */
} IndentSolver;

PetscErrorCode indent_solver_create(Contact *ct, Mat K, IndentSolver *s);
PetscErrorCode indent_solver_destroy(IndentSolver *s);
/* Solve J dx = -F for the current blocks; F is given by its parts (R_r on rank 0), dx returned likewise. */
PetscErrorCode indent_solver_solve(IndentSolver *s, Contact *ct, Vec Ru, PetscReal Rr, Vec Rlam, Vec du, PetscReal *dur,
                                   Vec dlam, PetscBool *ok);

/* The product of the current blocks with a direction (du, dur, dlam): (ju, jr, jlam) = J d (for the
 * finite-difference check of the tangent). */
PetscErrorCode indent_solver_apply(IndentSolver *s, Vec du, PetscReal dur, Vec dlam, Vec ju, PetscReal *jr, Vec jlam);

#endif
