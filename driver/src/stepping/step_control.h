/* How a stage is divided into steps, and how a step's error is judged.
 *
 * Fixed steps: a count (equal, or growing geometrically). Adaptive steps: the length follows an error
 * measure chosen by the scene (steps.error), within [min, max] and growing at most by 'growth':
 *   worst_point  the UMAT's own control (PNEWDT with PROPS tol, Abaqus CETOL-like): the worst point rules;
 *   volume       the volume-weighted norm of the change of the viscoplastic strain rate over the step, at
 *                every point (the same local estimate as CETOL: dt |rate_end - rate_start|), relative to the
 *                volume norm of the step's viscoplastic strain increment;
 *   output       the difference between the step's converged increment of what the scene reports (the
 *                indenter depth; the volume-mean strain; a point's strain and stress) and its linear
 *                extrapolation from the previous step (the predictor-corrector estimate of a first-order
 *                method), relative to the increment itself.
 * The relative measures bound the error per unit of change: the accumulated error of an output is about
 * tol times its change, so halving tol halves the error (first order). See docs/driver.md. */
#ifndef STEP_CONTROL_H
#define STEP_CONTROL_H

#include "../io/yaml_doc.h"

typedef enum { MEASURE_WORST_POINT, MEASURE_VOLUME, MEASURE_OUTPUT } ErrorMeasure;

typedef struct {
  int          adaptive, count;
  double       ratio;                   /* fixed steps: dt_{k+1} = ratio dt_k (1: equal steps) */
  double       first, min, max, growth; /* adaptive steps */
  ErrorMeasure measure;
  double       tol;                     /* <= 0 with worst_point: PROPS tol as the material gives it */
} StepControl;

/* One cutback policy for every scene kind. */
#define STEP_MAX_CUTBACKS 30    /* consecutive cutbacks of one step before the run stops */
#define STEP_CUT_DIVERGED 0.25  /* the step's Newton method (or the control Newton) did not converge */
#define STEP_SAFETY 0.9         /* error controller: aim below the tolerance */
#define STEP_PI_I 0.7           /* PI controller's exponents for an estimate first order in dt (Gustafsson 1991; */
#define STEP_PI_P 0.4           /* Soderlind 2002): dt' = dt S r^-0.7 r_prev^0.4 */

/* steps: {count: N, spacing: linear | geometric, ratio: r}
 *    or  {adaptive: true, first, min, max, growth, error: {measure: worst_point | volume | output, tol}}.
 * node may be NULL (one step). Returns 0, or 1 with err naming file, line and key. */
int step_control_read(const YdDoc *doc, YdNode *node, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen);
/* The k-th planned fixed step (k from 0) of a stage of this duration; adaptive: the first step. */
double step_control_planned(const StepControl *sc, double duration, int k);
/* After an accepted adaptive step of length dt: the next one. pnewdt: the UMAT's suggestion (worst_point);
 * ratio: error estimate / tol of a relative measure (< 0: none this step); ratio_prev: the previous accepted
 * step's (< 0: none, or the elementary controller asked for): with both, the PI controller. */
double step_control_next(const StepControl *sc, double dt, double pnewdt, double ratio, double ratio_prev);
/* The factor a rejected step is cut by: the UMAT's PNEWDT (< 1), or error ratio (> 1), or divergence. */
double step_control_cut_factor(int diverged, double pnewdt, double ratio);
const char *step_control_measure_name(ErrorMeasure m);

/* 'until' events. Rising events (ABOVE, DEPTH, LOAD) and Q_BELOW are landed on: a step that overshoots is
 * redone shorter (secant), so the stage ends within EVENT_TOL of the value. EVP_RATE_BELOW ends the stage
 * after the first step whose volume-mean viscoplastic strain rate is below the value. */
typedef enum { EVENT_NONE, EVENT_EVP_RATE_BELOW, EVENT_Q_ABOVE, EVENT_Q_BELOW, EVENT_P_ABOVE, EVENT_DEPTH, EVENT_LOAD, EVENT_KINDS } EventKind;
#define EVENT_TOL 1e-5

typedef struct {
  EventKind kind;
  double    value;
} StageEvent;

/* Read 'until: {KIND: value}' (one key of the allowed ones: a subset of evp_rate_below, q_above, q_below,
 * p_above, depth, load, comma separated). node may be NULL. */
int stage_event_read(const YdDoc *doc, YdNode *node, const char *path, const char *allowed, StageEvent *ev, char *err,
                     size_t errlen);
const char *stage_event_name(EventKind k);


#endif
