/* The one stage runner (driver/src/stepping/stage_runner.c) driven by a mock StepSolver, as PETSc keeps a TEST
 * block beside each example: no mesh, no UMAT, a scalar "physics" whose answers are known in closed form.
 *
 * The mock: x' = -x/tau solved exactly over each step (x1 = x0 exp(-h/tau), so after any steps x(t) = x0
 * exp(-t/tau)), an event quantity q = t (linear in the total time: its crossing time is the target itself), an
 * error estimate it sets itself (the 'volume' measure: the runner's ratio is vol_err / tol) and a Newton failure
 * it reports on a chosen solve call. It records every solve's step, every accepted time and every fields time.
 *
 * Cases, and what each number is checked against:
 *  1 accept      10 equal steps over 1 s: 10 solves, 10 accepts, each 0.1, end at t = 1 exactly (==), x = x0 e^-1/tau
 *                (1e-14); then 4 geometric steps (ratio 2) over 1.5 s: 0.1, 0.2, 0.4, 0.8 (scene/stage.h's plan,
 *                first = T (r - 1)/(r^n - 1)).
 *  2 reject      adaptive (growth 1, estimate 0.1 tol): the 4th solve's estimate is 3 tol, so the step is redone
 *                at 0.9/3 = 0.3 of its length (step_control.h: STEP_SAFETY / ratio, within [0.1, 0.5]; docs/driver.md
 *                "Step controller"); 1 rejection, 1 cutback, no later step longer, end at t = 1 exactly.
 *  3 cutback     fixed 10 x 0.1 s, the 4th solve does not converge: redone at STEP_CUT_DIVERGED = 0.25 of it
 *                (0.025), the plan resumed by doubling to the planned step's end (0.025, 0.05, 0.025: next_length),
 *                then 0.1 again; the summary counts 1 cutback, 12 steps, end at t = 1, x = x0 e^-1/tau.
 *  4 event       until q_above 0.537 (fixed 0.1 s steps): the stage ends with |q - 0.537| <= EVENT_TOL 0.537
 *                (scene/stage.h, docs/driver.md "Events"), i.e. at t = 0.537 within that; the next stage's target
 *                0.03 later lies inside its first step, at 0.3 of it (not mid-step: an interpolation from the
 *                wrong end of the step, 0.7, would land there too): that step is redone by the secant (one solve
 *                more than accepts), its retried length 0.03 (q linear: the secant is exact), and lands on 0.567
 *                the same way; no cutback counted.
 *  5 output      output times 0.25, 0.5, 0.8 of a 1 s stage in 3 steps: write_fields at t = 0, 0.25, 0.5, 0.8, 1
 *                exactly (==), nothing else, each a report time; with output.fields_every 1 over 10 steps and the
 *                output time 0.25: 12 writes, of which t = 0, 0.25 and 1 alone are report times.
 *  6 checkpoint  an adaptive two-stage run (the 'output' measure on x, then the mock's estimate varying in time;
 *                the PI controller and the output measure both carry memory across steps): its steps in stage 0
 *                settle at the controller's fixed point h = tau ln(1 + tol 0.9^(1/0.85)) (1e-5); run once
 *                whole; once with -checkpoint_every 3 stopped by -max_steps 7; then restarted: the restart reads
 *                checkpoint.latest = step 6 and its accepted times, steps and x are those of the whole run from
 *                step 6 on, bit for bit.
 *  8 jump        x constant but for a jump J = 0.3 at t = 0.5 (a snap at a limit point: every step across it holds the
 *                whole jump, however short), the 'output' measure at tol 0.02: the step across it is accepted once a
 *                shorter one did not lower its estimate, and the step after it has no estimate (its predecessor's
 *                increment predicts nothing: docs/driver.md). Before, that step was measured against the jump and
 *                cut to min (the run failed: "the time-step error stays above its tolerance"). Checked: the run
 *                ends at t = 1 exactly, x = x0 + J (1e-12), one accepted step holds the jump and the summary counts
 *                one jump, every step after it is accepted at its first try (x is constant there: the extrapolation
 *                is exact, so no cutback), and the
 *                stated time-step error of x's change over the (held) stage is below 1e-9 J (the jump is exact).
 *  9 floor     (error.floor, docs/driver.md "Error measures") x = x0 exp(-t/tau) + c/2 max(t - 0.7, 0)^2, tau 0.02 s: a
 *                decay that settles (the stage's change, -x0), then a quadratic onset whose increments are tiny against
 *                it; the 'output' measure at tol 0.02 with the floor 1e-3: in the onset, the steps settle at the PI
 *                controller's fixed point with the departure c h^2 relative to the floor 1e-3 |x - x0|,
 *                h = sqrt(tol 0.9^(1/0.85) 1e-3 |x - x0| / c) (1 %; x0 the solver's start value, StepSolver.outputs,
 *                not 0); without the floor the onset takes more than twice the steps (relative to its own increments).
 * 10 kinks     (docs/driver.md "Stages, steps and error control") the onset of case 9 without the floor, every step reported as crossing a kink (a node
 *                entering contact: StepOutcome.kink): no step is rejected on its estimate, but the estimate sets the next
 *                step's length, so in the onset the steps follow the curvature: the I controller (no memory across a kink)
 *                holds the ratio h_mean / (s + h/2) / tol at about STEP_SAFETY (s the step's start after the onset), i.e.
 *                h = 0.9 tol s within 5 %; held at their length instead (before), the steps kept the 0.05 s they had
 *                before the onset, 14 times that at t = 0.9.
 *  7 errors      (stage_runner.h, docs/driver.md "Error codes") a check that fails with STEP_FAIL after t = 0.45 (0.1 s
 *                steps): status 1, err exactly the callback's message, 5 steps accepted; a solve that fails with a PETSc
 *                error (PETSC_ERR_MEM) on its 3rd call: that code returned, err empty (main prints PETSc's message), 2
 *                steps accepted.
 * Exit 0 when every check holds. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stepping/stage_runner.h"

static int failures = 0;
#define CHECK(cond, ...)                                    \
  do {                                                      \
    if (!(cond)) {                                          \
      fprintf(stderr, "FAILED (%s): ", __func__);           \
      fprintf(stderr, __VA_ARGS__);                         \
      fprintf(stderr, "\n");                                \
      failures++;                                           \
    }                                                       \
  } while (0)

static int near(double a, double b, double rtol) { return fabs(a - b) <= rtol * fmax(fabs(b), 1e-300); }

/* ---------------------------------------------------------------------------------------------------- */
/* The mock solver                                                                                      */

