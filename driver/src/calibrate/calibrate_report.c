/* The report of a calibration: the Jacobian at the fit by central differences (in the [0, 1] variables TAO
 * works on), standard errors for residuals correlated along a curve (Newey-West, calibrate_stats.c; the white
 * s^2 (J^T J)^-1 beside them), the fitted drift rates and theirs, correlations, the hold blocks' trends, the data
 * against the fitted curves (curves.csv), the forward model's error against its reference (the full model),
 * fit.yaml. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "../io/json_write.h"
#include "../stepping/run_status.h"
#include "calibrate_drift.h"
#include "calibrate_load.h"
#include "calibrate_protocol.h"
#include "calibrate_refine.h"
#include "calibrate_report.h"
#include "calibrate_residual.h"
#include "calibrate_stats.h"
#include "calibrate_yaml.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define CAL_FD_STEP 0.01 /* in u: 1 % of the bounds' span (of its logarithm on a log scale) */

/* J (m x n, column-major by parameter) at u by central differences, one-sided at a bound or where a forward run
 * fails on one side (the fit itself then the other point; said in the log); dd (n x nrun): each run's fitted drift
 * rate's derivative (drift: fit; 0 otherwise). */
static int jacobian(Calib *c, const double *u, double *J, double *dd, char *err, size_t errlen) {
  double *rp = malloc(sizeof(double) * c->m * 2), *rm = rp + c->m, dp[CAL_MAX_RUNS], dm[CAL_MAX_RUNS];
  for (int k = 0; k < c->np; k++) {
    double up[CAL_MAX_PARAMS], um[CAL_MAX_PARAMS];
    char   tag[32], msg[1024];
    memcpy(up, u, sizeof(double) * c->np), memcpy(um, u, sizeof(double) * c->np);
    up[k] = fmin(1, u[k] + CAL_FD_STEP), um[k] = fmax(0, u[k] - CAL_FD_STEP);
    for (int side = 0; side < 2; side++) {
      double *x = side ? um : up, *r = side ? rm : rp, *d = side ? dm : dp;
      snprintf(tag, sizeof tag, "jac%d_%s", k, side ? "minus" : "plus");
      if (cal_evaluate(c, x, r, tag, msg, sizeof msg)) {
        PetscPrintf(PETSC_COMM_SELF, "  the Jacobian's %s point of %s failed (%s): a one-sided difference from the fit\n",
                    side ? "lower" : "upper", c->p[k].name, msg);
        memcpy(x, u, sizeof(double) * c->np);
        if (up[k] == um[k] || cal_evaluate(c, x, r, "fit", err, errlen)) {
          if (up[k] == um[k]) snprintf(err, errlen, "%s", msg);
          return free(rp), 1;
        }
      }
      for (int j = 0; j < c->nrun; j++) d[j] = c->run[j].drift_rate;
    }
    for (int i = 0; i < c->m; i++) J[k * c->m + i] = (rp[i] - rm[i]) / (up[k] - um[k]);
    for (int j = 0; j < c->nrun; j++) dd[k * c->nrun + j] = c->run[j].drift == CAL_DRIFT_FIT ? (dp[j] - dm[j]) / (up[k] - um[k]) : 0;
  }
  free(rp);
  return 0;
}

/* The uncertainty of the fit at u: Newey-West standard errors of the parameters and of the fitted drift rates (their
 * influence on the residuals' errors: d = -a.e / a.a + sum_k dd_k du_k), the white ones beside them, and each hold
 * block's trend. X: the fit's columns (J and the drift regressors), filled for the trend check; cov (n x n). */
