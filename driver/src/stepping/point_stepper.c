#include "point_stepper.h"


#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../io/fsutil.h"
#include "../point/point_solve.h"

/* The point being stepped: the committed call (cur), the trial (next), the predictor (the last increment)
 * and the segment's start values. */
typedef struct {
  const PointScene *sc;
  UmatControl       umat; /* the UMAT's step control of the last step solved */
  UmatCall          cur, next;
  PointStepResult   res;
  double            last_deps[6], last_dt, start[6], devp_prev[6], t;
  int               have_devp;
  double           *t_start, *t_end;
  PointSummary     *sum;
  MaterialPointState hs; /* the committed state's quantities, for the history's row */
} Point;

/* Component i of the total viscoplastic strain of a call's state (0 where the UMAT keeps none). */
static double evp_of(const Point *pt, const UmatCall *c, int i) { return material_quantity(&pt->sc->mat, c->statev, MATERIAL_EVP, i); }

/* The callbacks (stage_runner.h): the point's Newton calls no PETSc, and a step that does not converge is no
   error, so they return 0. */
static PetscErrorCode stage_begin(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen) {
  Point         *pt = ctx;
  const Segment *sg = &pt->sc->seg[s];
  int            n  = pt->sc->mat.ntens;
  if (!resumed) { /* values at the segment start: ramps begin there; linear constraints keep their value */
    for (int i = 0; i < n; i++) {
      const Equation *eq = &sg->eq[i];
      if (eq->kind == EQ_STRESS) pt->start[i] = pt->cur.stress[i];
      else if (eq->kind == EQ_STRAIN) pt->start[i] = pt->cur.stran[i];
      else if (!isnan(eq->value)) pt->start[i] = eq->value;
      else {
        double val = 0;
        for (int j = 0; j < n; j++) val += eq->a[j] * pt->cur.stran[j] + eq->b[j] * pt->cur.stress[j];
        pt->start[i] = val;
      }
    }
    pt->t_start[s] = pt->t;
  }
  double p, q;
  point_invariants(pt->cur.stress, n, &p, &q);
  stage_view_of(&sg->stage, v);
  v->event_start = v->until.kind == EVENT_P_ABOVE ? p : q;
  return 0;
}

static double norm6(const double *a) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3] + a[4] * a[4] + a[5] * a[5]); }

/* What the runner judges a converged step by: p, q, the viscoplastic rate, strain and stress (outputs), and
 * the change of the viscoplastic strain rate (the 'volume' measure of one point). */
static void observe(Point *pt, const StepRequest *rq, StepOutcome *o) {
  int    n = pt->sc->mat.ntens;
  double p, q, devp[6];
  point_invariants(pt->next.stress, n, &p, &q);
  for (int i = 0; i < 6; i++) devp[i] = evp_of(pt, &pt->next, i) - evp_of(pt, &pt->cur, i);
  o->event[EVENT_P_ABOVE] = p, o->event[EVENT_Q_ABOVE] = o->event[EVENT_Q_BELOW] = q;
  o->event[EVENT_EVP_RATE_BELOW] = rq->h > 0 ? norm6(devp) / rq->h : INFINITY;
  o->nout = 2 * n;
  for (int i = 0; i < n; i++) {
    o->out[i] = pt->cur.stran[i] + pt->next.dstran[i], o->group[i] = 0;
    o->out[n + i] = pt->next.stress[i], o->group[n + i] = 1;
  }
  if (rq->want_volume_error && pt->have_devp && rq->h > 0 && pt->last_dt > 0) {
    double d[6], evp[6];
    for (int i = 0; i < 6; i++) d[i] = devp[i] - rq->h / pt->last_dt * pt->devp_prev[i], evp[i] = evp_of(pt, &pt->next, i);
    o->vol_err = norm6(d) / fmax(norm6(devp), 1e-9 * norm6(evp) + 1e-300);
  }
}

static PetscErrorCode solve(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen) {
  Point         *pt = ctx;
  const Segment *sg = &pt->sc->seg[rq->s];
  int            n  = pt->sc->mat.ntens;
  double         target[6], deps[6];
  for (int i = 0; i < n; i++) target[i] = point_target(sg, i, pt->start, rq->lambda, rq->ts0 + rq->h);
  for (int i = 0; i < n; i++) deps[i] = pt->last_dt > 0 && rq->h > 0 ? pt->last_deps[i] * rq->h / pt->last_dt : 0;
  pt->umat        = rq->umat;
  pt->cur.time[0] = rq->ts0, pt->cur.time[1] = rq->t0;
  int rc = point_mixed_step(&pt->sc->mat, pt->umat, sg, &pt->cur, target, rq->h, deps, &pt->next, &pt->res);
  pt->sum->umat_calls += pt->res.umat_calls;
  /* a UMAT that asks for a smaller step: 'converged' with PNEWDT < 1, so the runner cuts by PNEWDT */
  o->converged = !rc || pt->res.failed.have;
  o->pnewdt    = pt->res.pnewdt;
  o->its       = pt->res.newton;
  o->why       = "the mixed-control Newton did not converge";
  if (!rc) observe(pt, rq, o);
  return 0;
}

