/* scene: calibrate: the scene, and TAO's least-squares solve over the parameters mapped to [0, 1] (linear or
 * logarithmic within their bounds); each evaluation's forward runs in calibrate_forward.c. */
#include "calibrate.h"

#include <math.h>
#include <petsctao.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../io/fsutil.h"
#include "../material/material_input.h"
#include "../stepping/run_status.h"
#include "calibrate_check.h"
#include "calibrate_data.h"
#include "calibrate_forward.h"
#include "calibrate_load.h"
#include "calibrate_protocol.h"
#include "calibrate_refine.h"
#include "calibrate_report.h"
#include "calibrate_residual.h"
#include "calibrate_units.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

static double param_u(const CalParam *p, double v) {
  return p->log ? log(v / p->lo) / log(p->hi / p->lo) : (v - p->lo) / (p->hi - p->lo);
}

/* parameters: [{name, start, min, max, scale: linear | log}] */
static int read_param(const YdDoc *doc, YdNode *nd, int k, CalParam *p, char *err, size_t errlen) {
  char        path[64], sub[96];
  const char *s;
  YdNode     *v;
  snprintf(path, sizeof path, "parameters[%d]", k);
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  p->line = nd->line;
  snprintf(sub, sizeof sub, "%s.name", path);
  if (!(v = yd_require(doc, nd, "name", YD_SCALAR, sub, err, errlen)) || yd_string(doc, v, sub, &s, err, errlen)) return 1;
  snprintf(p->name, sizeof p->name, "%s", s);
  char list[400];
  if ((p->slot = material_slot(s)) < 0)
    FAIL("%s:%d: key '%s': unknown PROPS name '%s': expected one of %s", doc->file, v->line, sub, s, material_slot_list(list, sizeof list));
  const char *keys[3] = {"start", "min", "max"};
  double     *vals[3] = {&p->start, &p->lo, &p->hi};
  for (int i = 0; i < 3; i++) {
    snprintf(sub, sizeof sub, "%s.%s", path, keys[i]);
    if (!(v = yd_require(doc, nd, keys[i], YD_SCALAR, sub, err, errlen)) || yd_double(doc, v, sub, vals[i], err, errlen))
      return 1;
  }
  p->log = 0;
  snprintf(sub, sizeof sub, "%s.scale", path);
  if ((v = yd_get(nd, "scale"))) {
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    if (strcmp(s, "log") && strcmp(s, "linear"))
      FAIL("%s:%d: key '%s': expected linear or log, got '%s'", doc->file, v->line, sub, s);
    p->log = !strcmp(s, "log");
  }
  int line = yd_key_line(nd, "max");
  if (!(p->lo < p->hi))
    FAIL("%s:%d: key '%s': bounds the wrong way round: min = %g must be below max = %g", doc->file, line, path, p->lo, p->hi);
  if (p->log && !(p->lo > 0))
    FAIL("%s:%d: key '%s.min': a log scale needs min > 0, got %g", doc->file, yd_key_line(nd, "min"), path, p->lo);
  if (!(p->start >= p->lo && p->start <= p->hi))
    FAIL("%s:%d: key '%s.start': expected a start within [min, max] = [%g, %g], got %g", doc->file,
         yd_key_line(nd, "start"), path, p->lo, p->hi, p->start);
  return yd_check_unused(doc, nd, path, "name, start, min, max, scale", err, errlen);
}

/* accept: [rows, scale, bound]: checks whose finding the user means (a warning, not an error). */
static int read_accept(YdDoc *doc, Calib *c, char *err, size_t errlen) {
  static const char *names[3] = {"rows", "scale", "bound"};
  YdNode            *v        = yd_get(doc->root, "accept");
  if (!v) return 0;
  if (yd_expect(doc, v, YD_SEQUENCE, "accept", err, errlen)) return 1;
  for (size_t i = 0; i < v->n; i++) {
    const char *s;
    char        sub[32];
    int         bit = 0;
    snprintf(sub, sizeof sub, "accept[%zu]", i);
    if (yd_string(doc, v->items[i], sub, &s, err, errlen)) return 1;
    for (int k = 0; k < 3; k++)
      if (!strcmp(s, names[k])) bit = 1 << k;
    if (!bit) FAIL("%s:%d: key '%s': expected rows, scale or bound, got '%s'", doc->file, v->items[i]->line, sub, s);
    c->accept |= bit;
  }
  return 0;
}