static void uncertainty(Calib *c, const double *u, const double *J, const double *dd, const double *r, double *inv,
                        double *cov, CalUncertainty *un) {
  int     n = c->np, m = c->m, q = n, drun[CAL_MAX_RUNS], blocks[CAL_MAX_RUNS * CAL_MAX_CURVES], nblock;
  double *G = malloc(sizeof(double) * m * (n + CAL_MAX_RUNS)), *X = malloc(sizeof(double) * m * (n + CAL_MAX_RUNS));
  double  full[(CAL_MAX_PARAMS + CAL_MAX_RUNS) * (CAL_MAX_PARAMS + CAL_MAX_RUNS)];
  double  white[(CAL_MAX_PARAMS + CAL_MAX_RUNS) * (CAL_MAX_PARAMS + CAL_MAX_RUNS)];
  memset(un, 0, sizeof *un);
  cal_influence(n, m, J, G, inv);
  memcpy(X, J, sizeof(double) * m * n);
  for (int j = 0, off = 0; j < c->nrun; off += cal_run_size(&c->run[j]), j++) { /* the drift rates' rows */
    un->drift_se[j] = NAN;
    if (c->run[j].drift != CAL_DRIFT_FIT) continue;
    double *a = X + (size_t)q * m, *g = G + (size_t)q * m, aa = 0;
    for (int i = 0; i < m; i++) a[i] = 0;
    cal_drift_regressor(&c->run[j], a + off);
    for (int i = 0; i < m; i++) aa += a[i] * a[i];
    for (int i = 0; i < m; i++) {
      g[i] = aa > 0 ? -a[i] / aa : 0;
      for (int k = 0; k < n; k++) g[i] += dd[k * c->nrun + j] * G[k * m + i];
    }
    drun[q - n] = j, q++;
  }
  cal_blocks(c->run, c->nrun, blocks, &nblock);
  cal_hac(q, m, G, r, blocks, nblock, q, full, white, &un->hac);
  for (int a = 0; a < n; a++) {
    for (int b = 0; b < n; b++) cov[a * n + b] = full[a * q + b];
    un->se[a]    = sqrt(full[a * q + a]) * cal_dparam(&c->p[a], u[a]);
    un->white[a] = sqrt(white[a * q + a]) * cal_dparam(&c->p[a], u[a]);
  }
  for (int k = n; k < q; k++) un->drift_se[drun[k - n]] = sqrt(full[k * q + k]);
  for (int j = 0, off = 0; j < c->nrun; off += cal_run_size(&c->run[j]), j++) { /* a measured drift's own uncertainty */
    if (c->run[j].drift != CAL_DRIFT_MEASURED || !(c->run[j].drift_se > 0)) continue;
    double *a = malloc(sizeof(double) * cal_run_size(&c->run[j]));
    cal_drift_regressor(&c->run[j], a);
    for (int k = 0; k < n; k++) { /* an error e in the rate removed leaves e a in the residuals: du = G a e */
      double ga = 0;
      for (int i = 0; i < cal_run_size(&c->run[j]); i++) ga += G[k * m + off + i] * a[i];
      un->se[k] = sqrt(un->se[k] * un->se[k] + pow(ga * c->run[j].drift_se * cal_dparam(&c->p[k], u[k]), 2));
    }
    free(a);
  }
  for (int a = 0; a < n; a++) { /* G r: the Gauss-Newton step from the fit */
    double du = 0;
    for (int i = 0; i < m; i++) du += G[a * m + i] * r[i];
    un->step[a] = cal_param(&c->p[a], fmin(1, fmax(0, u[a] + du))) - cal_param(&c->p[a], u[a]);
  }
  un->ntrend = cal_hold_trends(c->run, c->nrun, c->m, X, q, r, un->trend, CAL_MAX_RUNS * CAL_MAX_CURVES);
  free(G), free(X);
}

/* One draw of the fitted load histories' uncertainty (cal_load_draw) into rd: every run that follows a fitted history
 * run at the parameters p with its knots moved (its scene and tables under D/forward/loadI), its residuals (the fitted
 * drift profiled out, as at the fit) into rd; the other runs' are the fit's, r. Each run's own scenes stay its own. */
static int load_draw(Calib *c, const double *p, int draw, const double *r, double *rd, char *err, size_t errlen) {
  memcpy(rd, r, sizeof(double) * c->m);
  for (int j = 0, off = 0; j < c->nrun; off += cal_run_size(&c->run[j]), j++) {
    CalRun *run = &c->run[j];
    char    dir[PATH_MAX + 64], runs[PATH_MAX + 128], driven[PATH_MAX], driven_reference[PATH_MAX];
    if (!run->load_fitted) continue;
    double *keep = run->knot_p, *moved = malloc(sizeof(double) * (size_t)run->nknot);
    memcpy(driven, run->driven, sizeof driven), memcpy(driven_reference, run->driven_reference, sizeof driven_reference);
    cal_load_draw(run, draw, moved);
    run->knot_p = moved;
    snprintf(dir, sizeof dir, "%s/forward/load%d", c->outdir, draw);
    snprintf(runs, sizeof runs, "%s/%s", dir, run->name);
    int bad = cal_protocol_write(run, dir, err, errlen) || cal_evaluate_run(c, run, p, runs, 0, rd + off, err, errlen);
    run->knot_p = keep, free(moved);
    memcpy(run->driven, driven, sizeof driven), memcpy(run->driven_reference, driven_reference, sizeof driven_reference);
    if (bad) return 1;
    if (run->drift == CAL_DRIFT_FIT) cal_drift_project(run, rd + off);
  }
  return 0;
}

