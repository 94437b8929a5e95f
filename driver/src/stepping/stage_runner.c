#include "stage_runner.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "checkpoint.h"

/* ---------------------------------------------------------------------------------------------------- */
/* Events                                                                                               */

/* +1: the event is reached from below; -1: from above; 0: not a landing event. */
static int event_direction(EventKind k) {
  return k == EVENT_Q_BELOW ? -1 : (k == EVENT_Q_ABOVE || k == EVENT_P_ABOVE || k == EVENT_DEPTH || k == EVENT_LOAD);
}

/* ---------------------------------------------------------------------------------------------------- */
/* The run                                                                                              */

/* A callback of the solver: on an error, return from the calling function with the run's status. */
#define SOLVER_CALL(call) \
  do { \
    PetscErrorCode ierr_ = (call); \
    if (ierr_) return stage_runner_status(ierr_, err); \
  } while (0)

typedef struct {
  StepSolver          *sv;
  const RunnerOptions *opt;
  RunState             st;
  HistoryFile          hist;
  int                  rank, promoted, last_ckpt;
  struct timespec      w0;
  double               stage_wall0;
  StageView            view;
  StepGains            gains; /* the step controller's exponents: the options', or the PI default */
} Run;

void stage_view_of(const Stage *g, StageView *v) {
  memset(v, 0, sizeof *v);
  v->name = g->name, v->duration = g->duration, v->instant = g->instant, v->steps = &g->steps, v->until = g->until;
  v->nout_times = g->nout_times, v->out_times = g->out_times;
}

static double wall_since(const struct timespec *w0) {
  struct timespec w;
  clock_gettime(CLOCK_MONOTONIC, &w);
  return (double)(w.tv_sec - w0->tv_sec) + 1e-9 * (double)(w.tv_nsec - w0->tv_nsec);
}

/* The history (history_columns.h, HistoryFile), on rank 0 with an output directory. */
static int history_open(Run *r, char *err, size_t errlen) {
  const char *dir = r->opt->outdir;
  if (r->rank || !dir || !dir[0]) return 0;
  return history_file_open(&r->hist, dir, r->opt->restart, r->st.history_offset, r->sv->columns, r->sv->ncolumns, r->sv->ctx, err,
                           errlen);
}

/* The first valid output: the new files replace the earlier run's. */
static int promote(Run *r) {
  if (r->promoted || r->opt->restart) return 0;
  r->promoted = 1;
  if (history_file_promote(&r->hist, r->opt->outdir)) return 1;
  if (!r->rank && r->opt->part_file) {
    char final[1024];
    snprintf(final, sizeof final, "%s", r->opt->part_file);
    char *dot = strstr(final, ".part"); /* mesh.part.msh -> mesh.msh */
    if (dot) {
      memmove(dot, dot + 5, strlen(dot + 5) + 1);
      if (rename(r->opt->part_file, final)) return 1;
    }
  }
  return r->sv->promote && r->sv->promote(r->sv->ctx);
}

static int history_row(Run *r, int its, double dt, int cut, char *err, size_t errlen) {
  const StepSolver *sv = r->sv;
  if (!r->hist.fp) return 0;
  const char *name = r->view.name ? r->view.name : sv->stage_name ? sv->stage_name(sv->ctx, r->st.stage) : NULL;
  RunnerRow   row  = {r->st.t, dt, wall_since(&r->w0), r->st.stage, r->st.step, its, cut, name};
  if (sv->history_prepare) sv->history_prepare(sv->ctx);
  return history_file_row(&r->hist, sv->columns, sv->ncolumns, sv->ctx, &row, err, errlen);
}

