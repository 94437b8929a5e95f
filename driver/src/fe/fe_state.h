/* The state of the finite-element problem between steps: commit (with the viscoplastic increments kept for
 * the 'volume' error measure), the measure itself, and the state's part of a checkpoint. */
#ifndef FE_STATE_H
#define FE_STATE_H

#include "../io/binfile.h"
#include "fe_problem.h"

/* Commit the trial state; keeps each point's viscoplastic strain increment (h: the step's length). */
PetscErrorCode fe_state_commit(FeProblem *p, PetscReal h);
/* The 'volume' measure of the trial state against the committed one, for a step of length h after one of
 * h_prev: || d evp - (h / h_prev) d evp_prev ||_V / || d evp ||_V over all points of all ranks (the change of
 * the viscoplastic strain rate over the step, CETOL's local estimate, relative to the step's increment).
 * -1 when there is no previous increment. */
PetscErrorCode fe_state_volume_error(FeProblem *p, PetscReal h, PetscReal h_prev, PetscReal *err);
/* This rank's part of a checkpoint: U, every point's state and increments, the UMAT call count. */
int fe_state_save(FeProblem *p, Vec U, BinFile *f);
int fe_state_load(FeProblem *p, Vec U, BinFile *f);

#endif