#define MAXREC 512
typedef struct {
  Stage  stage[3];
  int    nstage;
  double tau, x0, x, x_trial, t; /* the committed state; t the mock's own clock (sum of accepted steps) */
  int    fail_solve;            /* this solve call (from 1) reports no convergence (0: none) */
  int    petsc_error_solve;     /* this solve call fails with a PETSc error (0: none) */
  double fail_after;            /* > 0: the check fails (STEP_FAIL) once t is past it */
  int    spike_solve;           /* this solve call's estimate is spike x tol */
  double t_jump, jump;          /* jump != 0: x jumps by it in the step across t_jump (a snap) */
  double t_onset, onset_c;      /* onset_c != 0: x(t) = x0 exp(-t/tau) + onset_c/2 max(t - t_onset, 0)^2 */
  int    naccept_late;          /* onset: accepted steps that end after t_onset */
  double h_probe, t_probe, x_probe; /* onset: the first accepted step that ends after t_probe, and x there */
  int    nsolve_after, naccept_after; /* solves and accepts of the steps that start after the jump */
  int    held;                  /* the stages are held (StageView.held): the runner states x's time-step error */
  int    kink_all;              /* every step crosses a kink (StepOutcome.kink) */
  double t_probe_end;           /* onset: where the probe's step ended */
  double spike, err_level;      /* otherwise err_level x tol, or ... */
  double err_coef;              /* ... when > 0: err_coef h (1 + 0.5 sin 5 t0), an estimate that varies */
  int    nsolve, naccept, nwrite;
  double stage_t0[3]; /* the time each stage began at */
  double solve_h[MAXREC], accept_t[MAXREC], accept_h[MAXREC], write_t[MAXREC];
  int    write_report[MAXREC]; /* each fields time: one the run reports at (write_fields' report) */
} Mock;

static void mock_init(Mock *m) {
  memset(m, 0, sizeof *m);
  m->tau = 2.0, m->x0 = m->x = 3.0;
}

static PetscErrorCode stage_begin(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen) {
  Mock *m = ctx;
  stage_view_of(&m->stage[s], v);
  if (m->held) v->held = 1;
  v->event_start = m->t; /* q = t */
  m->stage_t0[s] = m->t;
  return 0;
}

/* The onset case's answer in closed form: a decay that settles, then a quadratic onset (x'' = onset_c). */
static double onset_x(const Mock *m, double t) {
  double s = fmax(t - m->t_onset, 0);
  return m->x0 * exp(-t / m->tau) + 0.5 * m->onset_c * s * s;
}