/* refine: auto (default: when the forward model's bias exceeds the standard error) | yes | no. */
static int read_refine(YdDoc *doc, Calib *c, char *err, size_t errlen) {
  const char *s;
  YdNode     *v = yd_get(doc->root, "refine");
  int         refs = 0;
  c->refine       = 1;
  for (int j = 0; j < c->nrun; j++) refs += c->run[j].reference[0] != 0;
  if (!v) return 0;
  if (yd_string(doc, v, "refine", &s, err, errlen)) return 1;
  if (strcmp(s, "auto") && strcmp(s, "yes") && strcmp(s, "no"))
    FAIL("%s:%d: key 'refine': expected auto (on the full model when the forward model's bias exceeds the standard "
         "error), yes or no, got '%s'", doc->file, v->line, s);
  c->refine = !strcmp(s, "no") ? 0 : !strcmp(s, "yes") ? 2 : 1;
  if (c->refine == 2 && !refs)
    FAIL("%s:%d: key 'refine': yes needs a full model: no run has a reference (runs[k].reference)", doc->file, v->line);
  return 0;
}

/* weighting: range (default: each block's residuals divided by its data's range, blocks of different units alike) |
 * noise (by the noise of its data column: the maximum-likelihood weighting of independent errors). */
static int read_weighting(YdDoc *doc, Calib *c, char *err, size_t errlen) {
  const char *s;
  YdNode     *v = yd_get(doc->root, "weighting");
  if (!v) return 0;
  if (yd_string(doc, v, "weighting", &s, err, errlen)) return 1;
  if (strcmp(s, "range") && strcmp(s, "noise"))
    FAIL("%s:%d: key 'weighting': expected range (each block by its data's range) or noise (by its data column's noise, "
         "from its second differences), got '%s'", doc->file, v->line, s);
  for (int j = 0; j < c->nrun; j++) c->run[j].weighting = strcmp(s, "noise") ? CAL_WEIGHT_RANGE : CAL_WEIGHT_NOISE;
  return 0;
}

/* refine_runs: the refinement's full-model runs at most (default 6). */
static int read_refine_runs(YdDoc *doc, Calib *c, char *err, size_t errlen) {
  YdNode *v      = yd_get(doc->root, "refine_runs");
  c->refine_runs = 6;
  return v && yd_int_range(doc, v, "refine_runs", 1, CAL_REFINE_CAP, &c->refine_runs, err, errlen);
}

