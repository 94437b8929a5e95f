/* Indentation scenes: each step solved by the semismooth Newton method of the contact module (Box 1) from
 * the committed state; the indenter's load or depth follows the stage (indent_scene.h), the boundary loads
 * and the 'until' events those of any FE stage. */
#include "fe_stepper.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../contact/contact_io.h"
#include "../contact/semismooth.h"
#include "../fe/fe_state.h"

typedef struct {
  FeCommon     c;
  IndentScene *is;
  Semismooth   in;
  double       load, load_max, stage_start, force, pen, lmin;
  char         until_key[64];
} Indent;

static const char *shape_name(const IndentScene *is) {
  return (const char *[]){"berkovich", "cone", "wedge", "sphere", "flat_punch"}[is->shape.kind];
}

/* A load of the model as the whole indenter's (indenter.copies: the model is one of that many mirror copies). */
static inline double whole(const Indent *d, double model_load) { return model_load * d->is->copies; }

static PetscErrorCode stage_begin(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen) {
  Indent      *d  = ctx;
  IndentStage *st = &d->is->stage[s];
  Stage       *g  = &d->c.sc->stage[s];
  PetscFunctionBeginUser;
  fe_common_stage_begin(&d->c, s, resumed, v);
  semismooth_set_stage(&d->in, indent_stage_depth_control(st), !resumed);
  if (!resumed) d->stage_start = d->in.depth_control ? d->in.ur : d->load;
  v->held = v->held && (st->kind == IND_LOAD_HOLD || ((st->kind == IND_LOAD_RAMP || st->kind == IND_DEPTH_RAMP) && st->fn.target == d->stage_start));
  if ((st->until_depth > 0 || st->until_load > 0) && g->until.kind != EVENT_NONE)
    STEP_FAIL(err, errlen, "%s: key 'stages[%d].indenter.until': stage '%s': give one end event: indenter.until or until, not both",
              d->is->file, s, g->name);
  if (st->until_load > 0) { /* the time the load reaches the event, known in advance */
    double te = indent_stage_time_of_load(st, d->stage_start, g->duration, st->until_load);
    if (te < 0)
      STEP_FAIL(err, errlen, "%s: key 'stages[%d].indenter.until.load': stage '%s': the load never reaches %g within the stage's "
                "duration %g s", d->is->file, s, g->name, whole(d, st->until_load), g->duration);
    v->duration = te;
  }
  if (st->until_depth > 0) {
    snprintf(d->until_key, sizeof d->until_key, "stages[%d].indenter.until.depth", s);
    v->until.kind = EVENT_DEPTH, v->until.value = st->until_depth, v->must_reach = 1, v->event_start = d->in.ur, v->until_key = d->until_key;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode solve(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen) {
  Indent      *d  = ctx;
  Semismooth  *in = &d->in;
  FeProblem   *p  = d->c.p;
  IndentStage *st = &d->is->stage[rq->s];
  double       ts = rq->ts0 + rq->h;
  PetscFunctionBeginUser;
  PetscCall(fe_common_set_loads(&d->c, rq));
  double target = indent_stage_value(st, d->stage_start, rq->lambda, ts);
  if (st->until_load > 0 && rq->lambda >= 1) target = st->until_load; /* the event time is the stage's end */
  semismooth_set_target(in, target, d->load, d->load_max, rq->newton_etol);
  int      status;
  PetscInt its = 0;
  fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0)); /* Newton iterates without it */
  PetscCall(semismooth_step(in, rq->h, &status, &its));
  o->converged = status == STEP_OK, o->its = (int)its, o->why = status == STEP_OK ? "" : semismooth_failure(in, status), o->stalled = status == STEP_STALLED;
  if (!o->converged) PetscFunctionReturn(0);
  PetscReal tol = umat_control_tol(fe_problem_material(p), rq->umat), m;
  if (tol > 0) { /* the same state, now with the UMAT's PNEWDT */
    fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_AT, tol));
    PetscCall(semismooth_evaluate(in, &m));
    fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0));
  }
  o->pnewdt = fe_problem_diag(p)->min_pnewdt;
  PetscCall(fe_common_observe(&d->c, rq, o));
  PetscCall(contact_summary(&in->ct, in->lam, &d->force, &d->pen, &d->lmin));
  o->event[EVENT_DEPTH] = in->ur;
  o->event[EVENT_LOAD]  = whole(d, in->depth_control ? d->force : in->target);
  o->progress           = st->until_depth > 0 ? in->ur / st->until_depth : -1;
  o->kink               = in->changes > 0; /* a node entered or left contact: the depth rate jumps */
  o->nout = 2, o->out[0] = in->ur, o->group[0] = 0, o->out[1] = d->force, o->group[1] = 1;
  PetscFunctionReturn(0);
}