static int progress_line(Run *r, const StepOutcome *o, double h, char *err) {
  const RunnerOptions *opt = r->opt;
  if (r->rank || opt->quiet || (opt->progress_every > 1 && r->st.step % opt->progress_every)) return 0;
  double frac = o->progress >= 0 ? o->progress : r->view.duration > 0 ? r->st.t_stage / r->view.duration : 1;
  frac        = fmin(fmax(frac, 0), 1);
  double wall = wall_since(&r->w0), spent = wall - r->stage_wall0;
  char   left[64] = "", part[256] = "";
  if (frac >= 0.02 && frac < 1 && spent > 0.2) snprintf(left, sizeof left, ", about %.0f s left", spent * (1 - frac) / frac);
  if (r->sv->progress) SOLVER_CALL(r->sv->progress(r->sv->ctx, part, sizeof part));
  printf("step %5d  %-8s t = %-11.5g dt = %-10.4g newton %2d  %s cutbacks %d  wall %7.2f s  stage %3.0f%%%s%s\n",
         r->st.step, r->view.name, r->st.t, h, o->its, part, r->st.cutbacks, wall, 100 * frac, left,
         r->view.until.kind == EVENT_EVP_RATE_BELOW ? " (or less: it ends at steady state)" : "");
  fflush(stdout);
  return 0;
}

/* A step's increment d less the previous increment d_prev scaled to its length: (h (h + h_prev)/2) y'' + O(h^3), the
 * second difference both the 'output' measure (error_ratio) and the stated time-step error (time_error_step) read. */
static double departure(double d, double d_prev, double h, double h_prev) { return d - h / h_prev * d_prev; }

/* The error estimate of a converged step relative to tol ('output', 'volume'), or -1 when there is none
 * (worst_point, fixed steps, the first step of a stage, an instant step, a solver that reports no outputs).
 * 'output' relative to the step: the departure over the step's increment, so the stage's accumulated error is about
 * tol times its total change (docs/driver.md, Error measures). Relative to the stage (relative_to: stage): over the
 * larger of the increment and the step's share of the stage's mean change so far, h |y - y_start| / (t - t_start):
 * a step whose increment is small against the stage's mean rate (the tail of a transient, an exponential load's
 * start) is asked for tol of that share, not of its own small increment: a share of the stage's change in
 * proportion to the step's length. The floor (error.floor f): over at least f |y - y_start|, an absolute tolerance
 * (docs/driver.md, Error measures). *size tells a jump apart (judge): for 'output' the departure itself over the
 * outputs' scale, which falls as h (h + h_prev) where the answer is smooth and stays that of the jump where it
 * jumps (the ratio, relative to the increment, tends to h_prev y''/(2 y') as h goes to 0); for 'volume' the ratio. */
static double error_ratio(Run *r, const StepOutcome *o, const StepRequest *rq, double *size) {
  const StepControl *sc = r->view.steps;
  RunState          *st = &r->st;
  *size = -1;
  if (!sc->adaptive || sc->measure == MEASURE_WORST_POINT || rq->h == 0) return -1;
  if (sc->measure == MEASURE_VOLUME) return rq->first_in_stage || o->vol_err < 0 ? -1 : (*size = o->vol_err / sc->tol);
  if (rq->first_in_stage || !st->have_prev || o->nout <= 0 || st->nout != o->nout || st->h_prev <= 0) return -1;
  double worst = 0, worst_size = 0;
  for (int g = 0; g <= o->group[o->nout - 1]; g++) {
    double num = 0, den = 0, scale = 0;
    for (int k = 0; k < o->nout; k++)
      if (o->group[k] == g) {
        double d = o->out[k] - st->out_prev[k], s = 0;
        double c = sc->floor * (o->out[k] - st->out_start[k]); /* the floor: a share of the stage's change so far */
        if (sc->per_stage) s = rq->h * (o->out[k] - st->out_start[k]) / (rq->ts0 + rq->h);
        num += pow(departure(d, st->dout_prev[k], rq->h, st->h_prev), 2), den += fmax(fmax(d * d, s * s), c * c);
        scale += fmax(st->out_scale[k] * st->out_scale[k], o->out[k] * o->out[k]);
      }
    double e   = sqrt(num) / fmax(fmax(sqrt(den), 1e-6 * sqrt(scale)), 1e-300);
    worst      = fmax(worst, e);
    worst_size = fmax(worst_size, sqrt(num) / fmax(sqrt(scale), 1e-300));
  }
  *size = worst_size;
  return worst / sc->tol;
}