static PetscErrorCode solve(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen) {
  Mock *m = ctx;
  int   call = ++m->nsolve;
  PetscFunctionBeginUser;
  if (call <= MAXREC) m->solve_h[call - 1] = rq->h;
  PetscCheck(call != m->petsc_error_solve, PETSC_COMM_SELF, PETSC_ERR_MEM, "mock: a PETSc error on purpose");
  m->x_trial   = m->x * exp(-rq->h / m->tau);
  if (m->jump != 0 && m->t < m->t_jump && m->t + rq->h >= m->t_jump) m->x_trial += m->jump;
  if (m->jump != 0 && m->t >= m->t_jump) m->nsolve_after++;
  if (m->onset_c != 0) m->x_trial = onset_x(m, m->t + rq->h);
  o->converged = call != m->fail_solve;
  o->why       = "mock: not converged on purpose";
  o->its       = 1;
  o->kink      = m->kink_all;
  o->event[EVENT_Q_ABOVE] = rq->t0 + rq->h;
  o->nout = 1, o->out[0] = m->x_trial, o->group[0] = 0; /* the 'output' measure's estimate: the runner's own */
  if (rq->want_volume_error) {
    double tol = m->stage[rq->s].steps.tol;
    o->vol_err = m->err_coef > 0 ? m->err_coef * rq->h * (1 + 0.5 * sin(5 * rq->t0)) : m->err_level * tol;
    if (call == m->spike_solve) o->vol_err = m->spike * tol;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode accept(void *ctx, const StepRequest *rq, char *err, size_t errlen) {
  Mock *m = ctx;
  if (m->jump != 0 && m->t >= m->t_jump) m->naccept_after++;
  m->x = m->x_trial, m->t += rq->h;
  if (m->onset_c != 0 && m->t > m->t_onset) m->naccept_late++;
  if (m->onset_c != 0 && m->t > m->t_probe && m->h_probe == 0) m->h_probe = rq->h, m->x_probe = m->x, m->t_probe_end = m->t;
  if (m->naccept < MAXREC) m->accept_t[m->naccept] = m->t, m->accept_h[m->naccept] = rq->h;
  m->naccept++;
  return 0;
}

/* A failure the user must act on, past this time (the stage runner's STEP_FAIL). */
static PetscErrorCode check(void *ctx, double t, char *err, size_t errlen) {
  Mock *m = ctx;
  PetscFunctionBeginUser;
  if (m->fail_after > 0 && t > m->fail_after) STEP_FAIL(err, errlen, "mock.yaml: key 'limit': t = %g is past the limit %g", t, m->fail_after);
  PetscFunctionReturn(0);
}

static PetscErrorCode write_fields(void *ctx, double t, int report, char *err, size_t errlen) {
  Mock *m = ctx;
  if (m->nwrite < MAXREC) m->write_t[m->nwrite] = t, m->write_report[m->nwrite] = report;
  m->nwrite++;
  return 0;
}

static HistValue        x_value(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const Mock *)ctx)->x}; }
static const HistColumn columns[] = {{"x", "%.17g", 1, NULL, x_value, NULL, NULL}};

/* The checkpoint holds the physics' state only: what the runner must restore is its own business. A write or
   read that fails leaves f->ok 0. */
static PetscErrorCode save(void *ctx, BinFile *f) {
  Mock *m = ctx;
  binfile_write(f, &m->x, sizeof m->x, 1);
  binfile_write(f, &m->t, sizeof m->t, 1);
  return 0;
}
static PetscErrorCode load(void *ctx, BinFile *f) {
  Mock *m = ctx;
  binfile_read(f, &m->x, sizeof m->x, 1);
  binfile_read(f, &m->t, sizeof m->t, 1);
  return 0;
}

static void report_x(void *ctx, double *v) { v[0] = ((const Mock *)ctx)->x; }
static void outputs_x(void *ctx, double *out) { out[0] = ((const Mock *)ctx)->x; } /* x0 at the start, not 0 */

static StepSolver mock_solver(Mock *m) {
  return (StepSolver){.ctx = m, .kind = "mock", .nstage = m->nstage, .comm = PETSC_COMM_SELF, .stage_begin = stage_begin,
                      .solve = solve, .accept = accept, .check = check, .columns = columns, .ncolumns = 1,
                      .write_fields = write_fields, .save = save, .load = load, .nreport = 1, .report = report_x, .outputs = outputs_x,
                      .report_names = {"x"}};
}

static Stage fixed_stage(double duration, int count, double ratio) {
  Stage g;
  memset(&g, 0, sizeof g);
  snprintf(g.name, sizeof g.name, "fixed");
  g.duration = duration, g.steps.count = count, g.steps.ratio = ratio;
  return g;
}