static int read_scene(YdDoc *doc, Calib *c, const char *outdir, char *err, size_t errlen) {
  const char *s;
  YdNode     *v;
  snprintf(c->name, sizeof c->name, "calibrate");
  if ((v = yd_get(doc->root, "name")) && !yd_string(doc, v, "name", &s, err, errlen)) snprintf(c->name, sizeof c->name, "%s", s);
  else if (v) return 1;
  YdNode *ps = yd_require(doc, doc->root, "parameters", YD_SEQUENCE, "parameters", err, errlen);
  if (!ps) return 1;
  if (ps->n < 1 || ps->n > CAL_MAX_PARAMS)
    FAIL("%s:%d: key 'parameters': expected 1 to %d parameters, got %zu", doc->file, ps->line, CAL_MAX_PARAMS, ps->n);
  c->np = (int)ps->n;
  for (int k = 0; k < c->np; k++) {
    if (read_param(doc, ps->items[k], k, &c->p[k], err, errlen)) return 1;
    for (int j = 0; j < k; j++)
      if (c->p[j].slot == c->p[k].slot)
        FAIL("%s:%d: key 'parameters[%d].name': '%s' is fitted twice", doc->file, ps->items[k]->line, k, c->p[k].name);
  }
  YdNode *rs = yd_require(doc, doc->root, "runs", YD_SEQUENCE, "runs", err, errlen);
  if (!rs) return 1;
  if (rs->n < 1 || rs->n > CAL_MAX_RUNS)
    FAIL("%s:%d: key 'runs': expected 1 to %d forward runs, got %zu", doc->file, rs->line, CAL_MAX_RUNS, rs->n);
  for (size_t k = 0; k < rs->n; k++, c->nrun++)
    if (cal_run_read(doc, rs->items[k], (int)k, &c->run[k], err, errlen)) return 1;
  snprintf(c->outdir, sizeof c->outdir, "out/calibrate/%s", c->name);
  YdNode *out = yd_get(doc->root, "output"), *d;
  if (out && (yd_expect(doc, out, YD_MAPPING, "output", err, errlen) ||
              ((d = yd_get(out, "directory")) && yd_string(doc, d, "output.directory", &s, err, errlen)) ||
              yd_check_unused(doc, out, "output", "directory", err, errlen)))
    return 1;
  if (out && yd_get(out, "directory")) snprintf(c->outdir, sizeof c->outdir, "%s", s);
  if (outdir && outdir[0]) snprintf(c->outdir, sizeof c->outdir, "%s", outdir);
  if (read_accept(doc, c, err, errlen) || read_refine(doc, c, err, errlen) || read_refine_runs(doc, c, err, errlen) ||
      read_weighting(doc, c, err, errlen))
    return 1;
  return yd_check_unused(doc, doc->root, "", "scene, name, parameters, runs, refine, refine_runs, weighting, accept, output",
                         err, errlen);
}

/* TAO's residual routine: a failed evaluation is rejected (a large residual), not fatal. */
static PetscErrorCode tao_residual(Tao tao, Vec U, Vec R, void *ctx) {
  Calib             *c = ctx;
  const PetscScalar *u;
  PetscScalar       *r;
  char               tag[32], err[1024] = "";
  double             uu[CAL_MAX_PARAMS], f = 0, t0 = MPI_Wtime();
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(U, &u));
  for (int k = 0; k < c->np; k++) uu[k] = PetscMin(1, PetscMax(0, PetscRealPart(u[k])));
  PetscCall(VecRestoreArrayRead(U, &u));
  PetscCall(VecGetArray(R, &r));
  snprintf(tag, sizeof tag, "e%04d", ++c->nevals);
  int runs = c->nforward, bad = cal_evaluate(c, uu, r, tag, err, sizeof err);
  for (int i = 0; i < c->m; i++) {
    if (bad) r[i] = c->penalty;
    f += r[i] * r[i];
  }
  PetscCall(VecRestoreArray(R, &r));
  if (bad) {
    c->nrejected++;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  evaluation %d rejected: %s\n", c->nevals, err));
  } else if (f < c->best_f) {
    c->best_f = f;
    memcpy(c->best_u, uu, sizeof uu);
  }
  fprintf(c->evals, "%d,%d", c->nevals, !bad);
  for (int k = 0; k < c->np; k++) fprintf(c->evals, ",%.10g", cal_param(&c->p[k], uu[k]));
  fprintf(c->evals, ",%.10g,%d,%.3f\n", bad ? NAN : f, c->nforward - runs, MPI_Wtime() - t0);
  fflush(c->evals);
  PetscFunctionReturn(0);
}