/* RunState.kink: what the last accepted step crossed. A kink of the rate (a contact node came or went): the next
 * step's estimate starts from this step's increment. A jump of the value (a step accepted because shorter ones did
 * not lower its estimate: a snap at a limit point of the load's path): its increment predicts nothing, so the
 * estimates start afresh from the next step's increment, as after a stage's first step. */
enum { KINK_NONE, KINK_RATE, KINK_JUMP };
#define JUMP_SHARE 0.5 /* a jump's departure from the extrapolation: at least this share of the step's increment */
#define KINK_CUT 0.5   /* the next step after a kink: at least this share of it (after_accept) */

static void remember_output(Run *r, const StepOutcome *o, const StepRequest *rq) {
  RunState *st = &r->st;
  int       same = st->have_prev && st->nout == o->nout, fresh = rq->first_in_stage || st->kink;
  for (int k = 0; k < o->nout && k < STEP_MAX_OUT; k++) {
    if (rq->first_in_stage) st->out_start[k] = st->out_prev[k]; /* before the stage's first step */
    st->dout_prev[k] = same || fresh ? o->out[k] - st->out_prev[k] : 0;
    st->out_prev[k]  = o->out[k];
    st->out_scale[k] = fmax(st->out_scale[k], fabs(o->out[k]));
  }
  /* The stage's first step may hold a jump of the load (an exp load from P0, an instant load): its increment
     predicts nothing, so the estimate starts from the second step's increment, at the third. */
  st->have_prev = rq->h > 0 && (same || fresh) && !rq->first_in_stage && st->kink != KINK_JUMP;
  st->kink      = rq->first_in_stage || st->kink == KINK_JUMP ? KINK_RATE : KINK_NONE; /* the next increment starts afresh */
  st->nout      = o->nout;
  st->h_prev    = rq->h;
}

/* The length of the next step: the plan (fixed steps, resumed after a cutback once the planned step is
 * done), or the controller (adaptive), then shortened to land on an output time. */
static double next_length(Run *r, const StepRequest *rq, const StepOutcome *o, double ratio) {
  const StepControl *sc = r->view.steps;
  RunState          *st = &r->st;
  double             dt;
  if (sc->adaptive) dt = step_control_next(sc, &r->gains, rq->h, o->pnewdt, ratio, st->ratio_prev);
  else if (st->cut_in_plan) {
    double planned_end = 0;
    for (int k = 0; k <= st->k_planned; k++) planned_end += step_control_planned(sc, r->view.duration, k);
    if (st->t_stage >= planned_end * (1 - 1e-12)) {
      st->k_planned++, st->cut_in_plan = 0;
      dt = step_control_planned(sc, r->view.duration, st->k_planned);
    } else dt = fmin(2 * rq->h, planned_end - st->t_stage);
  } else dt = step_control_planned(sc, r->view.duration, ++st->k_planned);
  return dt;
}

/* The step to try: the planned length, cut to the stage's end, an event landing or an output time. */
static void plan_step(Run *r, StepRequest *rq, int *at_output) {
  RunState *st  = &r->st;
  double    dur = r->view.duration;
  memset(rq, 0, sizeof *rq);
  rq->s = st->stage, rq->t0 = st->t, rq->ts0 = st->t_stage, rq->first_in_stage = st->first_in_stage, rq->h_prev = st->h_prev;
  *at_output = 0;
  if (st->pending_instant) rq->h = 0;
  else {
    double h = st->landing > 0 ? st->landing : fmin(st->dt, dur - st->t_stage);
    if (dur - st->t_stage - h < 1e-9 * dur) h = dur - st->t_stage; /* no sliver at the stage's end */
    const StageView *v = &r->view; /* the stage's output times, in stage time */
    while (st->next_stage_time < v->nout_times && v->out_times[st->next_stage_time] <= st->t_stage * (1 + 1e-14)) st->next_stage_time++;
    if (st->next_stage_time < v->nout_times && st->t_stage + h >= v->out_times[st->next_stage_time] * (1 - 1e-12))
      h = v->out_times[st->next_stage_time] - st->t_stage, *at_output = 1;
    rq->h = h;
  }
  rq->lambda = r->view.instant || dur == 0 ? 1 : fmin((st->t_stage + rq->h) / dur, 1);
  const StepControl *sc = r->view.steps;
  if (!sc->adaptive) rq->umat = umat_control(UMAT_CONTROL_AS_GIVEN, 0); /* fixed steps: the material as given */
  else if (sc->measure != MEASURE_WORST_POINT) rq->umat = umat_control(UMAT_CONTROL_OFF, 0);
  else rq->umat = sc->tol > 0 ? umat_control(UMAT_CONTROL_AT, sc->tol) : umat_control(UMAT_CONTROL_AS_GIVEN, 0);
  rq->want_volume_error = sc->adaptive && sc->measure == MEASURE_VOLUME;
  rq->newton_etol       = sc->adaptive && sc->measure != MEASURE_WORST_POINT && sc->tol > 0 ? NEWTON_KAPPA * sc->tol : 0;
}