static Stage adaptive_stage(double duration, double first, double growth, double max, ErrorMeasure measure, double tol) {
  Stage g;
  memset(&g, 0, sizeof g);
  snprintf(g.name, sizeof g.name, "adaptive");
  g.duration = duration, g.steps.adaptive = 1, g.steps.first = first, g.steps.min = 1e-6, g.steps.max = max;
  g.steps.growth = growth, g.steps.measure = measure, g.steps.tol = tol;
  return g;
}

static RunnerOptions quiet_options(void) {
  RunnerOptions opt;
  memset(&opt, 0, sizeof opt);
  opt.max_steps = -1, opt.quiet = 1, opt.outdir = "";
  return opt;
}

static int run(Mock *m, const RunnerOptions *opt, RunnerSummary *sum) {
  StepSolver sv = mock_solver(m);
  char       err[2048] = "";
  int        rc = stage_runner_run(&sv, opt, sum, err, sizeof err);
  CHECK(rc == 0, "stage_runner_run returned %d: %s", rc, err);
  return rc;
}

/* A run without files or progress. */
static int run_quiet(Mock *m, RunnerSummary *sum) {
  RunnerOptions opt = quiet_options();
  return run(m, &opt, sum);
}

/* The run ended at t = T exactly: the runner's clock and the mock's (the sum of the accepted steps). */
static void check_end_exactly(const char *name, const Mock *m, const RunnerSummary *sum, double T) {
  CHECK(sum->t == T && m->t == T, "%s: end at t = %.17g (runner), %.17g (accepted steps), expected %g exactly", name, sum->t, m->t, T);
}

/* ---------------------------------------------------------------------------------------------------- */
/* The cases                                                                                            */

static void case_accept(void) {
  Mock          m;
  RunnerSummary sum;
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 10, 1);
  if (run_quiet(&m, &sum)) return;
  CHECK(m.nsolve == 10 && m.naccept == 10 && sum.steps == 10 && sum.cutbacks == 0, "solves %d, accepts %d, steps %d, cutbacks %d (expected 10, 10, 10, 0)",
        m.nsolve, m.naccept, sum.steps, sum.cutbacks);
  for (int k = 0; k < m.naccept && k < 10; k++) CHECK(near(m.accept_h[k], 0.1, 1e-14), "step %d: h = %.17g, expected 0.1", k, m.accept_h[k]);
  check_end_exactly(__func__, &m, &sum, 1.0);
  CHECK(near(m.x, m.x0 * exp(-1.0 / m.tau), 1e-14), "x = %.17g, expected x0 exp(-t/tau) = %.17g", m.x, m.x0 * exp(-1.0 / m.tau));

  mock_init(&m); /* geometric: first = 1.5 (2 - 1)/(2^4 - 1) = 0.1 */
  m.nstage = 1, m.stage[0] = fixed_stage(1.5, 4, 2);
  if (run_quiet(&m, &sum)) return;
  const double want[4] = {0.1, 0.2, 0.4, 0.8};
  CHECK(m.naccept == 4, "geometric: %d steps, expected 4", m.naccept);
  for (int k = 0; k < m.naccept && k < 4; k++) CHECK(near(m.accept_h[k], want[k], 1e-14), "geometric step %d: h = %.17g, expected %g", k, m.accept_h[k], want[k]);
  CHECK(near(sum.t, 1.5, 1e-15), "geometric: end at t = %.17g, expected 1.5", sum.t);
}

static void case_reject(void) {
  Mock          m;
  RunnerSummary sum;
  mock_init(&m);
  m.nstage = 1, m.stage[0] = adaptive_stage(1.0, 0.1, 1.0, 1.0, MEASURE_VOLUME, 0.1);
  m.err_level = 0.1, m.spike_solve = 4, m.spike = 3;
  if (run_quiet(&m, &sum)) return;
  /* step_control_cut: STEP_SAFETY / ratio within [0.1, 0.5], with STEP_SAFETY the documented 0.9 */
  CHECK(STEP_SAFETY == 0.9 && m.nsolve >= 5, "STEP_SAFETY %g (docs/driver.md: 0.9), %d solves", STEP_SAFETY, m.nsolve);
  CHECK(near(m.solve_h[3], 0.1, 1e-14), "the rejected step: h = %.17g, expected 0.1", m.solve_h[3]);
  CHECK(near(m.solve_h[4], 0.3 * 0.1, 1e-14), "the retried step: h = %.17g, expected 0.9/3 x 0.1 = 0.03", m.solve_h[4]);
  CHECK(sum.rejected_error == 1 && sum.cutbacks == 1, "rejected %d, cutbacks %d (expected 1, 1)", sum.rejected_error, sum.cutbacks);
  CHECK(m.naccept == m.nsolve - 1, "accepts %d, solves %d: one solve is the rejected one", m.naccept, m.nsolve);
  for (int k = 3; k < m.naccept; k++) CHECK(m.accept_h[k] <= 0.03 * (1 + 1e-12), "step %d after the rejection: h = %g > 0.03 (growth 1)", k, m.accept_h[k]);
  check_end_exactly(__func__, &m, &sum, 1.0);
}

