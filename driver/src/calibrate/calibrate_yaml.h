/* What a calibration tells its user: the fit's uncertainty, fit.yaml, the summary on stdout, the value to quote. */
#ifndef CALIBRATE_YAML_H
#define CALIBRATE_YAML_H

#include <petscsys.h>
#include <stdio.h>

#include "calibrate_drift.h"
#include "calibrate_forward.h"
#include "calibrate_refine.h"
#include "calibrate_stats.h"

/* The uncertainty of the fit (filled by cal_report): the data's part (Newey-West) and the drift rates. */
typedef struct {
  double     se[CAL_MAX_PARAMS], white[CAL_MAX_PARAMS]; /* Newey-West, and white (independent residuals) */
  double     step[CAL_MAX_PARAMS];  /* the Gauss-Newton step left at the fit (in the parameter): TAO's convergence */
  double     drift_se[CAL_MAX_RUNS];
  double     load[CAL_MAX_PARAMS]; /* the fitted load histories' share (NAN: no fitted history, or not measured) */
  CalHacInfo hac;
  CalTrend   trend[CAL_MAX_RUNS * CAL_MAX_CURVES];
  int        ntrend;
} CalUncertainty;

/* fit.yaml and the summary on stdout. */
void cal_write_yaml(Calib *c, FILE *fp, const double *u, const CalUncertainty *un, const double *cov, double ssr, PetscInt its,
                    const char *reason, const CalBias *b);
PetscErrorCode cal_print_summary(Calib *c, const double *u, const CalUncertainty *un, const CalBias *b);
/* The value to quote, its standard error and its parts (data; model: NAN when not measured; load: the fitted load
 * history's, NAN without one; convergence), and where it comes from. */
typedef struct {
  double v, s, data, model, load, conv;
  char   why[256];
} CalQuote;
void cal_quote(const Calib *c, const double *u, const CalUncertainty *un, const CalBias *b, int k, CalQuote *q);

#endif
