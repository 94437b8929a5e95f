/* How the stepping follows a stage's step plan (scene/stage.h): the planned fixed steps, the step controller of
 * the adaptive ones and the one cutback policy of every scene kind. */
#ifndef STEP_CONTROL_H
#define STEP_CONTROL_H

#include "../scene/stage.h"

/* One cutback policy for every scene kind. */
#define STEP_MAX_CUTBACKS 30    /* consecutive cutbacks of one step before the run stops */
#define STEP_CUT_DIVERGED 0.25  /* the step's Newton method (or the control Newton) did not converge */
#define STEP_SAFETY 0.9         /* error controller: aim below the tolerance */

/* The step controller's exponents: dt' = dt S ratio^-alpha ratio_prev^beta (step_control_next); (1, 0) is the
 * elementary controller. The default (1, 0.15), a PI controller with integral gain 0.85 and proportional gain 0.15
 * in Soderlind's terms, was chosen by measurement on every shipped scene (docs/driver.md, "Step controller"):
 * fewer UMAT calls than the elementary one on each, and than Gustafsson's (0.7, 0.4), which grows steps slowly. */
typedef struct {
  double alpha, beta;
} StepGains;
#define STEP_GAINS_PI ((StepGains){1.0, 0.15}) /* the default; alpha = 0 in RunnerOptions means this */

/* The k-th planned fixed step (k from 0) of a stage of this duration; adaptive: the first step. */
double step_control_planned(const StepControl *sc, double duration, int k);
/* After an accepted adaptive step of length dt: the next one. pnewdt: the UMAT's suggestion (worst_point);
 * ratio: error estimate / tol of a relative measure (< 0: none this step); ratio_prev: the previous accepted
 * step's (< 0: none: then the elementary controller); g: the controller's exponents. */
double step_control_next(const StepControl *sc, const StepGains *g, double dt, double pnewdt, double ratio, double ratio_prev);
/* The length a rejected step of length dt is redone at: cut by divergence, or the UMAT's PNEWDT (< 1), or the error
 * ratio (> 1). A step rejected on its error alone is redone at min at the shortest (a step of min is accepted
 * whatever its estimate); the others may come out below min, where the run stops. */
double step_control_cut(const StepControl *sc, double dt, int diverged, double pnewdt, double ratio);

#endif