static void case_cutback(void) {
  Mock          m;
  RunnerSummary sum;
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 10, 1);
  m.fail_solve = 4;
  if (run_quiet(&m, &sum)) return;
  CHECK(STEP_CUT_DIVERGED == 0.25, "STEP_CUT_DIVERGED %g, the documented 0.25", STEP_CUT_DIVERGED);
  CHECK(m.nsolve == 13 && m.naccept == 12 && sum.steps == 12, "solves %d, accepts %d, steps %d (expected 13, 12, 12)", m.nsolve, m.naccept, sum.steps);
  CHECK(near(m.solve_h[3], 0.1, 1e-14) && near(m.solve_h[4], 0.025, 1e-14), "failed step h = %.17g, retried h = %.17g (expected 0.1, 0.025)",
        m.solve_h[3], m.solve_h[4]);
  const double want[12] = {0.1, 0.1, 0.1, 0.025, 0.05, 0.025, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1};
  for (int k = 0; k < m.naccept && k < 12; k++) CHECK(fabs(m.accept_h[k] - want[k]) <= 1e-15, "step %d: h = %.17g, expected %g", k, m.accept_h[k], want[k]);
  CHECK(sum.cutbacks == 1 && sum.rejected_error == 0, "cutbacks %d, rejected by error %d (expected 1, 0)", sum.cutbacks, sum.rejected_error);
  check_end_exactly(__func__, &m, &sum, 1.0);
  CHECK(near(m.x, m.x0 * exp(-1.0 / m.tau), 1e-14), "x = %.17g, expected %.17g", m.x, m.x0 * exp(-1.0 / m.tau));
}

static void case_event(void) {
  Mock          m;
  RunnerSummary sum;
  const double  q1 = 0.537, q2 = 0.567;
  mock_init(&m);
  m.nstage   = 2;
  m.stage[0] = fixed_stage(1.0, 10, 1), m.stage[0].until = (StageEvent){EVENT_Q_ABOVE, q1};
  m.stage[1] = fixed_stage(1.0, 10, 1), m.stage[1].until = (StageEvent){EVENT_Q_ABOVE, q2};
  if (run_quiet(&m, &sum)) return;
  CHECK(m.naccept == 7, "%d steps, expected 7: 5 x 0.1 and the landing, then the redone first step of stage 1", m.naccept);
  double t1 = m.stage_t0[1], t2 = sum.t; /* q = t */
  printf("event: stage 0 ends at q - %g = %.3g, stage 1 at q - %g = %.3g (tolerance %g)\n", q1, t1 - q1, q2, t2 - q2, EVENT_TOL * q1);
  CHECK(fabs(t1 - q1) <= EVENT_TOL * q1, "stage 0 ended at q = %.17g, expected %g within %g", t1, q1, EVENT_TOL * q1);
  CHECK(fabs(t2 - q2) <= EVENT_TOL * q2, "stage 1 ended at q = %.17g, expected %g within %g", t2, q2, EVENT_TOL * q2);
  CHECK(near(m.accept_t[4], 0.5, 1e-14), "the step before the landing ended at %.17g, expected 0.5", m.accept_t[4]);
  CHECK(m.nsolve == m.naccept + 1 && near(m.solve_h[6], 0.1, 1e-14), "solves %d (expected %d: stage 1's first step of 0.1 (%g) overshoots, redone)",
        m.nsolve, m.naccept + 1, m.solve_h[6]);
  /* q = t is linear, so the secant through the step's start is exact: the retry is q2 - q(start) = 0.03 long */
  CHECK(near(m.solve_h[7], q2 - t1, 1e-12), "the retried step is %.17g long, expected q2 - t1 = %.17g (the secant from the step's start)",
        m.solve_h[7], q2 - t1);
  CHECK(sum.cutbacks == 0 && m.t == t2, "cutbacks %d (expected 0), end %.17g (the mock's clock %.17g)", sum.cutbacks, t2, m.t);
}