enum { STEP_ACCEPTED, STEP_RETRY, STEP_FAILED };

/* For run-time messages: the scene file and the name of its list of stages. */
static const char *scene_file(const Run *r) { return r->opt->scene_file ? r->opt->scene_file : "(scene)"; }
static const char *stage_list(const Run *r) { return r->sv->kind && !strcmp(r->sv->kind, "point") ? "segments" : "stages"; }

/* Judge a solved step: cut back (failure, the UMAT's PNEWDT, the error measure), land on an event, or
 * accept. */
static int judge(Run *r, const StepRequest *rq, const StepOutcome *o, double *ratio, double *kink_ratio, int *landed, char *err,
                 size_t errlen) {
  RunState          *st = &r->st;
  const StepControl *sc = r->view.steps;
  double size = -1; /* the estimate's size (error_ratio) */
  *landed = 0, *ratio = -1, *kink_ratio = -1;
  /* A step whose Newton method made no iteration (the predictor met the tolerance) is the extrapolation
     itself: its estimate would be zero whatever the error, so it gets none. A step across a kink (a contact
     node came or went) mixes the jump of the rate into its estimate: it is not rejected on it, but the estimate
     may hold the next step's length (after_accept). */
  if (o->converged && !o->kink && o->its > 0) *ratio = error_ratio(r, o, rq, &size);
  if (o->converged && o->kink && o->its > 0) *kink_ratio = error_ratio(r, o, rq, &size);
  if (o->converged && o->kink) st->kink = KINK_RATE;
  /* A rejected step redone shorter (by 0.5 or less) whose estimate did not fall by half: accept it. It holds a jump
     (of the load, of the answer at a limit point of the load's path) if the estimate's size (error_ratio) did not
     halve either and the departure is at least JUMP_SHARE of the increment: then the estimates restart after it
     (KINK_JUMP). Otherwise the estimate is mostly the previous step's, which was long for the rate now (the ratio
     tends to h_prev y''/(2 y')), or the solver's noise on a small increment: the next step is estimated from this
     one's increment, as after a kink of the rate. */
  int jump = 0;
  if (*ratio > 1 && st->reject_ratio > 0 && *ratio > 0.5 * st->reject_ratio) {
    jump = st->reject_size > 0 && size > 0.5 * st->reject_size && *ratio * sc->tol >= JUMP_SHARE;
    if (!jump) st->kink = KINK_RATE;
    *ratio = -1;
  }
  int error_cut = *ratio > 1 && rq->h > sc->min * (1 + 1e-9); /* a step of min is accepted as it is */
  if (!o->converged || o->pnewdt < 1 || error_cut) {
    double h_cut = step_control_cut(sc, rq->h, !o->converged, o->pnewdt, *ratio);
    st->cutbacks++, st->cut_in_step++;
    if (error_cut && o->converged && o->pnewdt >= 1) st->rejected_error++, st->reject_ratio = *ratio, st->reject_size = size;
    if (!o->converged) o->stalled ? st->rejected_stalled++ : st->rejected_unconverged++;
    else if (o->pnewdt < 1) st->rejected_umat++;
    st->ratio_prev = -1;
    if (rq->h == 0 || st->cut_in_step > STEP_MAX_CUTBACKS || (sc->adaptive && h_cut < sc->min * (1 - 1e-12))) {
      snprintf(err, errlen, "%s: %s[%d] (stage '%s'): step failed for good at t = %.6g s (dt = %.3g s): %s", scene_file(r),
               stage_list(r), st->stage, r->view.name, st->t, rq->h,
               !o->converged ? (o->why ? o->why : "not converged")
               : o->pnewdt < 1 ? "the UMAT asked for a smaller step" : "the time-step error stays above its tolerance");
      return STEP_FAILED;
    }
    st->dt = h_cut, st->landing = 0, st->cut_in_plan = !sc->adaptive;
    return STEP_RETRY;
  }
  int dir = event_direction(r->view.until.kind);
  if (dir && rq->h > 0) {
    double v = o->event[r->view.until.kind], target = r->view.until.value, scale = fmax(fabs(target), 1e-300);
    double d = dir * (v - target) / scale;
    if (d > EVENT_TOL) { /* overshot: redo the step shorter, by the secant through the step's start */
      double frac = (target - st->event_prev) / (v - st->event_prev);
      st->landing = rq->h * fmin(fmax(isfinite(frac) ? frac : 0.5, 0.01), 0.999);
      return STEP_RETRY;
    }
    *landed = d >= -EVENT_TOL;
  }
  if (jump) st->kink = KINK_JUMP, st->jumps++;
  return STEP_ACCEPTED;
}

