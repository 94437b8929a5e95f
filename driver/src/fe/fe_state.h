/* The state of the finite-element problem between steps: commit (with the viscoplastic increments kept for
 * the 'volume' error measure), the measure itself, and the state's part of a checkpoint. */
#ifndef FE_STATE_H
#define FE_STATE_H

#include <petscviewer.h>

#include "fe_problem.h"

/* Commit the trial state; keeps each point's viscoplastic strain increment (h: the step's length). */
PetscErrorCode fe_state_commit(FeProblem *p, PetscReal h);
/* Whether the last committed step kept its viscoplastic increments (the 'volume' measure's previous step), for a
 * checkpoint. */
static inline PetscBool fe_state_have_devp(const FeProblem *p) { return p->pts.have_devp; }
static inline void      fe_state_set_have_devp(FeProblem *p, PetscBool have) { p->pts.have_devp = have; }
/* The 'volume' measure of the trial state against the committed one, for a step of length h after one of
 * h_prev: || d evp - (h / h_prev) d evp_prev ||_V / || d evp ||_V over all points of all ranks (the change of
 * the viscoplastic strain rate over the step, CETOL's local estimate, relative to the step's increment).
 * -1 when there is no previous increment. */
PetscErrorCode fe_state_volume_error(FeProblem *p, PetscReal h, PetscReal h_prev, PetscReal *err);
/* The state's part of a checkpoint's shared file (a PETSc HDF5 viewer), in the serial mesh's order
 * (fe_natural.h), so that a run written on N ranks restarts on any M: the nodal vectors given (global vectors of
 * p->dm: the displacement, the predictor's increment) under /nodes, every point's state and viscoplastic
 * increment per cell under /cells, each rank's UMAT call count. Collective. */
PetscErrorCode fe_state_view(FeProblem *p, PetscViewer v, PetscInt nvec, Vec vecs[], const char *const names[]);
/* Read it back; the UMAT call counts: each rank its own on as many ranks as wrote them, else rank 0 their sum. */
PetscErrorCode fe_state_read(FeProblem *p, PetscViewer v, PetscInt nvec, Vec vecs[], const char *const names[]);

#endif