static void case_output_times(void) {
  Mock          m;
  RunnerSummary sum;
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 3, 1);
  const double times[3] = {0.25, 0.5, 0.8}, want[5] = {0, 0.25, 0.5, 0.8, 1.0};
  m.stage[0].nout_times = 3;
  memcpy(m.stage[0].out_times, times, sizeof times);
  if (run_quiet(&m, &sum)) return;
  CHECK(m.nwrite == 5, "%d field outputs, expected 5 (t = 0, the three times, the stage's end)", m.nwrite);
  for (int k = 0; k < m.nwrite && k < 5; k++) {
    CHECK(m.write_t[k] == want[k], "fields %d at t = %.17g, expected %g exactly", k, m.write_t[k], want[k]);
    CHECK(m.write_report[k], "fields %d at t = %g: not marked a report time (the start, an output time, the end)", k, want[k]);
  }
  /* every step's fields as well (output.fields_every 1): 10 steps of 0.1 s and the output time 0.25; only the start,
     0.25 and the end are report times, the times the error indicator's history keeps (fe_estimate.h) */
  RunnerOptions opt = quiet_options();
  opt.fields_every  = 1;
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 10, 1), m.stage[0].nout_times = 1, m.stage[0].out_times[0] = 0.25;
  if (run(&m, &opt, &sum)) return;
  int nreport = 0;
  for (int k = 0; k < m.nwrite && k < MAXREC; k++) {
    const int want_report = m.write_t[k] == 0 || m.write_t[k] == 0.25 || m.write_t[k] == 1.0;
    CHECK(m.write_report[k] == want_report, "fields_every 1: fields at t = %.17g marked %s", m.write_t[k], m.write_report[k] ? "a report time" : "not a report time");
    nreport += m.write_report[k];
  }
  CHECK(m.nwrite == 12 && nreport == 3, "fields_every 1: %d field outputs (%d report times), expected 12 (3)", m.nwrite, nreport);
}

/* ---------------------------------------------------------------------------------------------------- */
/* Checkpoint and restart                                                                               */

static void checkpoint_mock(Mock *m) {
  mock_init(m);
  m->nstage = 2, m->err_coef = 0.5;
  m->stage[0] = adaptive_stage(1.0, 0.05, 1.5, 0.3, MEASURE_OUTPUT, 0.02);
  m->stage[1] = adaptive_stage(1.0, 0.05, 1.5, 0.3, MEASURE_VOLUME, 0.05);
}

static int make_dir(const char *tmpl, char *dir, size_t n, const char *sub) {
  snprintf(dir, n, "%s/%s", tmpl, sub);
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "mkdir -p '%s'", dir);
  return system(cmd);
}

static int latest_step(const char *dir) {
  char path[1200];
  int  step = -1, ranks = 0;
  snprintf(path, sizeof path, "%s/checkpoint.latest", dir);
  FILE *fp = fopen(path, "r");
  if (fp && fscanf(fp, "%d %d", &step, &ranks) != 2) step = -1;
  if (fp) fclose(fp);
  return step;
}

static void case_checkpoint(const char *tmp) {
  char          whole_dir[1100], ckpt_dir[1100], scene[1200];
  Mock          whole, part, resumed;
  RunnerSummary s_whole, s_part, s_res;
  if (make_dir(tmp, whole_dir, sizeof whole_dir, "whole") || make_dir(tmp, ckpt_dir, sizeof ckpt_dir, "ckpt")) {
    CHECK(0, "cannot create the run folders under %s", tmp);
    return;
  }
  snprintf(scene, sizeof scene, "%s/scene.txt", tmp); /* hashed into the checkpoint: a restart needs the same */
  FILE *fp = fopen(scene, "w");
  if (fp) fprintf(fp, "mock scene\n"), fclose(fp);

  RunnerOptions opt = quiet_options();
  opt.scene_file = scene, opt.outdir = whole_dir;
  checkpoint_mock(&whole);
  if (run(&whole, &opt, &s_whole)) return;

  /* The 'output' measure on x' = -x/tau with equal steps h is e^(h/tau) - 1 (the increment's change over the
     increment); the PI controller holds h where 0.9 ratio^-(alpha - beta) = 1: h = tau ln(1 + tol 0.9^(1/0.85)). */
  double h_pi = whole.tau * log(1 + 0.02 * pow(STEP_SAFETY, 1 / (1 - 0.15))), h_25 = whole.accept_h[25];
  printf("checkpoint: stage 0's step 25 h = %.9g, the PI fixed point %.9g\n", h_25, h_pi);
  CHECK(near(h_25, h_pi, 1e-5) && whole.accept_t[25] < 1, "stage 0 settles at h = %.9g (step 25), the controller's fixed point %.9g", h_25, h_pi);
  opt.outdir = ckpt_dir, opt.checkpoint_every = 3, opt.max_steps = 7;
  checkpoint_mock(&part);
  if (run(&part, &opt, &s_part)) return;
  int k = latest_step(ckpt_dir);
  CHECK(s_part.stopped && s_part.steps == 7 && k == 6, "interrupted run: stopped %d after %d steps, checkpoint.latest %d (expected 1, 7, 6)",
        s_part.stopped, s_part.steps, k);

  opt.restart = 1, opt.max_steps = -1;
  checkpoint_mock(&resumed); /* a fresh solver: the state comes from the checkpoint */
  resumed.x = -1, resumed.t = -1;
  if (run(&resumed, &opt, &s_res) || k != 6) return;
  CHECK(whole.naccept > 12 && whole.accept_t[5] < 1.0, "the whole run: %d steps, step 6 at t = %g (expected > 12 steps, step 6 inside stage 0)",
        whole.naccept, whole.accept_t[5]);
  CHECK(resumed.naccept == whole.naccept - k && s_res.steps == s_whole.steps, "restart: %d steps after the checkpoint, %d in all; whole run %d, %d",
        resumed.naccept, s_res.steps, whole.naccept - k, s_whole.steps);
  int n = resumed.naccept < whole.naccept - k ? resumed.naccept : whole.naccept - k, same = 1;
  for (int i = 0; i < n; i++) same &= !memcmp(&resumed.accept_t[i], &whole.accept_t[k + i], sizeof(double));
  CHECK(same, "restart: accepted times differ from the whole run's from step %d on", k);
  CHECK(!memcmp(&resumed.x, &whole.x, sizeof(double)) && !memcmp(&s_res.t, &s_whole.t, sizeof(double)) && near(s_res.t, 2.0, 1e-14),
        "restart: x %.17g, t %.17g; whole run x %.17g, t %.17g (expected equal bit for bit, t = 2)", resumed.x, s_res.t, whole.x, s_whole.t);
}