/* The fitted load histories' share of the standard errors (docs/calibrate.md, "A noisy load"). A run that follows a
 * fitted history follows one estimate of the load: its knots carry the load's noise, covariance sigma^2 N^-1
 * (calibrate_load.c), which the data's part does not hold. To first order the parameters move by du = G dr, dr the
 * residuals' change under a change dc of the knots (G = -(J^T J)^-1 J^T, as for the data's part), so
 * var(du_a) = E[(w.z)^2] = |w|^2 for dc = sigma L^-T z, z of independent random signs, w fixed: Hutchinson's (1990)
 * estimator, here the mean of (du_a)^2 over c->load_draws forward runs at the fit (its relative spread at most
 * sqrt(2 / draws)). NAN without a fitted history, with no draws, or when a draw's run fails (said in the log). */
static PetscErrorCode load_share(Calib *c, const double *u, const double *J, const double *inv, const double *r, CalUncertainty *un) {
  int     n = c->np, m = c->m, any = 0;
  double  p[CAL_MAX_PARAMS], var[CAL_MAX_PARAMS] = {0}, coef[CAL_MAX_PARAMS + CAL_MAX_RUNS], *rd;
  char    msg[1024];
  PetscFunctionBeginUser;
  for (int k = 0; k < n; k++) un->load[k] = NAN, p[k] = cal_param(&c->p[k], u[k]);
  for (int j = 0; j < c->nrun; j++) any |= c->run[j].load_fitted;
  if (!any || c->load_draws < 1) PetscFunctionReturn(0);
  PetscCall(PetscMalloc1(m, &rd));
  for (int i = 0; i < c->load_draws; i++) {
    if (load_draw(c, p, i, r, rd, msg, sizeof msg)) {
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "warning: the fitted load history's share of the standard errors is not measured: "
                            "draw %d: %s\n", i, msg));
      PetscCall(PetscFree(rd));
      PetscFunctionReturn(0);
    }
    for (int l = 0; l < m; l++) rd[l] -= r[l];
    cal_normal_coef(n, m, J, inv, rd, coef);
    for (int k = 0; k < n; k++) var[k] += coef[k] * coef[k] / c->load_draws;
  }
  for (int k = 0; k < n; k++) un->load[k] = sqrt(var[k]) * cal_dparam(&c->p[k], u[k]);
  PetscCall(PetscFree(rd));
  PetscFunctionReturn(0);
}

/* The data against the fitted curves: curves.csv (run, block, x, y, data, model). */
static int write_curves(Calib *c, char *err, size_t errlen) {
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/curves.csv", c->outdir);
  FILE *fp = fopen(file, "w");
  if (!fp) FAIL("calibrate: cannot write %s", file);
  fprintf(fp, "run,block,x_name,y_name,x,data,model,drift,stage\n");
  for (int j = 0; j < c->nrun; j++) cal_run_write_curves(&c->run[j], fp);
  fclose(fp);
  return 0;
}

/* A parameter at one of its bounds (the fit's, or the refined one): the bound's key, or NULL. */
static const char *at_bound(const CalParam *p, double v) {
  if (fabs(v - p->lo) <= 1e-6 * fabs(p->hi - p->lo) || (p->log && fabs(log(v / p->lo)) <= 1e-6 * log(p->hi / p->lo))) return "min";
  if (fabs(v - p->hi) <= 1e-6 * fabs(p->hi - p->lo) || (p->log && fabs(log(v / p->hi)) <= 1e-6 * log(p->hi / p->lo))) return "max";
  return NULL;
}