/* After an accepted step: the next length, and a landing on the event if it falls within it. */
static void after_accept(Run *r, const StepRequest *rq, const StepOutcome *o, double ratio, double kink_ratio) {
  RunState *st = &r->st;
  if (st->pending_instant) st->pending_instant = 0, st->dt = step_control_planned(r->view.steps, r->view.duration, 0);
  else st->dt = next_length(r, rq, o, ratio);
  /* A step across a kink is not rejected on its estimate (a jump of the rate would cut every step where nodes keep
     entering contact), but its estimate sets the next step as any step's does, shortened by at most KINK_CUT. Where
     every step crosses a kink (a fine contact surface: each node's jump small, the estimate the answer's curvature),
     the estimate must still shorten the steps; held at their length instead, they grew past what the curvature
     asked for on an adapted 3D level and its creep depth came out low (docs/performance.md, "Time steps across
     contact kinks"; docs/driver.md, "Stages, steps and error control"). */
  if (kink_ratio >= 0 && r->view.steps->adaptive)
    st->dt = fmin(st->dt, fmax(step_control_next(r->view.steps, &r->gains, rq->h, o->pnewdt, kink_ratio, -1), KINK_CUT * rq->h));
  st->ratio_prev = ratio; /* the PI controller's memory: none across a kink, a rejection or a stage's start */
  st->landing = 0;
  int dir = event_direction(r->view.until.kind);
  if (dir && rq->h > 0) {
    double v = o->event[r->view.until.kind], target = r->view.until.value;
    if (dir * (v - st->event_prev) > 0) { /* moving toward the event: aim at it (secant) */
      double h_event = rq->h * (target - v) / (v - st->event_prev);
      if (h_event > 0 && h_event < st->dt) st->landing = h_event * (1 + 0.5 * EVENT_TOL);
    }
  }
  if (dir) st->event_prev = o->event[r->view.until.kind];
  remember_output(r, o, rq);
  st->first_in_stage = 0, st->cut_in_step = 0;
  /* a later rejection starts afresh, unless this step was the predictor itself (no Newton iteration): then
     the rejection before it still tells whether shorter steps lower the estimate */
  if (ratio >= 0 || o->its > 0) st->reject_ratio = st->reject_size = 0;
}

/* The scene's reported quantities at the start (k = 0) or at the end of stage k - 1, with the time-step error of
 * their change over a held stage (time_error_step). */