/* A snap: the answer jumps at t = 0.5 whatever the step (module comment, case 8). */
static void case_jump(void) {
  Mock          m;
  RunnerSummary sum;
  mock_init(&m);
  m.tau = 1e12, m.t_jump = 0.5, m.jump = 0.3, m.held = 1; /* x constant (3) but for the jump */
  m.nstage = 1, m.stage[0] = adaptive_stage(1.0, 0.05, 1.5, 0.3, MEASURE_OUTPUT, 0.02);
  if (run_quiet(&m, &sum)) return;
  check_end_exactly(__func__, &m, &sum, 1.0);
  CHECK(near(m.x, m.x0 + m.jump, 1e-12), "x = %.17g, expected x0 + J = %.17g", m.x, m.x0 + m.jump);
  int k_jump = -1;
  for (int k = 0; k < m.naccept && k < MAXREC; k++)
    if (m.accept_t[k] >= m.t_jump && (k == 0 || m.accept_t[k - 1] < m.t_jump)) k_jump = k;
  CHECK(k_jump > 0, "no accepted step across t = %g", m.t_jump);
  if (k_jump <= 0) return;
  printf("jump: %d steps, %d cutbacks; the step across the jump h = %.3g\n", m.naccept, sum.cutbacks, m.accept_h[k_jump]);
  CHECK(sum.jumps == 1, "%d steps counted as across a jump, expected 1", sum.jumps);
  double terr = sum.time_error_change[1][0]; /* x's change over the stage: the jump, exact whatever the steps */
  CHECK(terr >= 0 && terr < 1e-9 * m.jump, "stated time-step error of x's change %.3g, expected about 0 (the jump is no time-step error)", terr);
  /* after the jump x is constant, so the extrapolation is exact: no step there may be rejected */
  CHECK(m.naccept_after > 0 && m.nsolve_after == m.naccept_after, "after the jump %d solves for %d accepted steps (expected equal: no cutback)",
        m.nsolve_after, m.naccept_after);
}

/* A small late onset after the stage's change (module comment, case 9): the steps with and without the floor. */
static void onset_run(Mock *m, double floor, RunnerSummary *sum) {
  mock_init(m);
  m->tau = 0.02, m->t_onset = 0.7, m->onset_c = 10, m->t_probe = 0.75;
  m->nstage = 1, m->stage[0] = adaptive_stage(1.0, 1e-3, 1.5, 0.05, MEASURE_OUTPUT, 0.02);
  m->stage[0].steps.floor = floor;
  run_quiet(m, sum);
}