static PetscErrorCode accept(void *ctx, const StepRequest *rq, char *err, size_t errlen) {
  Indent     *d  = ctx;
  Semismooth *in = &d->in;
  PetscFunctionBeginUser;
  if (semismooth_released(in) && in->nactive == 0) { /* the indenter rests on the surface: its gaps change */
    PetscCall(semismooth_rest_on_surface(in));
    PetscCall(contact_summary(&in->ct, in->lam, &d->force, &d->pen, &d->lmin));
  }
  PetscCall(semismooth_commit(in, rq->h, PETSC_TRUE));
  d->load = in->depth_control ? d->force : in->target;
  if (!in->depth_control) d->load_max = PetscMax(d->load_max, in->target);
  PetscCall(fe_common_accept(&d->c, rq));
  PetscFunctionReturn(0);
}

/* Beyond the potential contact surface the nodes are not checked: the results would be wrong from here. */
static PetscErrorCode check(void *ctx, double t, char *err, size_t errlen) {
  Indent  *d = ctx;
  PetscInt on_rim;
  PetscFunctionBeginUser;
  PetscCall(contact_on_rim(&d->in.ct, &on_rim));
  if (on_rim)
    STEP_FAIL(err, errlen, "%s: at t = %.6g s (depth %.6g) the contact reached the edge of the potential contact surface '%s' (%d active "
              "nodes on its rim): enlarge it (the mesh's contact region), then rerun; the history up to here is kept",
              d->is->file, t, (double)d->in.ur, d->is->contact_group, (int)on_rim);
  PetscFunctionReturn(0);
}

/* The indentation history's own columns (history_columns.h): the indenter's load and depth, the contact, the
   costs, the viscoplastic strain rate. */
#define IND(ctx) ((const Indent *)(ctx))
static HistValue v_load(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = whole(IND(ctx), IND(ctx)->load)}; }
static HistValue v_depth(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = (double)IND(ctx)->in.ur}; }
static HistValue v_active(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = (int)IND(ctx)->in.nactive}; }
static HistValue v_changes(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = (int)IND(ctx)->in.changes}; }
static HistValue v_force(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = whole(IND(ctx), IND(ctx)->force)}; }
static HistValue v_pen(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = IND(ctx)->pen}; }
static HistValue v_lmin(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = IND(ctx)->lmin}; }
static HistValue v_rate(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = row->step ? IND(ctx)->c.stats.evp_rate : 0.0}; }

static const HistColumn columns[] = {
  {"load", "%.17g", 1, NULL, v_load, NULL, NULL},
  {"depth", "%.17g", 1, NULL, v_depth, NULL, NULL},
  {"active_nodes", "%d", 1, NULL, v_active, NULL, NULL},
  {"active_changes", "%d", 1, NULL, v_changes, NULL, NULL},
  {"contact_force", "%.17g", 1, NULL, v_force, NULL, NULL},
  {"max_penetration", "%.6g", 1, NULL, v_pen, NULL, NULL},
  {"min_lambda", "%.6g", 1, NULL, v_lmin, NULL, NULL},
  FE_COMMON_COST_COLUMNS,
  {"evp_rate", "%.6g", 1, NULL, v_rate, NULL, NULL},
};