static void keep_report(Run *r, int k) {
  RunState *st = &r->st;
  if (!r->sv->report) return;
  for (int q = 0; q < r->sv->nreport && k <= RUNNER_MAX_STAGES; q++) st->terr_change[k][q] = k && r->view.held ? st->terr_stage[q] : NAN;
  for (int q = 0; q < r->sv->nreport; q++) st->terr_stage[q] = 0;
  if (k <= RUNNER_MAX_STAGES) r->sv->report(r->sv->ctx, st->report[k]);
  if (k == 0) memcpy(st->rep_prev, st->report[0], sizeof st->rep_prev); /* the first step's increment starts here */
}

/* The time-step error of the reported quantities after an accepted step (docs/adapt.md, "The time-step error").
 * Backward Euler's local error is -(h_n^2/2) y'' + O(h^3); the increment's departure from the previous one scaled
 * to this step is Delta_n - (h_n/h_{n-1}) Delta_{n-1} = (h_n (h_n + h_{n-1})/2) y'' + O(h^3), so the local error
 * is that departure times h_n/(h_n + h_{n-1}) (the same departure the 'output' measure controls, error_ratio).
 * The global error of a stable integration is at most the sum of the local ones: summed in absolute value over a
 * held stage, it estimates the error of the change over it (the creep depth). Where the loads change, the same
 * departure holds the curvature of the response to them (elastic, rate-independent), which is no time-step error:
 * no estimate there (StageView.held). A stage's first step (a kink of the rate) and an instant step predict
 * nothing: the estimate starts at the step after the next. A step accepted as a jump (KINK_JUMP) is no O(h^2)
 * error: it adds nothing, and the estimate starts afresh after it. */
static void time_error_step(Run *r, const StepRequest *rq) {
  RunState *st = &r->st;
  double    v[RUNNER_MAX_REPORT];
  if (!r->sv->report) return;
  r->sv->report(r->sv->ctx, v);
  int jump = st->kink == KINK_JUMP; /* no time-step error: shorter steps would not have lowered it */
  int have = st->rep_have_prev && !rq->first_in_stage && rq->h > 0 && st->rep_h_prev > 0 && !jump;
  for (int q = 0; q < r->sv->nreport; q++) {
    double d = v[q] - st->rep_prev[q];
    if (have) {
      double e = fabs(departure(d, st->drep_prev[q], rq->h, st->rep_h_prev)) * rq->h / (rq->h + st->rep_h_prev);
      st->terr_stage[q] += e;
    }
    st->drep_prev[q] = d, st->rep_prev[q] = v[q];
  }
  st->rep_have_prev = rq->h > 0 && !rq->first_in_stage && !jump;
  st->rep_h_prev    = rq->h;
}

static int write_fields(Run *r, int report, char *err, size_t errlen) {
  if (r->sv->write_fields) SOLVER_CALL(r->sv->write_fields(r->sv->ctx, r->st.t, report, err, errlen));
  return 0;
}

/* One stage from where the state says. Returns 0 (done), 1 (failed), 3 (stopped by -max_steps) or a PETSc error
 * code (> 3). */
