#include "run_status.h"

int stage_runner_status(PetscErrorCode ierr, char *err) {
  if (!ierr) return 0;
  if (ierr == STEP_ERR_REPORTED && err[0]) return 1;
  err[0] = '\0';
  return (int)ierr;
}