static PetscErrorCode accept(void *ctx, const StepRequest *rq, char *err, size_t errlen) {
  Point            *pt = ctx;
  const PointScene *sc = pt->sc;
  if (sc->check_tangent && rq->h > 0) pt->sum->umat_calls += 2 * sc->mat.ntens;
  if (sc->check_tangent && rq->h > 0)
    pt->sum->worst_tangent_error = fmax(pt->sum->worst_tangent_error, point_tangent_check(&sc->mat, pt->umat, &pt->cur, &pt->next));
  pt->sum->worst_control_error = fmax(pt->sum->worst_control_error, pt->res.control_error);
  if (sc->replay_step > 0 && pt->sum->steps + 1 == sc->replay_step) {
    UmatCall     in = pt->cur;
    UmatMaterial mat;
    memcpy(in.dstran, pt->next.dstran, sizeof in.dstran);
    in.dtime = rq->h;
    material_effective(&sc->mat, material_phi(&sc->mat), pt->umat, &mat);
    char rp[1100];
    snprintf(rp, sizeof rp, "%s/replay_step_%d.yaml", sc->outdir, sc->replay_step);
    if (umat_write_replay(rp, &mat, &in, &pt->next, "requested with -write_replay_at_step")) fprintf(stderr, "driver: could not write %s\n", rp);
  }
  for (int i = 0; i < 6; i++)
    pt->devp_prev[i] = evp_of(pt, &pt->next, i) - evp_of(pt, &pt->cur, i);
  pt->have_devp = rq->h > 0;
  memcpy(pt->last_deps, pt->next.dstran, sizeof pt->last_deps);
  pt->last_dt = rq->h;
  for (int i = 0; i < sc->mat.ntens; i++) pt->next.stran[i] = pt->cur.stran[i] + pt->next.dstran[i];
  pt->cur = pt->next;
  pt->cur.kinc++;
  pt->t += rq->h;
  pt->sum->steps++;
  pt->t_end[rq->s] = pt->t;
  return 0;
}

/* The point history's own columns (history_columns.h): the UMAT's local iterations, strain and stress, the
   frames' stresses and viscoplastic strains, the preconsolidation pressures and the local flags; history_prepare
   reads the committed state once a row. */
static void history_prepare(void *ctx) {
  Point *pt = ctx;
  material_point_state(&pt->sc->mat, pt->cur.statev, &pt->hs);
}
#define PT(ctx) ((const Point *)(ctx))
static HistValue v_local(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = PT(ctx)->hs.local.iterations}; }
static HistValue v_eps(const void *ctx, const RunnerRow *row, int k) {
  return (HistValue){.r = k < PT(ctx)->sc->mat.ntens ? PT(ctx)->cur.stran[k] : 0.0};
}
static HistValue v_sig(const void *ctx, const RunnerRow *row, int k) {
  return (HistValue){.r = k < PT(ctx)->sc->mat.ntens ? PT(ctx)->cur.stress[k] : 0.0};
}
static HistValue v_sig_hard(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.sig_hard[k]}; }
static HistValue v_sig_soft(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.sig_soft[k]}; }
static HistValue v_evp_hard(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.evp_hard[k]}; }
static HistValue v_evp_soft(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.evp_soft[k]}; }
static HistValue v_evp(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.evp[k]}; }
static HistValue v_pc_hard(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.pc_hard}; }
static HistValue v_pc_soft(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = PT(ctx)->hs.pc_soft}; }
static HistValue v_flags(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = PT(ctx)->hs.local.flags}; }