static void case_floor(void) {
  Mock          m, none;
  RunnerSummary sum, sum_none;
  const double  f = 1e-3, tol = 0.02;
  onset_run(&m, f, &sum);
  onset_run(&none, 0, &sum_none);
  check_end_exactly(__func__, &m, &sum, 1.0);
  /* equal steps h in the onset: the departure is onset_c h^2 (x quadratic), the increment it is relative to the floor
     f |x - x0| (the increment is below it), so the PI controller's fixed point 0.9 ratio^-(alpha - beta) = 1 holds h at */
  double h_star = sqrt(tol * pow(STEP_SAFETY, 1 / (1 - 0.15)) * f * fabs(m.x_probe - m.x0) / m.onset_c);
  printf("floor: %d steps (%d after the onset), without it %d (%d); h at t = %g: %.6g, the fixed point %.6g\n", m.naccept,
         m.naccept_late, none.naccept, none.naccept_late, m.t_probe, m.h_probe, h_star);
  CHECK(near(m.h_probe, h_star, 0.01), "the onset's steps with the floor: h = %.6g, expected the fixed point %.6g (1 %%)", m.h_probe, h_star);
  CHECK(2 * m.naccept_late < none.naccept_late, "steps after the onset: %d with the floor, %d without (expected 2 times fewer)",
        m.naccept_late, none.naccept_late);
}

/* Every step across a kink (module comment, case 10): the estimate still sets the steps' length. */
static void case_kinks(void) {
  Mock          m;
  RunnerSummary sum;
  const double  tol = 0.02;
  mock_init(&m);
  m.tau = 0.02, m.t_onset = 0.7, m.onset_c = 10, m.t_probe = 0.9, m.kink_all = 1;
  m.x0 = m.x = 0; /* x = 0 before the onset: the steps grow to max there */
  m.nstage = 1, m.stage[0] = adaptive_stage(1.0, 1e-3, 1.5, 0.05, MEASURE_OUTPUT, tol);
  if (run_quiet(&m, &sum)) return;
  check_end_exactly(__func__, &m, &sum, 1.0);
  double s = m.t_probe_end - m.h_probe - m.t_onset, h_star = STEP_SAFETY * tol * s;
  printf("kinks: %d steps (%d after the onset), %d cutbacks; h at t = %g: %.6g, 0.9 tol s = %.6g\n", m.naccept, m.naccept_late,
         sum.cutbacks, m.t_probe, m.h_probe, h_star);
  CHECK(sum.cutbacks == 0, "%d steps rejected, expected none (a step across a kink is not rejected on its estimate)", sum.cutbacks);
  CHECK(near(m.h_probe, h_star, 0.05), "the onset's steps across kinks: h = %.6g, expected 0.9 tol s = %.6g (5 %%)", m.h_probe, h_star);
}

/* ---------------------------------------------------------------------------------------------------- */
/* Errors                                                                                               */

static void case_errors(void) {
  Mock          m;
  RunnerSummary sum;
  RunnerOptions opt = quiet_options();
  char          err[2048] = "";
  const char   *want = "mock.yaml: key 'limit': t = 0.5 is past the limit 0.45";
  PetscPushErrorHandler(PetscReturnErrorHandler, NULL); /* as main does: no traceback */
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 10, 1), m.fail_after = 0.45;
  StepSolver sv = mock_solver(&m);
  int        rc = stage_runner_run(&sv, &opt, &sum, err, sizeof err);
  CHECK(rc == 1 && !strcmp(err, want) && m.naccept == 5, "a check's STEP_FAIL: status %d, err '%s', %d steps (expected 1, '%s', 5)", rc, err,
        m.naccept, want);
  mock_init(&m);
  m.nstage = 1, m.stage[0] = fixed_stage(1.0, 10, 1), m.petsc_error_solve = 3;
  sv = mock_solver(&m);
  rc = stage_runner_run(&sv, &opt, &sum, err, sizeof err);
  CHECK(rc == PETSC_ERR_MEM && !err[0] && m.naccept == 2, "a solve's PETSc error: status %d, err '%s', %d steps (expected %d, '', 2)", rc, err,
        m.naccept, PETSC_ERR_MEM);
  PetscPopErrorHandler();
}

int main(int argc, char **argv) {
  PetscCall(PetscInitialize(&argc, &argv, NULL, "The stage runner with a mock StepSolver.\n"));
  char tmp[] = "/tmp/stage_runner_mock_XXXXXX";
  if (!mkdtemp(tmp)) return perror("mkdtemp"), 1;
  case_accept();
  case_reject();
  case_cutback();
  case_event();
  case_output_times();
  case_checkpoint(tmp);
  case_errors();
  case_jump();
  case_floor();
  case_kinks();
  char cmd[128];
  snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmp);
  if (!failures && system(cmd)) fprintf(stderr, "note: could not remove %s\n", tmp);
  if (failures) fprintf(stderr, "%d check(s) failed (run folder kept: %s)\n", failures, tmp);
  else printf("stage runner with a mock solver: all checks hold\n");
  PetscCall(PetscFinalize());
  return failures ? 1 : 0;
}
