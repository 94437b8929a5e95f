/* Thermal drift of an indentation record's depth: read, its regressor and its projection out of the residuals;
 * the hold blocks' residual trends at the fit (docs/calibrate.md, "Thermal drift"). */
#ifndef CALIBRATE_DRIFT_H
#define CALIBRATE_DRIFT_H

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

/* drift: fit | {measured_in: STAGE} (read after the data and their stages; a measured drift is
 * removed from the data's depths there); the drift regressor of a run's residuals (each depth residual's change
 * per unit drift rate); its projection out of the residuals (drift: fit). */
int  cal_drift_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen);
void cal_drift_regressor(const CalRun *run, double *a);
void cal_drift_project(CalRun *run, double *r);

/* A hold block's residual trend at the fit that the fitted parameters cannot take up (cal_hold_trends). */
typedef struct {
  int    run, block, warn;
  double rate, se, z;   /* depth per s, the forward scene's units: the data's depth rises this much faster than the model's */
  double size;          /* the trend over the hold, relative to the hold's data range */
  double model_rate;    /* drift measured in this stage: the model's own rate there at the fit (NAN otherwise) */
} CalTrend;

/* The hold blocks' residual trends at the fit, the nrun runs' blocks in order (m residuals; X: the fit's q columns),
 * and the drift-stage check. */
int cal_hold_trends(const CalRun *runs, int nrun, int m, const double *X, int q, const double *r, CalTrend *out, int max);
int cal_rest_warning(const CalRun *run, const CalTrend *t);

#endif