static int run_stage(Run *r, char *err, size_t errlen) {
  StepSolver          *sv = r->sv;
  RunState            *st = &r->st;
  const RunnerOptions *opt = r->opt;
  int                  resumed = st->in_stage;
  SOLVER_CALL(sv->stage_begin(sv->ctx, st->stage, resumed, &r->view, err, errlen));
  if (!resumed) {
    st->t_stage = 0, st->k_planned = 0, st->cut_in_plan = 0, st->landing = 0, st->first_in_stage = 1, st->next_stage_time = 0;
    st->ratio_prev = -1;
    st->pending_instant = r->view.instant || r->view.duration == 0;
    st->dt              = step_control_planned(r->view.steps, r->view.duration, 0);
    st->event_prev      = r->view.event_start;
  }
  st->in_stage   = 1;
  r->stage_wall0 = wall_since(&r->w0);
  int landed = 0, rate_done = 0;
  while (st->pending_instant || (!landed && !rate_done && st->t_stage < r->view.duration * (1 - 1e-12))) {
    StepRequest rq;
    StepOutcome o;
    int         at_output;
    plan_step(r, &rq, &at_output);
    memset(&o, 0, sizeof o);
    o.pnewdt = 1e300, o.progress = -1, o.vol_err = -1;
    SOLVER_CALL(sv->solve(sv->ctx, &rq, &o, err, errlen));
    double ratio, kink_ratio;
    int    verdict = judge(r, &rq, &o, &ratio, &kink_ratio, &landed, err, errlen);
    if (verdict == STEP_FAILED) {
      /* the step's failure is the message; a replay that could not be written only adds to it */
      if (sv->replay && opt->outdir && opt->outdir[0] && sv->replay(sv->ctx, opt->outdir, err, errlen)) {
        size_t len = strlen(err);
        snprintf(err + len, errlen - len, " (a replay of the failing UMAT call could not be written)");
      }
      return 1;
    }
    if (verdict == STEP_RETRY) continue;
    int was_instant = st->pending_instant, cut = st->cut_in_step;
    SOLVER_CALL(sv->accept(sv->ctx, &rq, err, errlen));
    st->t += rq.h, st->t_stage += rq.h, st->step++, st->its += o.its;
    time_error_step(r, &rq);
    if (st->kink == KINK_JUMP && !r->rank && !opt->quiet)
      printf("step %d (stage '%s', t = %.9g s): accepted across a jump of the outputs: shorter steps did not lower its error "
             "estimate (a snap, not a time-step error); the estimates restart after it\n", st->step, r->view.name, st->t);
    after_accept(r, &rq, &o, ratio, kink_ratio);
    if (promote(r)) {
      snprintf(err, errlen, "%s: cannot rename the new output files into place", opt->outdir);
      return 1;
    }
    int rc = history_row(r, o.its, rq.h, cut, err, errlen);
    if (rc || (rc = progress_line(r, &o, rq.h, err))) return rc;
    if (sv->check) SOLVER_CALL(sv->check(sv->ctx, st->t, err, errlen));
    rate_done = !was_instant && r->view.until.kind == EVENT_EVP_RATE_BELOW && o.event[EVENT_EVP_RATE_BELOW] < r->view.until.value;
    int stage_done = landed || rate_done || (!st->pending_instant && st->t_stage >= r->view.duration * (1 - 1e-12));
    if (at_output || (opt->fields_every > 0 && st->step % opt->fields_every == 0) || stage_done)
      if ((rc = write_fields(r, at_output || stage_done, err, errlen))) return rc;
    if (stage_done && !landed && r->view.must_reach && r->view.until.kind != EVENT_NONE) {
      char key[128];
      if (r->view.until_key) snprintf(key, sizeof key, "%s", r->view.until_key);
      else snprintf(key, sizeof key, "%s[%d].until", stage_list(r), st->stage);
      snprintf(err, errlen, "%s: key '%s': stage '%s': %s = %g (until) was not reached by the stage's end (t = %g s): lengthen its "
               "duration (%s[%d].duration = %g s)", scene_file(r), key, r->view.name, stage_event_name(r->view.until.kind),
               r->view.until.value, st->t, stage_list(r), st->stage, r->view.duration);
      return 1;
    }
    if (stage_done) keep_report(r, st->stage + 1), st->stage++, st->in_stage = 0;
    if (opt->checkpoint_every > 0 && st->step % opt->checkpoint_every == 0) {
      if (r->hist.fp) fflush(r->hist.fp);
      st->history_offset = r->hist.fp ? ftell(r->hist.fp) : 0;
      if ((rc = checkpoint_write(sv, opt, &r->st, &r->last_ckpt, err, errlen))) return rc;
    }
    if (opt->max_steps >= 0 && st->step >= opt->max_steps) return (rc = write_fields(r, 0, err, errlen)) ? rc : 3; /* its last step's fields too */
    if (stage_done) return 0;
  }
  keep_report(r, st->stage + 1);
  st->stage++, st->in_stage = 0;
  return 0;
}