static PetscErrorCode tao_monitor(Tao tao, void *ctx) {
  Calib             *c = ctx;
  PetscInt           its;
  PetscReal          f;
  Vec                U;
  const PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(TaoGetSolutionStatus(tao, &its, &f, NULL, NULL, NULL, NULL));
  PetscCall(TaoGetSolution(tao, &U));
  PetscCall(VecGetArrayRead(U, &u));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "iteration %3d  misfit (sum of squares) %.6e ", (int)its, (double)f));
  for (int k = 0; k < c->np; k++)
    PetscCall(PetscPrintf(PETSC_COMM_SELF, " %s %.6g", c->p[k].name, cal_param(&c->p[k], PetscRealPart(u[k]))));
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  forward runs %d (%d rejected evaluations)  wall %.1f s\n", c->nforward,
                        c->nrejected, MPI_Wtime() - c->wall0));
  PetscCall(VecRestoreArrayRead(U, &u));
  c->iterations = (int)its;
  PetscFunctionReturn(0);
}

/* TAO's own tests, and a stop on no progress: the iterate and the misfit unchanged over two iterations (POUNDERS
 * went on evaluating the same point after convergence: 3-4 iterations seen; the cache makes those free). */
static PetscErrorCode converged(Tao tao, void *ctx) {
  Calib             *c = ctx;
  TaoConvergedReason why;
  PetscReal          f;
  PetscInt           its;
  Vec                U;
  const PetscScalar *u;
  PetscFunctionBeginUser;
  PetscCall(TaoDefaultConvergenceTest(tao, NULL));
  PetscCall(TaoGetConvergedReason(tao, &why));
  PetscCall(TaoGetSolutionStatus(tao, &its, &f, NULL, NULL, NULL, NULL));
  PetscCall(TaoGetSolution(tao, &U));
  PetscCall(VecGetArrayRead(U, &u));
  int same = its > 0 && f >= c->last_f;
  for (int k = 0; k < c->np; k++) same &= PetscRealPart(u[k]) == c->last_u[k], c->last_u[k] = PetscRealPart(u[k]);
  PetscCall(VecRestoreArrayRead(U, &u));
  c->last_f  = f;
  c->stalled = same ? c->stalled + 1 : 0;
  if (why == TAO_CONTINUE_ITERATING && c->stalled >= 2) {
    c->no_progress = 1;
    PetscCall(TaoSetConvergedReason(tao, TAO_CONVERGED_USER));
  }
  PetscFunctionReturn(0);
}

/* TAO over u in [0, 1]^n from the start; its solution and converged reason. */
static PetscErrorCode solve(Calib *c, double *u, PetscInt *its, char *reason, size_t rlen) {
  Tao                tao;
  Vec                U, R, L, H;
  TaoType            type;
  TaoConvergedReason why;
  PetscScalar       *a;
  PetscFunctionBeginUser;
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->np, &U));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, c->m, &R));
  PetscCall(VecDuplicate(U, &L));
  PetscCall(VecDuplicate(U, &H));
  PetscCall(VecSet(L, 0));
  PetscCall(VecSet(H, 1));
  PetscCall(VecGetArray(U, &a));
  for (int k = 0; k < c->np; k++) a[k] = u[k];
  PetscCall(VecRestoreArray(U, &a));
  PetscCall(TaoCreate(PETSC_COMM_SELF, &tao));
  PetscCall(TaoSetType(tao, TAOPOUNDERS));
  PetscCall(TaoSetSolution(tao, U));
  PetscCall(TaoSetResidualRoutine(tao, R, tao_residual, c));
  PetscCall(TaoSetVariableBounds(tao, L, H));
  PetscCall(TaoSetTolerances(tao, 1e-9, 0, 1e-4)); /* gatol; gttol: the gradient reduced 1e4 times */
  PetscCall(TaoSetMaximumFunctionEvaluations(tao, 60));
  PetscCall(TaoSetMonitor(tao, tao_monitor, c, NULL));
  PetscCall(TaoSetConvergenceTest(tao, converged, c));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoGetType(tao, &type));
  snprintf(c->tao_type, sizeof c->tao_type, "%s", type);
  PetscCall(TaoSolve(tao));
  PetscCall(TaoGetSolutionStatus(tao, its, NULL, NULL, NULL, NULL, &why));
  snprintf(reason, rlen, "%s", c->no_progress ? "NO_PROGRESS (the iterate and misfit unchanged over 2 iterations)"
                                                : TaoConvergedReasons[why]);
  PetscCall(VecGetArray(U, &a));
  for (int k = 0; k < c->np; k++) u[k] = PetscRealPart(a[k]);
  PetscCall(VecRestoreArray(U, &a));
  PetscCall(TaoDestroy(&tao));
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&R));
  PetscCall(VecDestroy(&L));
  PetscCall(VecDestroy(&H));
  PetscFunctionReturn(0);
}