static PetscErrorCode progress(void *ctx, char *buf, size_t n) {
  Indent *d = ctx;
  PetscFunctionBeginUser;
  snprintf(buf, n, "load %-10.5g depth %-10.5g active %4d (%3d changes) ", whole(d, d->load), (double)d->in.ur, (int)d->in.nactive, (int)d->in.changes);
  PetscFunctionReturn(0);
}

static PetscErrorCode write_fields(void *ctx, double t, int report, char *err, size_t errlen) {
  Indent *d = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_common_fields(&d->c, d->in.U0, t, report, err, errlen));
  PetscFunctionReturn(0);
}

static PetscErrorCode promote(void *ctx) {
  PetscFunctionBeginUser;
  PetscCall(fe_common_promote(&((Indent *)ctx)->c));
  PetscFunctionReturn(0);
}

/* The indenter's state, with the predictor's (the last converged increments), so a restart is exact: the values
   every rank holds alike here, the multipliers and the active set (per node) in the shared file (contact_io.h).
   A write or read that fails leaves f->ok 0. */
static void state_io(Indent *d, BinFile *f, int write) {
  double vals[3] = {d->load, d->load_max, d->stage_start};
  if (semismooth_state_io(&d->in, f, write)) return;
  if (write) binfile_write(f, vals, sizeof(double), 3);
  else binfile_read(f, vals, sizeof(double), 3), d->load = vals[0], d->load_max = vals[1], d->stage_start = vals[2];
}

static PetscErrorCode save(void *ctx, BinFile *f) {
  Indent *d = ctx;
  PetscFunctionBeginUser;
  indent_solver_refresh(&d->in.sol); /* the next solve factors afresh, as a run restarted from here does */
  PetscCall(fe_common_save(&d->c, f));
  if (f->ok) state_io(d, f, 1);
  PetscFunctionReturn(0);
}

static PetscErrorCode load(void *ctx, BinFile *f) {
  Indent *d = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_common_load(&d->c, f));
  if (f->ok) state_io(d, f, 0);
  PetscFunctionReturn(0);
}

/* The committed displacement and its last increment, the points' state (fe/fe_state.h), the multipliers. */
static const char *const shared_names[2] = {"displacement", "increment"};

/* The run's shared state (displacements, rates, multipliers) written to or read from one HDF5 file. */
static PetscErrorCode shared_io(Indent *d, const char *path, PetscBool write) {
  PetscViewer v;
  Vec         vecs[2] = {d->in.U0, d->in.rateU};
  DM          dm      = fe_problem_dm(d->c.p);
  PetscFunctionBeginUser;
  PetscCall(fe_common_shared_open(&d->c, path, write, &v));
  if (write) {
    PetscCall(fe_state_view(d->c.p, v, 2, vecs, shared_names));
    PetscCall(contact_io_view(&d->in.ct, dm, v, d->in.lam0, d->in.ratelam));
  } else {
    PetscCall(fe_state_read(d->c.p, v, 2, vecs, shared_names));
    PetscCall(contact_io_read(&d->in.ct, dm, v, d->in.lam0, d->in.ratelam));
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(0);
}

static PetscErrorCode save_shared(void *ctx, const char *path) { return shared_io(ctx, path, PETSC_TRUE); }
static PetscErrorCode load_shared(void *ctx, const char *path) { return shared_io(ctx, path, PETSC_FALSE); }

static PetscErrorCode resume(void *ctx) {
  Indent *d = ctx;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(d->in.U0, d->in.U));
  PetscCall(VecCopy(d->in.lam0, d->in.lam));
  PetscCall(contact_update_gaps(&d->in.ct, d->in.U, d->in.ur));
  PetscCall(fe_common_resume(&d->c));
  PetscFunctionReturn(0);
}

static PetscErrorCode replay(void *ctx, const char *dir, char *msg, size_t n) {
  PetscFunctionBeginUser;
  PetscCall(fe_common_replay(&((Indent *)ctx)->c, dir, msg, n));
  PetscFunctionReturn(0);
}

static long umat_calls(void *ctx) { return (long)fe_problem_diag(((Indent *)ctx)->c.p)->umat_calls; }