int stage_runner_run(StepSolver *sv, const RunnerOptions *opt, RunnerSummary *sum, char *err, size_t errlen) {
  Run r;
  memset(&r, 0, sizeof r);
  memset(sum, 0, sizeof *sum);
  r.sv = sv, r.opt = opt, r.last_ckpt = -1;
  r.gains = opt->gains.alpha > 0 ? opt->gains : STEP_GAINS_PI;
  MPI_Comm_rank(sv->comm, &r.rank);
  if (opt->checkpoint_every < 0) {
    snprintf(err, errlen, "-checkpoint_every %d: expected a number of steps >= 0 (0: no checkpoints)", opt->checkpoint_every);
    return 2;
  }
  if (opt->restart) { /* the history's layout first: reading the checkpoint resumes the solver's files (the fields) */
    int rc = !r.rank && opt->outdir && opt->outdir[0] ? history_file_check(opt->outdir, sv->columns, sv->ncolumns, sv->ctx, err, errlen) : 0;
    MPI_Bcast(&rc, 1, MPI_INT, 0, sv->comm); /* rank 0 holds the history: every rank stops with its message */
    MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, sv->comm);
    if (rc || (rc = checkpoint_read(sv, opt, &r.st, &r.last_ckpt, err, errlen))) return rc;
  }
  if (!opt->restart) r.st.mesh_hash = binfile_hash(opt->mesh_file);
  int rc = history_open(&r, err, errlen);
  MPI_Bcast(&rc, 1, MPI_INT, 0, sv->comm); /* as above */
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, sv->comm);
  if (rc) return rc;
  clock_gettime(CLOCK_MONOTONIC, &r.w0);
  if (!opt->restart) {
    r.view.name = NULL; /* row 0: the solver names it */
    keep_report(&r, 0);
    if (sv->outputs) sv->outputs(sv->ctx, r.st.out_prev); /* the first stage's start values (else 0) */
    if ((rc = history_row(&r, 0, 0, 0, err, errlen)) || (rc = write_fields(&r, 1, err, errlen))) return rc;
  }
  while (!rc && r.st.stage < sv->nstage) {
    rc = opt->max_steps >= 0 && r.st.step >= opt->max_steps ? 3 : run_stage(&r, err, errlen);
    if (rc == 3) {
      if (!r.rank && !opt->quiet) printf("stopped after %d steps (-max_steps)\n", r.st.step);
      sum->stopped = 1, rc = 0;
      break;
    }
  }
  if (r.hist.fp) fclose(r.hist.fp);
  long calls = sv->umat_calls ? sv->umat_calls(sv->ctx) : 0;
  MPI_Allreduce(&calls, &sum->umat_calls, 1, MPI_LONG, MPI_SUM, sv->comm);
  sum->steps = r.st.step, sum->cutbacks = r.st.cutbacks, sum->its = r.st.its, sum->rejected_error = r.st.rejected_error;
  sum->rejected_umat = r.st.rejected_umat, sum->rejected_stalled = r.st.rejected_stalled, sum->rejected_unconverged = r.st.rejected_unconverged;
  sum->jumps = r.st.jumps;
  sum->failed = rc != 0, sum->t = r.st.t, sum->wall = wall_since(&r.w0);
  sum->ran = 1, sum->replaced = r.promoted || opt->restart;
  sum->nreport = sv->report ? sv->nreport : 0, sum->nstages_done = PetscMin(r.st.stage, RUNNER_MAX_STAGES);
  for (int k = 0; k < sum->nreport; k++) sum->report_names[k] = sv->report_names[k];
  memcpy(sum->report, r.st.report, sizeof sum->report);
  memcpy(sum->time_error_change, r.st.terr_change, sizeof sum->time_error_change);
  if (opt->summary) *opt->summary = *sum;
  if (rc && err[0] && opt->outdir && opt->outdir[0] && !r.promoted && !opt->restart) {
    size_t len = strlen(err);
    snprintf(err + len, errlen - len, " (nothing of an earlier run in %s was replaced; this run's files end in .part)", opt->outdir);
  }
  return rc;
}