/* TAO's solve; with a drift fitted (drift: fit), two: first with the drift rates held at 0, then with them profiled
 * out, from the first's fit. A drift fitted from the start can take up the material's creep instead: at a viscosity
 * too high the model hardly creeps and a steeper drift explains the depth's rise, a second minimum of the misfit
 * (the nano record with 1 nm noise and 0.05 nm/s drift: from 3x above the truth, eta_soft 4.0e10 and 0.107 nm/s
 * at a misfit of 2.09; from the fit without drift, 1.28e10 and 0.049 nm/s at 1.81). */
static PetscErrorCode solve_with_drift(Calib *c, double *u, PetscInt *its, char *reason, size_t rlen) {
  PetscInt first = 0;
  int      fit   = 0;
  PetscFunctionBeginUser;
  for (int j = 0; j < c->nrun; j++) fit |= c->run[j].drift == CAL_DRIFT_FIT;
  if (fit) {
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "drift: fit: the parameters first with the drift held at 0, then with the drift "
                          "rate profiled out from there (a drift fitted from the start can take up the creep)\n"));
    c->drift_held = 1;
    PetscCall(solve(c, u, &first, reason, rlen));
    c->drift_held = 0, c->stalled = 0, c->no_progress = 0, c->best_f = INFINITY;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "drift: fit: the drift held at 0: %s after %d iterations; now with the drift rate "
                          "fitted\n", reason, (int)first));
  }
  PetscCall(solve(c, u, its, reason, rlen));
  *its += first;
  PetscFunctionReturn(0);
}

/* What each run's forward runs follow, and its full model: said in the log. */
static PetscErrorCode describe_run(Calib *c, const CalRun *run) {
  char buf[4096];
  PetscFunctionBeginUser;
  if (run->drive) {
    cal_protocol_describe(run, buf, sizeof buf);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "run '%s': the forward runs follow the data's history (drive: data), %d stages from %s%s%s:\n%s\n"
                          "  forward scene %s: %s's stages replaced by the data's\n", run->name, run->nstage,
                          run->stages_from_column ? "the data's column '" : "the load curve (loading, hold within 1 % of the peak, unloading)",
                          run->stages_from_column ? run->stage_col : "", run->stages_from_column ? "'" : "", buf, run->driven, run->scene));
  } else
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "run '%s': the forward runs follow the stages of %s (drive: scene)\n", run->name, run->scene));
  cal_ranges_describe(run, buf, sizeof buf);
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", buf));
  if (run->drive) {
    cal_load_describe(run, buf, sizeof buf);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s\n", buf));
  }
  if (run->drift == CAL_DRIFT_MEASURED)
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  drift: %.4g +- %.2g %s/s measured in the data's stage '%s' (a line through depth "
                          "against time over its %d rows; %.4g in the data's depth unit per s), removed from every depth "
                          "(ISO 14577-1; Oliver & Pharr 1992)\n", run->drift_rate, run->drift_se, run->scene_unit[2],
                          run->stage[run->drift_stage].name, run->drift_rows, run->drift_rate / run->factor[2]));
  else if (run->drift == CAL_DRIFT_FIT)
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  drift: fitted beside the parameters (a constant rate from the data's first row, "
                          "profiled out of each evaluation's residuals)\n"));
  if (run->reference[0])
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  full model (reference%s): %s, run at the fit for the forward model's bias\n",
                          run->reference_default ? ", the default beside the forward scene" : "", run->reference));
  else PetscCall(PetscPrintf(PETSC_COMM_SELF, "  no full model (reference): the forward model's bias is not measured\n"));
  PetscFunctionReturn(0);
}

