/* A run's status from a PETSc error code, and the code of a failure the project reported itself (stage_runner.h,
 * "Errors of the callbacks"; docs/driver.md, "Error codes"). Apart from the runner so that the files the runner
 * calls (the checkpoints) and the layers above it (calibrate/) can use it without it. */
#ifndef RUN_STATUS_H
#define RUN_STATUS_H

#include <petscsys.h>
#include <stdio.h>

#define STEP_ERR_REPORTED PETSC_ERR_USER_INPUT
#define STEP_FAIL(err, errlen, ...) \
  do { \
    snprintf((err), (errlen), __VA_ARGS__); \
    SETERRQ(PETSC_COMM_SELF, STEP_ERR_REPORTED, "%s", (err)); \
  } while (0)

/* The run status of an error code: 0 for 0, 1 for a failure reported in err (STEP_ERR_REPORTED), else the PETSc
 * code itself with err emptied (main prints PETSc's message). */
int stage_runner_status(PetscErrorCode ierr, char *err);

#endif
