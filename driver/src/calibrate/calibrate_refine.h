/* The forward model's bias at the fit and the two-fidelity refinement on the full model. */
#ifndef CALIBRATE_REFINE_H
#define CALIBRATE_REFINE_H

#include "calibrate_forward.h"

#define CAL_REFINE_CAP 32 /* refine_runs at most */

/* The forward model's bias at the fit (a full-model run there) and the two-fidelity refinement. */
typedef struct {
  int    have, refined, converged, nfull; /* a reference was run; refined; its steps converged; full-model runs */
  double first[CAL_MAX_PARAMS];           /* the bias from the first full-model run (linearised) */
  double p[CAL_MAX_PARAMS], se[CAL_MAX_PARAMS];       /* refined values and standard errors (se_data, se_model combined) */
  double se_data[CAL_MAX_PARAMS], se_model[CAL_MAX_PARAMS]; /* the data's part (Newey-West), the model's (the last step) */
  double bias[CAL_MAX_PARAMS], bias_se[CAL_MAX_PARAMS]; /* the forward fit less the refined one */
  double steps[CAL_REFINE_CAP][CAL_MAX_PARAMS];       /* each refinement step, relative to the value */
  int    nsteps;
  double max_diff[CAL_MAX_RUNS];          /* each run's largest model difference at the fit / data range; -1: none */
  int    max_block[CAL_MAX_RUNS];         /* the block where it is */
  char   failed[1024];                    /* a reference run failed: why ("" otherwise) */
} CalBias;

/* The bias of the fit at u (J, the inverse of J^T J, the standard errors se, all of the forward model) from a
 * full-model run there, and the refinement on the full model. 1 with err when a reference
 * run failed (b->failed says so too). */
int cal_bias(Calib *c, const double *u, const double *J, const double *inv, const double *se, CalBias *b, char *err,
             size_t errlen);

#endif