/* The first evaluation, at the start: every error here is the input's (fatal: 1), or a PETSc error code. */
static int start(Calib *c, double *u, char *err, size_t errlen) {
  double *r = malloc(sizeof(double) * 1), p[CAL_MAX_PARAMS];
  int     m = 0;
  for (int k = 0; k < c->np; k++) u[k] = param_u(&c->p[k], c->p[k].start), p[k] = c->p[k].start;
  for (int j = 0; j < c->nrun; j++) {
    CalRun *run = &c->run[j];
    char    dir[PATH_MAX + 200];
    PetscErrorCode ierr = describe_run(c, run);
    if (ierr) return free(r), stage_runner_status(ierr, err);
    if (cal_check_load_scale(run, c->accept, err, errlen)) return free(r), 1;
    snprintf(dir, sizeof dir, "%s/forward/start_%s", c->outdir, run->name);
    int rc = cal_forward(c, run, cal_run_scene(run, 0), p, dir);
    if (rc) {
      double pmax = 0;
      for (int i = 0; run->drive && i < run->rows; i++) pmax = fmax(pmax, run->data[i * run->ncol + run->col_load]);
      free(r);
      if (run->drive)
        FAIL("%s:%d: key 'runs[%d].scene': the forward run at the start failed (exit code %d; its log: %s/forward.log), driven "
             "by the data's loads up to %g (after runs[%d].data.factors.load = %g): are they in the units of %s?", run->file,
             run->line, run->index, rc, dir, pmax, run->index, run->factor[1], run->scene);
      FAIL("%s:%d: key 'runs[%d].scene': the forward run at the start failed (exit code %d; its log: %s/forward.log)", run->file,
           run->line, run->index, rc, dir);
    }
    if (cal_run_setup(run, dir, err, errlen) || cal_check_rows(run, dir, c->accept, err, errlen) ||
        cal_check_scale(run, dir, c->accept, 0, err, errlen))
      return free(r), 1;
    for (int role = 2; run->weighting == CAL_WEIGHT_NOISE && role <= 3; role++) {
      int given = role == 2 ? run->col_depth >= 0 : run->col_value >= 0;
      ierr = !given ? 0 : isnan(run->noise[role])
        ? PetscPrintf(PETSC_COMM_SELF, "  weighting: noise: the %s column's noise is below 1e-6 of its range (a clean "
                      "record): its blocks keep their ranges\n", role == 2 ? "depth" : "value")
        : PetscPrintf(PETSC_COMM_SELF, "  weighting: noise: each %s block's residuals divided by the %s column's noise, %.4g "
                      "(%.4g in the data's unit; from its second differences along the blocks)\n", role == 2 ? "depth" : "value",
                      role == 2 ? "depth" : "value", run->noise[role], run->noise[role] / fabs(run->factor[role]));
      if (ierr) return free(r), stage_runner_status(ierr, err);
    }
    int n = cal_run_size(run);
    r     = realloc(r, sizeof(double) * (size_t)(m + n));
    if (cal_run_residual(run, dir, r + m, err, errlen) || cal_check_scale(run, dir, c->accept, 1, err, errlen))
      return free(r), 1;
    m += n;
  }
  c->m = m;
  double f = 0, rmax = 0;
  for (int i = 0; i < m; i++) f += r[i] * r[i], rmax = fmax(rmax, fabs(r[i]));
  c->penalty = 10 * fmax(1, rmax), c->best_f = f;
  memcpy(c->best_u, u, sizeof(double) * c->np);
  cal_cache_add(c, u, r); /* TAO's first evaluation is this one */
  free(r);
  if (m < c->np) FAIL("%s: key 'runs': %d data points for %d parameters: need at least as many points", c->doc->file, m, c->np);
  return stage_runner_status(PetscPrintf(PETSC_COMM_SELF, "calibrate %s: %d parameters, %d runs, %d residuals; misfit at the start %.6e\n",
                                         c->name, c->np, c->nrun, m, f), err);
}