static const HistColumn columns[] = {
  {"local_its", "%d", 1, NULL, v_local, NULL, NULL},
  {"eps", "%.12g", 6, hist_tensor_suffix, v_eps, NULL, NULL},
  {"sig", "%.12g", 6, hist_tensor_suffix, v_sig, NULL, NULL},
  {"sig_hard", "%.12g", 6, hist_tensor_suffix, v_sig_hard, NULL, NULL},
  {"sig_soft", "%.12g", 6, hist_tensor_suffix, v_sig_soft, NULL, NULL},
  {"evp_hard", "%.12g", 6, hist_tensor_suffix, v_evp_hard, NULL, NULL},
  {"evp_soft", "%.12g", 6, hist_tensor_suffix, v_evp_soft, NULL, NULL},
  {"evp", "%.12g", 6, hist_tensor_suffix, v_evp, NULL, NULL},
  {"pc_hard", "%.12g", 1, NULL, v_pc_hard, NULL, NULL},
  {"pc_soft", "%.12g", 1, NULL, v_pc_soft, NULL, NULL},
  {"flags", "%d", 1, NULL, v_flags, NULL, NULL},
};

/* What a point reports (summary.json, with the time-step error of its change over a held segment): the strain
   along the loading axis (that of the first creep segment, else of the first) and the volumetric strain. */
/* The outputs observe reports, at the committed state (StepSolver.outputs): strain and stress, the stress not 0 at
 * the start (the initial state). */
static void outputs(void *ctx, double *out) {
  const Point *pt = ctx;
  int          n  = pt->sc->mat.ntens;
  for (int i = 0; i < n; i++) out[i] = pt->cur.stran[i], out[n + i] = pt->cur.stress[i];
}

static void report(void *ctx, double *v) {
  const Point      *pt = ctx;
  const PointScene *sc = pt->sc;
  int               axis = sc->nseg ? sc->seg[0].axis : 2, n = sc->mat.ntens;
  for (int s = sc->nseg - 1; s >= 0; s--)
    if (sc->seg[s].stage.creep) axis = sc->seg[s].axis;
  double e[3];
  for (int i = 0; i < 3; i++) e[i] = i < n ? pt->cur.stran[i] : 0.0;
  v[0] = e[axis], v[1] = e[0] + e[1] + e[2];
}

static long umat_calls(void *ctx) { return ((Point *)ctx)->sum->umat_calls; }

static const char *stage_name(void *ctx, int s) { return ((Point *)ctx)->sc->seg[s].stage.name; }

static PetscErrorCode progress(void *ctx, char *buf, size_t n) {
  Point *pt = ctx;
  MaterialPointState s;
  material_point_state(&pt->sc->mat, pt->cur.statev, &s);
  snprintf(buf, n, "local %d ", s.local.iterations);
  return 0;
}

/* The point's state for a checkpoint: the committed call (plain values only), the predictor, the
   segment's start values, the times of the segments and the summary so far. A write or read that fails leaves
   f->ok 0. */
static PetscErrorCode state_io(Point *pt, BinFile *f, int write) {
  void  *parts[] = {&pt->cur, pt->last_deps, &pt->last_dt, pt->start, pt->devp_prev, &pt->have_devp, &pt->t, pt->t_start, pt->t_end, pt->sum};
  size_t sizes[] = {sizeof pt->cur, 6 * sizeof(double), sizeof(double), 6 * sizeof(double), 6 * sizeof(double), sizeof(int),
                    sizeof(double), (size_t)pt->sc->nseg * sizeof(double), (size_t)pt->sc->nseg * sizeof(double), sizeof *pt->sum};
  for (size_t k = 0; k < sizeof parts / sizeof parts[0]; k++) {
    if (write) binfile_write(f, parts[k], sizes[k], 1);
    else binfile_read(f, parts[k], sizes[k], 1);
  }
  return 0;
}

static PetscErrorCode save(void *ctx, BinFile *f) { return state_io(ctx, f, 1); }
static PetscErrorCode load(void *ctx, BinFile *f) { return state_io(ctx, f, 0); }

static PetscErrorCode replay(void *ctx, const char *dir, char *msg, size_t n) {
  Point *pt = ctx;
  if (!pt->res.failed.have) return 0;
  char rp[1100];
  snprintf(rp, sizeof rp, "%s/failed_call.yaml", dir);
  if (!material_failed_call_write(&pt->res.failed, rp, msg)) {
    size_t len = strlen(msg);
    snprintf(msg + len, n - len, "; the failing UMAT call is replayed by: driver -input %s", rp);
  }
  return 0;
}