/* What an indentation reports (StepSolver.report): the indenter's depth and the whole indenter's load. */
static void report(void *ctx, double *v) {
  Indent *d = ctx;
  v[0] = (double)d->in.ur, v[1] = whole(d, d->load);
}

/* After the run: the output closed, the summary line, the contact solver freed. */
static PetscErrorCode finish(Indent *d, MPI_Comm comm, const RunnerSummary *sum, const RunnerOptions *opt) {
  FeProblem *p = d->c.p;
  double     mb[2];
  PetscFunctionBeginUser;
  PetscCall(fe_common_finish(&d->c));
  PetscCall(PetscPrintf(comm, "indentation %s: %d steps, %d Newton iterations (predictor %s), %d cutbacks (%d by the error measure, %d asked by the UMAT, %d stalled, %d not converged), %d active-set cycles, "
                              "%ld UMAT calls, assembly %.2f s, linear solves %.2f s (%s, %d Krylov iterations, %d factorisations), wall %.2f s -> %s/history.csv\n",
                        d->c.sc->name, sum->steps, (int)d->in.its_total, d->in.predictor ? "on" : "off", sum->cutbacks, sum->rejected_error, sum->rejected_umat,
                        sum->rejected_stalled, sum->rejected_unconverged,
                        (int)d->in.cycles, sum->umat_calls, fe_problem_diag(p)->assembly_seconds, d->in.sol.seconds, d->in.sol.fieldsplit ? "fieldsplit" : "direct",
                        (int)d->in.sol.linear_its, (int)d->in.sol.setups, sum->wall, opt->outdir));
  PetscCall(fe_common_max_rss(comm, mb));
  PetscCall(PetscPrintf(comm, "memory: max RSS %.1f MB per rank, %.1f MB in all\n", mb[0], mb[1]));
  PetscCall(semismooth_destroy(&d->in));
  PetscFunctionReturn(0);
}

int indent_stepper_run(FeScene *sc, IndentScene *is, FeProblem *p, const RunnerOptions *opt, char *err, size_t errlen) {
  Indent d;
  int    bad = 0;
  MPI_Comm comm = PetscObjectComm((PetscObject)fe_problem_dm(p));
  PetscErrorCode ierr = PetscMemzero(&d, sizeof d);
  d.is = is;
  if (!ierr) ierr = semismooth_create(p, is, sc->msh, &d.in, err, errlen, &bad);
  if (ierr) return stage_runner_status(ierr, err);
  if (bad) return bad;
  ierr = fe_common_init(&d.c, sc, p, opt);
  char solver[64];
  if (!ierr) ierr = indent_solver_name(&d.in.sol, solver, sizeof solver);
  if (!ierr)
    ierr = PetscPrintf(comm, "indenter: %s, %d potential contact nodes (group '%s', weights sum %.6g), solver %s, complementarity c = %.4g, "
                             "indenter-row shift %.4g\n",
                       shape_name(is), (int)d.in.ct.N, is->contact_group, (double)d.in.ct.weight_sum, solver,
                       (double)d.in.ct.c, (double)d.in.ct.kn);
  if (ierr) return stage_runner_status(ierr, err);
  StepSolver sv = {.ctx = &d, .kind = "indentation", .nstage = sc->nstage, .comm = comm, .stage_begin = stage_begin,
                   .solve = solve, .accept = accept, .check = check, .columns = columns,
                   .ncolumns = sizeof columns / sizeof columns[0], .stage_name = fe_common_stage_name, .progress = progress,
                   .write_fields = write_fields, .promote = promote,
                   .save = save, .load = load, .replay = replay, .umat_calls = umat_calls, .resume = resume,
                   .save_shared = save_shared, .load_shared = load_shared,
                   .nreport = 2, .report_names = {"depth", "load"}, .report = report};
  RunnerSummary sum;
  int           rc = stage_runner_run(&sv, opt, &sum, err, errlen);
  ierr             = finish(&d, comm, &sum, opt);
  return rc ? rc : stage_runner_status(ierr, err);
}
