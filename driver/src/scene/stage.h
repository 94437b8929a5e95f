/* The scene layer: what every scene kind's stage is (FE and indentation stages, point segments), read in one place
 * below the stepping (app -> stepping -> contact -> {fe, point} -> scene -> material -> io).
 *
 * A stage: a name, a duration, its loads reached linearly at the end or at once ('load: instant': the targets
 * jump in a first zero-time step, then are held), how it is divided into steps ('steps'), an optional end event
 * ('until'), a creep flag for the plots, and stage times at which the fields are written ('output: {times}'). The
 * loads themselves are each kind's (pressures and tractions, the indenter, a point's controls), read by the kind
 * into arrays of its own beside the stages.
 *
 * Steps. Fixed: a count (equal, or growing geometrically). Adaptive: the length follows an error measure chosen by
 * the scene (steps.error), within [min, max] and growing at most by 'growth':
 *   worst_point  the UMAT's own control (PNEWDT with PROPS tol, Abaqus CETOL-like): the worst point rules;
 *   volume       the volume-weighted norm of the change of the viscoplastic strain rate over the step, at every
 *                point (the same local estimate as CETOL: dt |rate_end - rate_start|), relative to the volume norm
 *                of the step's viscoplastic strain increment;
 *   output       the difference between the step's converged increment of what the scene reports (the indenter
 *                depth; the volume-mean strain; a point's strain and stress) and its linear extrapolation from the
 *                previous step (the predictor-corrector estimate of a first-order method), relative to the
 *                increment itself.
 * The relative measures bound the error per unit of change: the accumulated error of an output is about tol times
 * its change, so halving tol halves the error (first order). How the steps follow: stepping/step_control.h. */
#ifndef SCENE_STAGE_H
#define SCENE_STAGE_H

#include "../io/yaml_doc.h"

typedef enum { MEASURE_WORST_POINT, MEASURE_VOLUME, MEASURE_OUTPUT } ErrorMeasure;

typedef struct {
  int          adaptive, count;
  double       ratio;                   /* fixed steps: dt_{k+1} = ratio dt_k (1: equal steps) */
  double       first, min, max, growth; /* adaptive steps */
  ErrorMeasure measure;
  double       tol;                     /* <= 0 with worst_point: PROPS tol as the material gives it */
  int          per_stage;               /* output: relative to the larger of the step's increment and its share of the
                                           stage's mean change so far (relative_to: stage), not the increment alone */
  double       floor;                   /* output: the increment measured against at least floor times the stage's
                                           change so far (error.floor, default 0: an ODE solver's absolute tolerance) */
} StepControl;

/* End events ('until'). Rising events (ABOVE, DEPTH, LOAD) and Q_BELOW are landed on: a step that overshoots is
 * redone shorter (secant), so the stage ends within EVENT_TOL of the value. EVP_RATE_BELOW ends the stage after the
 * first step whose volume-mean viscoplastic strain rate is below the value. */
typedef enum { EVENT_NONE, EVENT_EVP_RATE_BELOW, EVENT_Q_ABOVE, EVENT_Q_BELOW, EVENT_P_ABOVE, EVENT_DEPTH, EVENT_LOAD, EVENT_KINDS } EventKind;
#define EVENT_TOL 1e-5

typedef struct {
  EventKind kind;
  double    value;
} StageEvent;

#define STAGE_MAX_OUT_TIMES 64
#define MAXSTAGES 16 /* an FE scene's stages at most */

/* The stage of every scene kind. */
typedef struct {
  char        name[64];
  double      duration;
  int         instant;    /* load: instant */
  int         creep;      /* a creep stage (the plots' time origin) */
  StepControl steps;
  StageEvent  until;      /* kind NONE: none */
  int         nout_times; /* fields at exactly these stage times (output: {times: [...]}) */
  double      out_times[STAGE_MAX_OUT_TIMES];
} Stage;

/* Stage 'index' of a scene at node (a mapping), key path 'path' ("stages[2]"); default name word+index ("stage2",
 * "segment2"); events: the until kinds this scene kind allows (stage_event_read). Each key by its declaration
 * (scene/scene_keys.c: its type, range, choices and default); 'output' only where the scene kind declares it (a
 * point segment's is refused as a key of FE scenes). 0, or 1 with err filled. */
int stage_read(const YdDoc *doc, YdNode *node, const char *path, int index, const char *word, const char *events, Stage *st,
               char *err, size_t errlen);

/* steps: {count: N, spacing: linear | geometric, ratio: r}
 *    or  {adaptive: true, first, min, max, growth, error: {measure: worst_point | volume | output, tol}}.
 * node may be NULL (one step). Returns 0, or 1 with err naming file, line and key. */
int step_control_read(const YdDoc *doc, YdNode *node, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen);
const char *step_control_measure_name(ErrorMeasure m);

/* Read 'until: {KIND: value}' (one key of the allowed ones: a subset of evp_rate_below, q_above, q_below, p_above,
 * depth, load, comma separated). node may be NULL. */
int stage_event_read(const YdDoc *doc, YdNode *node, const char *path, const char *allowed, StageEvent *ev, char *err,
                     size_t errlen);
const char *stage_event_name(EventKind k);

#endif