/* scene.json (name: scene.json.part while the run has no results of its own: an earlier run's stays). */
static void write_json(const PointScene *sc, const double *t_start, const double *t_end, const char *name) {
  char path[1100];
  snprintf(path, sizeof path, "%s/%s", sc->outdir, name);
  FILE *fp = fopen(path, "w");
  if (!fp) return;
  fprintf(fp, "{\"name\": \"%s\", \"ntens\": %d, \"props\": [", sc->name, sc->mat.ntens);
  double    props[UMAT_MAX_PROPS], b[3];
  const int np = material_props_with_normal(&sc->mat, props, b);
  for (int i = 0; i < np; i++) fprintf(fp, "%s%.17g", i ? ", " : "", props[i]);
  double nn = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  fprintf(fp, "], \"normal\": [%.17g, %.17g, %.17g], \"units\": {\"stress\": \"MPa\", \"time\": \"s\"}, \"segments\": [",
          b[0] / nn, b[1] / nn, b[2] / nn);
  for (int s = 0; s < sc->nseg; s++)
    fprintf(fp, "%s{\"name\": \"%s\", \"t_start\": %.17g, \"t_end\": %.17g, \"creep\": %s, \"axis\": %d}", s ? ", " : "",
            sc->seg[s].stage.name, t_start[s], t_end[s], sc->seg[s].stage.creep ? "true" : "false", sc->seg[s].axis);
  fprintf(fp, "]}\n");
  fclose(fp);
}

int point_run(const PointScene *sc, const RunnerOptions *given, PointSummary *sum, char *err, size_t errlen) {
  Point pt;
  memset(&pt, 0, sizeof pt);
  memset(sum, 0, sizeof *sum);
  pt.sc = sc, pt.sum = sum, pt.umat = umat_control(UMAT_CONTROL_AS_GIVEN, 0);
  if (sc->outdir[0] && fs_make_directories(sc->outdir)) {
    snprintf(err, errlen, "output directory '%s': cannot create: %s", sc->outdir, strerror(errno));
    return 1;
  }
  memcpy(pt.cur.stress, sc->stress0, sizeof pt.cur.stress);
  memcpy(pt.cur.statev, sc->statev0, sizeof pt.cur.statev);
  pt.cur.noel = pt.cur.npt = pt.cur.kstep = pt.cur.kinc = 1;
  /* A zero increment (DSTRAN = 0, DTIME = 0) first: the UMAT initialises its state from STRESS if it needs
   * to (Cam-Clay IX's uninitialised-state rule), so that row 0 shows the real initial state. */
  MaterialPointDiag diag;
  material_point_update(&sc->mat, material_phi(&sc->mat), pt.umat, &pt.cur, &diag);
  sum->umat_calls = 1;
  if (diag.rejected) {
    snprintf(err, errlen, "the UMAT rejected the initial state (a zero increment returned PNEWDT = %g)", pt.cur.pnewdt);
    return 1;
  }
  pt.t_start = calloc((size_t)sc->nseg + 1, sizeof(double)), pt.t_end = calloc((size_t)sc->nseg + 1, sizeof(double));
  StepSolver sv = {.ctx = &pt, .kind = "point", .nstage = sc->nseg, .comm = MPI_COMM_SELF, .stage_begin = stage_begin,
                   .solve = solve, .accept = accept, .columns = columns, .ncolumns = sizeof columns / sizeof columns[0],
                   .history_prepare = history_prepare, .stage_name = stage_name, .nreport = 2,
                   .report_names = {"strain_axial", "strain_volumetric"}, .report = report, .outputs = outputs,
                   .umat_calls = umat_calls, .progress = progress, .save = save, .load = load, .replay = replay};
  RunnerOptions opt;
  memset(&opt, 0, sizeof opt);
  if (given) opt = *given;
  else opt.max_steps = -1;
  opt.outdir = sc->outdir, opt.quiet = opt.quiet || (sc->progress_every <= 0 && opt.progress_every <= 0);
  if (opt.progress_every <= 0) opt.progress_every = sc->progress_every;
  RunnerSummary rs;
  int           rc = stage_runner_run(&sv, &opt, &rs, err, errlen);
  sum->cutbacks = rs.cutbacks, sum->failed = rc != 0, sum->wall = rs.wall;
  memcpy(sum->final_stress, pt.cur.stress, sizeof sum->final_stress);
  sum->finite = 1;
  for (int i = 0; i < sc->mat.ntens; i++) sum->finite &= isfinite(pt.cur.stress[i]);
  for (int i = 0; i < sc->mat.nstatv; i++) sum->finite &= isfinite(pt.cur.statev[i]);
  if (sc->outdir[0] && rs.ran && rc != 2) /* not after bad input (a refused restart): nothing written */
    write_json(sc, pt.t_start, pt.t_end, rs.replaced ? "scene.json" : "scene.json.part");
  free(pt.t_start);
  free(pt.t_end);
  return rc;
}
