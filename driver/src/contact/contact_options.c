#include "contact_options.h"


#include "../io/options.h"

PetscErrorCode indent_options(MPI_Comm comm, IndentOptions *o) {
  const char *solvers[] = {"direct", "fieldsplit", "auto"}, *parts[] = {"all", "u", "r", "lambda"};
  PetscFunctionBeginUser;
  o->rtol = 1e-10, o->max_it = 30, o->stall_window = 8, o->predictor = PETSC_TRUE, o->monitor = PETSC_FALSE, o->line_search = PETSC_TRUE;
  o->newton_estimate = PETSC_TRUE, o->check_tangent = PETSC_FALSE, o->solver = 2, o->tangent_part = 0;
  o->refactor_its = 20, o->rtol_tight = 1e-10, o->check_solve = PETSC_FALSE, o->fieldsplit_above = FIELDSPLIT_ABOVE;
  o->pmg = PETSC_TRUE, o->ksp_ew = PETSC_FALSE;
  options_petsc_prefix("indent_"); /* the contact solver's KSP (indent_solver.c) */
  PetscOptionsBegin(comm, NULL, "Indentation (semismooth Newton, Box 1; docs/contact.md)", NULL);
  PetscCall(options_real(PetscOptionsObject, "-indent_rtol", "residual tolerance relative to the load", o->rtol, 0, 1, OPTIONS_LO_OPEN | OPTIONS_HI_OPEN,
                         &o->rtol, NULL));
  PetscCall(options_int(PetscOptionsObject, "-indent_max_it", "Newton iterations per step", o->max_it, 1, 10000, &o->max_it, NULL));
  PetscCall(options_int(PetscOptionsObject, "-indent_stall_window",
                        "give a step up (cut it back) once the merit has not fallen tenfold over this many iterations on an "
                        "unchanged active set (0: only at -indent_max_it)", o->stall_window, 0, 10000, &o->stall_window, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_predictor", "start each step from the extrapolated last increment", o->predictor,
                         &o->predictor, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_monitor", "print every Newton iteration", o->monitor, &o->monitor, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_line_search", "Armijo line search once the active set is fixed", o->line_search,
                         &o->line_search, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_newton_estimate",
                         "with an error measure, stop Newton once its estimated error is a small fraction of the step's tolerance",
                         o->newton_estimate, &o->newton_estimate, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_check_tangent", "compare the tangent with finite differences", o->check_tangent,
                         &o->check_tangent, NULL));
  PetscCall(options_elist(PetscOptionsObject, "-indent_check_tangent_part",
                          "with -indent_check_tangent: the whole direction, or only this part of it", parts, 4, 0, &o->tangent_part, NULL));
  PetscCall(options_elist(PetscOptionsObject, "-indent_solver",
                          "linear solver of the contact system (eq. 15); auto: in 3D fieldsplit above -indent_fieldsplit_above "
                          "unknowns, else direct", solvers, 3, 2, &o->solver, NULL));
  PetscCall(options_int(PetscOptionsObject, "-indent_fieldsplit_above",
                        "-indent_solver auto: the field split above this many displacement unknowns in 3D (2D: direct; measured: "
                        "docs/contact.md)",
                        o->fieldsplit_above, 0, PETSC_MAX_INT, &o->fieldsplit_above, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_fieldsplit_pmg",
                         "fieldsplit on P2: precondition the displacement block by a two-level p-multigrid, Chebyshev on P2 and GAMG "
                         "on the P1 space of the same mesh (false: GAMG on P2, -indent_fieldsplit_u_pc_*)", o->pmg, &o->pmg, NULL));
  PetscCall(options_int(PetscOptionsObject, "-indent_refactor_its",
                        "keep the factorisation (direct) or the multigrid hierarchy (fieldsplit) until the Krylov iterations beyond those of "
                        "a fresh one, summed since it was made, exceed this (0: a fresh one at every Newton iteration)",
                        o->refactor_its, 0, 1000000, &o->refactor_its, NULL));
  /* GMRES' tolerance of the contact solve is PETSc's (KSPSetFromOptions under the prefix indent_, indent_solver.c): declared
     here too, so that a value outside (0, 1) is refused, by its name, before the run (0: "the linear solver failed"; 1:
     no iteration at all; a negative one: PETSc's own message, after the run had begun) */
  PetscReal ksp_rtol = o->solver == 1 ? 1e-10 : 1e-2;
  PetscCall(options_real(PetscOptionsObject, "-indent_ksp_rtol",
                         "GMRES' relative tolerance of the contact solve (PETSc's KSP, prefix indent_; direct with a kept factorisation: "
                         "1e-2; fieldsplit: 1e-10; unused with -indent_refactor_its 0)", ksp_rtol, 0, 1, OPTIONS_LO_OPEN | OPTIONS_HI_OPEN,
                         &ksp_rtol, NULL));
  PetscCall(options_real(PetscOptionsObject, "-indent_ksp_rtol_tight",
                         "GMRES' relative tolerance while the active set changes or Newton iterates to a small residual (direct with a "
                         "kept factorisation, fieldsplit; -indent_ksp_rtol otherwise)", o->rtol_tight, 0, 1, OPTIONS_LO_OPEN | OPTIONS_HI_OPEN,
                         &o->rtol_tight, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_ksp_ew",
                         "on a settled active set, GMRES' tolerance by the inexact Newton forcing term of Eisenstat and Walker (as "
                         "loose as Newton's progress allows, at most 0.1, never tighter than -indent_rtol needs; docs/contact.md) instead "
                         "of -indent_ksp_rtol or -indent_ksp_rtol_tight", o->ksp_ew, &o->ksp_ew, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-indent_check_solve",
                         "direct, kept factorisation: compare every solve with a fresh LU solve of the same system (prints the difference)",
                         o->check_solve, &o->check_solve, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}
