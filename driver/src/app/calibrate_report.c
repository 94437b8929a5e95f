/* The report of a calibration: the Jacobian at the fit by central differences (in the [0, 1] variables TAO
 * works on), standard errors s^2 (J^T J)^-1 with s^2 = SSR / (m - n), correlations, the data against the
 * fitted curves (curves.csv), the forward model's error against its reference (the full model), fit.yaml. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../stepping/stage_runner.h"
#include "calibrate.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define CAL_FD_STEP 0.01 /* in u: 1 % of the bounds' span (of its logarithm on a log scale) */

int cal_invert(int n, double *a, double *b) {
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) b[i * n + j] = i == j;
  for (int col = 0; col < n; col++) {
    int piv = col;
    for (int i = col + 1; i < n; i++)
      if (fabs(a[i * n + col]) > fabs(a[piv * n + col])) piv = i;
    if (!(fabs(a[piv * n + col]) > 0)) return 1;
    for (int j = 0; j < n; j++) {
      double t = a[col * n + j];
      a[col * n + j] = a[piv * n + j], a[piv * n + j] = t;
      t = b[col * n + j], b[col * n + j] = b[piv * n + j], b[piv * n + j] = t;
    }
    double d = a[col * n + col];
    for (int j = 0; j < n; j++) a[col * n + j] /= d, b[col * n + j] /= d;
    for (int i = 0; i < n; i++)
      if (i != col) {
        double f = a[i * n + col];
        for (int j = 0; j < n; j++) a[i * n + j] -= f * a[col * n + j], b[i * n + j] -= f * b[col * n + j];
      }
  }
  return 0;
}

/* J (m x n, column-major by parameter) at u by central differences, one-sided at a bound. */
static int jacobian(Calib *c, const double *u, double *J, char *err, size_t errlen) {
  double *rp = malloc(sizeof(double) * c->m * 2), *rm = rp + c->m;
  for (int k = 0; k < c->np; k++) {
    double up[CAL_MAX_PARAMS], um[CAL_MAX_PARAMS];
    char   tag[32];
    memcpy(up, u, sizeof(double) * c->np), memcpy(um, u, sizeof(double) * c->np);
    up[k] = fmin(1, u[k] + CAL_FD_STEP), um[k] = fmax(0, u[k] - CAL_FD_STEP);
    snprintf(tag, sizeof tag, "jac%d_plus", k);
    if (cal_evaluate(c, up, rp, tag, err, errlen)) return free(rp), 1;
    snprintf(tag, sizeof tag, "jac%d_minus", k);
    if (cal_evaluate(c, um, rm, tag, err, errlen)) return free(rp), 1;
    for (int i = 0; i < c->m; i++) J[k * c->m + i] = (rp[i] - rm[i]) / (up[k] - um[k]);
  }
  free(rp);
  return 0;
}

/* The data against the fitted curves: curves.csv (run, block, x, y, data, model). */
static int write_curves(Calib *c, char *err, size_t errlen) {
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/curves.csv", c->outdir);
  FILE *fp = fopen(file, "w");
  if (!fp) FAIL("calibrate: cannot write %s", file);
  fprintf(fp, "run,block,x_name,y_name,x,data,model\n");
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

/* Bound and reference failures after fit.yaml is written: an error unless accepted (accept: [bound]). */
static int final_checks(Calib *c, const double *u, const CalBias *b, char *err, size_t errlen) {
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/fit.yaml", c->outdir);
  if (b->failed[0])
    FAIL("%s (fit.yaml has the forward model's fit; its bias is not known): %s", b->failed, file);
  if (b->refined && !b->converged)
    FAIL("%s: the refinement on the full model did not converge in %d full-model runs: its last value is in %s (quote), "
         "with its last step in the standard error", c->doc->file, b->nfull, file);
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

int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen) {
  int     n = c->np, m = c->m;
  double *J = malloc(sizeof(double) * m * n), *r = malloc(sizeof(double) * m), ssr = 0;
  double  JtJ[CAL_MAX_PARAMS * CAL_MAX_PARAMS], inv[CAL_MAX_PARAMS * CAL_MAX_PARAMS], cov[CAL_MAX_PARAMS * CAL_MAX_PARAMS];
  double  se[CAL_MAX_PARAMS];
  CalBias b;
  char    msg[2048] = "";
  PetscErrorCode ierr = PetscPrintf(PETSC_COMM_SELF, "TAO %s: %s after %d iterations; the Jacobian at the fit by central differences (%d runs)\n",
                                    c->tao_type, reason, (int)its, 2 * n * c->nrun);
  if (ierr) return free(J), free(r), stage_runner_status(ierr, err);
  if (jacobian(c, u, J, err, errlen)) return free(J), free(r), 1;
  if (cal_evaluate(c, u, r, "fit", err, errlen)) return free(J), free(r), 1;
  for (int i = 0; i < m; i++) ssr += r[i] * r[i];
  for (int a = 0; a < n; a++)
    for (int bb = 0; bb < n; bb++) {
      JtJ[a * n + bb] = 0;
      for (int i = 0; i < m; i++) JtJ[a * n + bb] += J[a * m + i] * J[bb * m + i];
    }
  double s2 = m > n ? ssr / (m - n) : NAN;
  if (cal_invert(n, JtJ, inv))
    for (int i = 0; i < n * n; i++) inv[i] = NAN; /* a parameter the data do not see */
  for (int a = 0; a < n; a++) {
    for (int bb = 0; bb < n; bb++) cov[a * n + bb] = s2 * inv[a * n + bb];
    se[a] = sqrt(cov[a * n + a]) * cal_dparam(&c->p[a], u[a]);
  }
  cal_bias(c, u, J, inv, se, &b, msg, sizeof msg);
  if (write_curves(c, err, errlen)) return free(J), free(r), 1;
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/fit.yaml", c->outdir);
  FILE *fp = fopen(file, "w");
  if (!fp) return free(J), free(r), snprintf(err, errlen, "calibrate: cannot write %s", file), 1;
  cal_write_yaml(c, fp, u, se, cov, ssr, its, reason, &b);
  fclose(fp);
  free(J), free(r);
  ierr = cal_print_summary(c, u, se, &b);
  if (!ierr)
    ierr = PetscPrintf(PETSC_COMM_SELF, "calibrate %s: misfit %.6e, %d evaluations (%d rejected), %d forward runs, wall %.1f s -> %s/fit.yaml\n",
                       c->name, ssr, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0, c->outdir);
  return ierr ? stage_runner_status(ierr, err) : final_checks(c, u, &b, err, errlen);
}
