/* The linearised indentation system of eq. 15 (Yin, Liu & Borja 2021) as a PETSc MatNest over
 * (u, u_r, lambda), of fixed size and nonzero pattern across iterations, and its two solver paths:
 *   direct      GMRES on the nest, preconditioned by the LU factorisation (MUMPS) of the nest of an earlier
 *               Newton iteration, converted to AIJ (pivoting copes with the zero diagonal of the indenter row
 *               under force control and of the active multiplier rows). The factorisation is kept across
 *               iterations and steps while GMRES converges in a few iterations, and rebuilt when the Krylov
 *               iterations beyond the first since it was made exceed -indent_refactor_its (the cost of a
 *               factorisation counted in Krylov iterations), when a solve fails (then at once), and after a
 *               checkpoint (so that a restart repeats the run bit for bit). The operator is the matrix-free
 *               tangent (fe_tangent_operator): K is assembled only when it is factored. GMRES solves to
 *               -indent_ksp_rtol (1e-2) while Newton stops on its error estimate (semismooth.c: a correction
 *               whose remaining error is theta |du| is accepted once that is below etol |dU|, and an inexact
 *               solve's theta is about its rtol), and to -indent_ksp_rtol_tight (1e-10) when Newton iterates
 *               to a small residual and while the active set changes, where an inexact direction could flip
 *               a node with lambda - c g near zero onto another branch of a non-unique contact solution (seen
 *               on the mirrored half model of test_sector). GMRES is right-
 *               preconditioned, so its residual is the true one; every row of the system is a force
 *               (contact.h), so its norm weighs the equilibrium, indenter and gap rows alike.
 *               -indent_refactor_its 0: a fresh factorisation at every iteration, LU alone;
 *   fieldsplit  flexible GMRES on the nest, preconditioned by PCFIELDSPLIT: u | (u_r, lambda), the lower Schur
 *               factorisation with one multigrid cycle for the displacement block (on P1 GAMG with the rigid-body
 *               near null space; on P2 a two-level p-multigrid, Chebyshev-Jacobi on P2 and one GAMG cycle on the
 *               P1 space of the same mesh, fe_pmg.h; -indent_fieldsplit_pmg false: GAMG on P2) and the
 *               Schur complement's "selfp" approximation, assembled here and factored, for the small block (inner
 *               solves preonly: the outer GMRES alone iterates). The operator is the matrix-free tangent, as on the
 *               direct path; K is assembled, and the multigrid set up on it, only when the hierarchy is rebuilt, by the
 *               direct path's rule with the Krylov iterations counted beyond those of the first solve on the
 *               set-up; the contact block and its Schur approximation follow the active set at every solve. Its
 *               memory grows with the unknowns, not with a factorisation's fill (docs/contact.md, "The field
 *               split"). The tolerances are the direct path's: -indent_ksp_rtol (here 1e-10: looser directions
 *               cost the P1 kerogen twin three to six times the Newton iterations) and -indent_ksp_rtol_tight.
 *   auto        (the default) the field split in 3D above -indent_fieldsplit_above displacement unknowns, else
 *               direct (in 2D the factorisation's fill stays mild: direct wins at every size measured).
 * -indent_solver direct|fieldsplit|auto selects; the solver's options take the prefix indent_ (-indent_ksp_rtol,
 * -indent_ksp_monitor, -indent_mat_mumps_icntl_*, -indent_fieldsplit_u_*, -indent_fieldsplit_contact_*). */
#ifndef INDENT_SOLVER_H
#define INDENT_SOLVER_H

#include <petscksp.h>

#include "contact.h"
#include "contact_options.h"

typedef struct {
  PetscBool fieldsplit;
  Mat       K;           /* the displacement block (the FE Jacobian), assembled by assemble(actx) when needed */
  PetscErrorCode (*assemble)(void *);
  void     *actx;
  Mat       A, Apc;      /* the nest (kept: its K block the matrix-free tangent) and the nest with K (A if not kept);
                            kept: refactor_its > 0 (indent_solver.c, kept()) */
  Mat       Aaij, Sp;    /* the AIJ copy of Apc that is factored (direct); the Schur preconditioning matrix */
  Mat       P, Kc;       /* fieldsplit with p-multigrid (P2): the prolongation P1 -> P2 and the coarse P^T K P; else NULL */
  MatNullSpace rbmc;     /* ... and the coarse rigid-body modes, GAMG's near null space there */
  IS        is[3], isrl; /* u, u_r, lambda in the flat layout; u_r and lambda together */
  Vec       X, F;        /* flat work vectors */
  KSP       ksp;
  PetscInt  refactor_its; /* the cost of a factorisation or multigrid set-up in Krylov iterations; 0: one at every solve */
  PetscInt  extra_its;    /* Krylov iterations since the last factorisation or set-up beyond a fresh one's (count_extra) */
  PetscInt  base_its[2];  /* fieldsplit: the Krylov iterations of the first solve on the set-up, loose and tight (-1: none) */
  PetscReal rtol, rtol_tight; /* GMRES' relative tolerances, loose and tight */
  PetscBool check;        /* -indent_check_solve: a fresh LU solve beside every kept one */
  PetscReal check_max;    /* the largest relative difference seen */
  PetscBool refactor;     /* rebuild the factorisation or the multigrid hierarchy at the next solve */
  PetscInt  linear_its;   /* Krylov iterations over the run */
  PetscInt  setups;       /* factorisations (direct) or preconditioner set-ups (fieldsplit) over the run */
  double    seconds;      /* wall time in set-up and solve */
} IndentSolver;

/* K: the assembled displacement block; Kmf: the same tangent as a matrix-free operator (fe_tangent_operator);
 * assemble(actx) assembles K at the current iterate, called only when K is factored or preconditioned; coarse(actx,
 * &P, &rbm), or NULL on P1, the p-multigrid's prolongation and coarse rigid-body modes (fe_pmg.h), called once if the
 * field split takes it. */
PetscErrorCode indent_solver_create(Contact *ct, Mat K, Mat Kmf, PetscErrorCode (*assemble)(void *), PetscErrorCode (*coarse)(void *, Mat *, MatNullSpace *),
                                   void *actx, const IndentOptions *o, IndentSolver *s);
/* The path and, on the direct one, its package, for the log: "direct (umfpack)", "fieldsplit". */
PetscErrorCode indent_solver_name(IndentSolver *s, char *name, size_t len);
PetscErrorCode indent_solver_destroy(IndentSolver *s);
/* The next solve factors afresh (a new stage, a checkpoint). */
static inline void indent_solver_refresh(IndentSolver *s) { s->refactor = PETSC_TRUE; }
/* Solve J dx = -F for the current blocks; F is given by its parts (R_r on rank 0), dx returned likewise. tight:
 * solve to -indent_ksp_rtol_tight, not -indent_ksp_rtol (when it is the smaller); eta > 0: to eta instead of either
 * (an inexact Newton forcing term, semismooth.c). */
PetscErrorCode indent_solver_solve(IndentSolver *s, Contact *ct, Vec Ru, PetscReal Rr, Vec Rlam, PetscBool tight, PetscReal eta, Vec du,
                                   PetscReal *dur, Vec dlam, PetscBool *ok);

/* The product of the current blocks with a direction (du, dur, dlam): (ju, jr, jlam) = J d (for the
 * finite-difference check of the tangent). */
PetscErrorCode indent_solver_apply(IndentSolver *s, Vec du, PetscReal dur, Vec dlam, Vec ju, PetscReal *jr, Vec jlam);

#endif