/* drive: data: the forward scenes that follow each run's data, written into the output directory. */
static int write_protocols(Calib *c, char *err, size_t errlen) {
  for (int j = 0; j < c->nrun; j++)
    if (c->run[j].drive && cal_protocol_write(&c->run[j], c->outdir, err, errlen)) return 1;
  return 0;
}

/* -calibrate_load_draws (declared with the driver's options, app/main.c); -calibrate_dry_run: say what each run's forward
 * runs follow, write the scenes that follow the data, and stop. */
static PetscErrorCode dry_run(Calib *c, PetscBool *dry) {
  PetscInt draws = CAL_LOAD_DRAWS;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-calibrate_load_draws", &draws, NULL));
  c->load_draws = (int)draws;
  *dry = PETSC_FALSE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-calibrate_dry_run", dry, NULL));
  for (int j = 0; *dry && j < c->nrun; j++) PetscCall(describe_run(c, &c->run[j]));

  if (*dry) PetscCall(PetscPrintf(PETSC_COMM_SELF, "calibrate %s: -calibrate_dry_run: nothing run; the scenes are in %s/protocol\n", c->name, c->outdir));
  PetscFunctionReturn(0);
}

int calibrate_run(YdDoc *doc, const char *outdir, char *err, size_t errlen) {
  Calib   *c = calloc(1, sizeof *c);
  double   u[CAL_MAX_PARAMS];
  PetscInt its    = 0;
  char     reason[128], file[PATH_MAX + 32];
  int      rc     = 2, bad;
  PetscBool      dry;
  PetscErrorCode ierr;
  c->doc          = doc;
  c->wall0        = MPI_Wtime();
  ssize_t len     = readlink("/proc/self/exe", c->exe, sizeof c->exe - 1);
  if (len <= 0) snprintf(err, errlen, "calibrate: cannot find the driver's own executable (/proc/self/exe)");
  else if (read_scene(doc, c, outdir, err, errlen)) {
  } else if (fs_prepare_output_dir(c->outdir, err, errlen) || write_protocols(c, err, errlen)) {
  } else if ((ierr = dry_run(c, &dry)) || dry) {
    rc = stage_runner_status(ierr, err);
    for (int j = 0; !ierr && j < c->nrun && !rc; j++) /* the checks that need no forward run */
      if (cal_check_load_scale(&c->run[j], c->accept, err, errlen)) rc = 2;
  } else if ((bad = start(c, u, err, errlen))) {
    if (bad > 2) rc = bad; /* a PETSc error; else the input's (2) */
  } else {
    rc = 1;
    snprintf(file, sizeof file, "%s/evaluations.csv", c->outdir);
    if (!(c->evals = fopen(file, "w"))) snprintf(err, errlen, "calibrate: cannot write %s", file);
    else {
      fprintf(c->evals, "evaluation,ok");
      for (int k = 0; k < c->np; k++) fprintf(c->evals, ",%s", c->p[k].name);
      fprintf(c->evals, ",misfit,forward_runs,wall\n");
      if ((ierr = solve_with_drift(c, u, &its, reason, sizeof reason))) rc = stage_runner_status(ierr, err);
      else rc = (bad = cal_report(c, u, its, reason, err, errlen)) > 2 ? bad : bad ? 1 : 0;
      fclose(c->evals);
    }
  }
  for (int j = 0; j < c->nrun; j++) cal_run_free(&c->run[j]);
  free(c->cache), free(c);
  return rc;
}
