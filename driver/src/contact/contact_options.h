/* The indentation's options (-indent_*), declared and read in one place: the semismooth Newton method reads
 * them at its set-up, main once before the run (io/options.h: -help, values checked, misspellings refused). */
#ifndef CONTACT_OPTIONS_H
#define CONTACT_OPTIONS_H

#include <petscsys.h>

/* -indent_fieldsplit_above's default (docs/contact.md, "The field split"): over whole runs the kept factorisation
   won at every size compared; above this its factors pass about 6 GB while the field split's memory stays linear */
#define FIELDSPLIT_ABOVE 200000

typedef struct {
  PetscReal rtol;            /* residual tolerance relative to the load */
  PetscInt  max_it;          /* Newton iterations per step */
  PetscInt  stall_window;    /* give a step up when its merit did not fall tenfold in this many iterations; 0: never */
  PetscBool predictor, monitor, line_search, newton_estimate, check_tangent;
  PetscInt  solver;          /* 0: direct (MUMPS), 1: fieldsplit, 2: auto (by size) */
  PetscInt  fieldsplit_above; /* auto: the field split above this many displacement unknowns */
  PetscBool pmg;             /* fieldsplit, P2: the displacement block by p-multigrid to P1 (fe_pmg.h), not GAMG on P2 */
  PetscInt  refactor_its;    /* the cost of a factorisation or GAMG set-up in Krylov iterations; 0: at every iteration */
  PetscReal rtol_tight;      /* GMRES' tolerance while the active set changes (indent_solver.h) */
  PetscBool ksp_ew;          /* GMRES' tolerance on a settled set by the inexact Newton forcing term (semismooth.c, forcing) */
  PetscBool check_solve;     /* direct, kept: compare every solve with a fresh LU solve of the same system */
  PetscInt  tangent_part;    /* -indent_check_tangent_part: 0 all, 1 u, 2 r, 3 lambda */
} IndentOptions;

PetscErrorCode indent_options(MPI_Comm comm, IndentOptions *o);

#endif
