/* The report of a calibration after TAO's fit. */
#ifndef CALIBRATE_REPORT_H
#define CALIBRATE_REPORT_H

#include <petscsys.h>

#include "calibrate_forward.h"

/* The report after TAO: Jacobian at u by finite differences, standard errors, correlations, the fitted
 * curves, the reference runs, fit.yaml. Returns 0, 1 (err filled) or a PETSc error code (err empty). */
int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen);

#endif