/* Why the refinement did not converge, from its steps (relative to the value), and what to do. */
static void not_converged(const Calib *c, const CalBias *b, char *buf, size_t n) {
  int    k = 0, ns = b->nsteps, swing = 1, shrink = 1;
  char   steps[256] = "";
  for (int a = 1; a < c->np; a++) /* the parameter whose last step is the largest */
    if (fabs(b->steps[ns - 1][a]) > fabs(b->steps[ns - 1][k])) k = a;
  for (int s = 0; s < ns; s++) {
    size_t len = strlen(steps);
    snprintf(steps + len, sizeof steps - len, "%s%+.2g %%", s ? ", " : "", 100 * b->steps[s][k]);
    if (s > 0) {
      swing &= b->steps[s][k] * b->steps[s - 1][k] < 0;
      shrink &= fabs(b->steps[s][k]) < 0.7 * fabs(b->steps[s - 1][k]);
    }
  }
  if (ns == 1)
    snprintf(buf, n, "one step in %s (%s) is all it had: give it more full-model runs (refine_runs: %d, now %d)", c->p[k].name,
             steps, 2 * c->refine_runs > CAL_REFINE_CAP ? CAL_REFINE_CAP : 2 * c->refine_runs, c->refine_runs);
  else if (ns >= 3 && swing)
    snprintf(buf, n, "its steps in %s swing from side to side (%s): the full model's misfit is not smooth in it at this "
             "scale, or the forward model's slope is far from the full model's. What to do: give a forward model nearer "
             "the full model (X_mid rather than X_fast), or a full model with smooth outputs (its error control at a tight "
             "tolerance; a noisy load history: load_history: fitted); or quote the forward model's fit with its bias "
             "(bias.first_estimate in fit.yaml) as its model error", c->p[k].name, steps);
  else if (ns >= 2 && shrink)
    snprintf(buf, n, "its steps in %s shrink (%s) but had not reached a fifth of the standard error: give it more "
             "full-model runs (refine_runs: %d, now %d), or a forward model nearer the full model", c->p[k].name, steps,
             2 * c->refine_runs > CAL_REFINE_CAP ? CAL_REFINE_CAP : 2 * c->refine_runs, c->refine_runs);
  else
    snprintf(buf, n, "its steps in %s do not shrink (%s): the forward model's Jacobian does not lead the full model's fit; "
             "give a forward model nearer the full model (X_mid rather than X_fast), or more full-model runs "
             "(refine_runs: %d, now %d)", c->p[k].name, steps, 2 * c->refine_runs > CAL_REFINE_CAP ? CAL_REFINE_CAP :
             2 * c->refine_runs, c->refine_runs);
}

/* Bound and reference failures after fit.yaml is written: an error unless accepted (accept: [bound]). */
static int final_checks(Calib *c, const double *u, const CalBias *b, char *err, size_t errlen) {
  char file[PATH_MAX + 32], why[1024];
  snprintf(file, sizeof file, "%s/fit.yaml", c->outdir);
  if (b->failed[0])
    FAIL("%s (fit.yaml has the forward model's fit; its bias is not known): %s", b->failed, file);
  if (b->refined && !b->converged) {
    not_converged(c, b, why, sizeof why);
    FAIL("%s: key 'refine': the refinement on the full model did not converge in %d full-model runs: %s. Its last value "
         "is in %s (quote), its last step counted in the standard error's model part", c->doc->file, b->nfull, why, file);
  }
  for (int k = 0; k < c->np; k++) {
    const CalParam *p = &c->p[k];
    double          v = b->refined ? b->p[k] : cal_param(p, u[k]);
    const char     *w = at_bound(p, v);
    if (!w) continue;
    if (c->accept & CAL_ACCEPT_BOUND) {
      PetscErrorCode ierr = PetscPrintf(PETSC_COMM_SELF, "warning: %s ended at its bound %s = %g (accepted: accept: [bound])\n", p->name, w, v);
      if (ierr) return stage_runner_status(ierr, err);
      continue;
    }
    FAIL("%s:%d: key 'parameters[%d].%s': %s ended at its bound %s = %g: the data want a value beyond it. Widen the bounds, "
         "or check the data's units (runs[k].data.factors) and the forward scene; a fit at a bound is no fit (its standard "
         "error means nothing). The fit is in %s; accept: [bound] to accept it", c->doc->file, p->line, k, w, p->name, w, v,
         file);
  }
  return 0;
}

/* summary.json of the calibration (docs/driver.md, "summary.json"): the fitted parameters as quoted (value and
   standard error), the misfit, TAO's ending, the counters and the cost (CPU: the driver's own and its forward runs'). */
static int write_summary(Calib *c, const double *u, const CalUncertainty *un, const CalBias *b, double ssr, int its,
                         const char *reason, int completed, char *err, size_t errlen) {
  char          part[PATH_MAX + 32];
  struct rusage self, kids;
  FILE         *fp = json_file_open(c->outdir, "summary.json", part, sizeof part, err, errlen);
  if (!fp) return 1;
  json_summary_head(fp, c->name, "calibrate", completed);
  fputs(",\n  \"parameters\": {", fp);
  for (int k = 0; k < c->np; k++) {
    CalQuote q;
    cal_quote(c, u, un, b, k, &q);
    fprintf(fp, "%s\n    ", k ? "," : "");
    json_str(fp, c->p[k].name);
    fputs(": {\"value\": ", fp);
    json_num(fp, q.v);
    fputs(", \"standard_error\": ", fp);
    json_num(fp, q.s);
    fputc('}', fp);
  }
  fputs("\n  },\n  \"misfit\": ", fp);
  json_num(fp, ssr);
  fputs(", \"ended\": ", fp);
  json_str(fp, reason);
  fprintf(fp, ",\n  \"counters\": {\"iterations\": %d, \"evaluations\": %d, \"rejected_evaluations\": %d, \"forward_runs\": %d, "
              "\"full_model_runs\": %d}", its, c->nevals, c->nrejected, c->nforward, c->nfull);
  getrusage(RUSAGE_SELF, &self), getrusage(RUSAGE_CHILDREN, &kids);
  double cpu = self.ru_utime.tv_sec + self.ru_stime.tv_sec + kids.ru_utime.tv_sec + kids.ru_stime.tv_sec +
               1e-6 * (self.ru_utime.tv_usec + self.ru_stime.tv_usec + kids.ru_utime.tv_usec + kids.ru_stime.tv_usec);
  fprintf(fp, ",\n  \"cost\": {\"cpu_s\": %.3f, \"wall_s\": %.3f, \"forward_wall_s\": %.3f}", cpu, MPI_Wtime() - c->wall0,
          c->forward_wall);
  return json_file_close(fp, part, 1, err, errlen);
}

int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen) {
  int     n = c->np, m = c->m;
  double *J = malloc(sizeof(double) * m * n), *r = malloc(sizeof(double) * m), ssr = 0;
  double  inv[CAL_MAX_PARAMS * CAL_MAX_PARAMS], cov[CAL_MAX_PARAMS * CAL_MAX_PARAMS], dd[CAL_MAX_PARAMS * CAL_MAX_RUNS];
  double  drift[CAL_MAX_RUNS];
  CalBias b;
  CalUncertainty *un = calloc(1, sizeof *un);
  char    msg[2048] = "";
  PetscErrorCode ierr = PetscPrintf(PETSC_COMM_SELF, "TAO %s: %s after %d iterations; the Jacobian at the fit by central differences (%d runs)\n",
                                    c->tao_type, reason, (int)its, 2 * n * c->nrun);
  if (ierr) return free(J), free(r), free(un), stage_runner_status(ierr, err);
  if (jacobian(c, u, J, dd, err, errlen)) return free(J), free(r), free(un), 1;
  if (cal_evaluate(c, u, r, "fit", err, errlen)) return free(J), free(r), free(un), 1;
  for (int i = 0; i < m; i++) ssr += r[i] * r[i];
  for (int j = 0; j < c->nrun; j++) drift[j] = c->run[j].drift_rate;
  uncertainty(c, u, J, dd, r, inv, cov, un);
  ierr = load_share(c, u, J, inv, r, un);
  if (!ierr && cal_evaluate(c, u, r, "fit", err, errlen)) return free(J), free(r), free(un), 1; /* the fit's curves and drift */
  if (ierr) return free(J), free(r), free(un), stage_runner_status(ierr, err);
  cal_bias(c, u, J, inv, un->white, &b, msg, sizeof msg); /* refine: auto: the bias against the white standard error */
  for (int j = 0; j < c->nrun; j++) c->run[j].drift_rate = drift[j], c->run[j].drift_se = c->run[j].drift == CAL_DRIFT_FIT ? un->drift_se[j] : c->run[j].drift_se;
  if (write_curves(c, err, errlen)) return free(J), free(r), free(un), 1;
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/fit.yaml", c->outdir);
  FILE *fp = fopen(file, "w");
  if (!fp) return free(J), free(r), free(un), snprintf(err, errlen, "calibrate: cannot write %s", file), 1;
  cal_write_yaml(c, fp, u, un, cov, ssr, its, reason, &b);
  fclose(fp);
  free(J), free(r);
  ierr = cal_print_summary(c, u, un, &b);
  if (!ierr)
    ierr = PetscPrintf(PETSC_COMM_SELF, "calibrate %s: misfit %.6e, %d evaluations (%d rejected), %d forward runs, wall %.1f s -> %s/fit.yaml\n",
                       c->name, ssr, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0, c->outdir);
  int  rc = ierr ? stage_runner_status(ierr, err) : final_checks(c, u, &b, err, errlen);
  char e2[512]; /* summary.json also after a failed final check; its own failure only when all went well */
  if (write_summary(c, u, un, &b, ssr, (int)its, reason, !rc, e2, sizeof e2) && !rc) rc = 1, snprintf(err, errlen, "%s", e2);
  free(un);
  return rc;
}
