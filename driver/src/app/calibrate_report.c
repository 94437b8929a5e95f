/* The report of a calibration: the Jacobian at the fit by central differences (in the [0, 1] variables TAO
 * works on), standard errors s^2 (J^T J)^-1 with s^2 = SSR / (m - n), correlations, the data against the
 * fitted curves (curves.csv), the forward model's error against its reference (the full model), fit.yaml. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define CAL_FD_STEP 0.01 /* in u: 1 % of the bounds' span (of its logarithm on a log scale) */

/* Inverse of the n x n matrix a (row-major) into b by Gauss-Jordan with partial pivoting; 1 if singular. */
static int invert(int n, double *a, double *b) {
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

/* A run's forward model against its reference at the fit: the largest difference of the model curves
 * relative to each block's data range (-1: no reference; NaN: the reference failed). */
static double reference_error(Calib *c, CalRun *run, const double *p) {
  char   dir[PATH_MAX + 200];
  double worst = 0;
  if (!run->reference[0]) return -1;
  snprintf(dir, sizeof dir, "%s/forward/reference_%s", c->outdir, run->name);
  int     m = cal_run_size(run), off = 0;
  double *cheap = malloc(sizeof(double) * m), *r = malloc(sizeof(double) * m);
  for (int k = 0; k < run->ncurve; k++) memcpy(cheap + off, run->curve[k].model, sizeof(double) * run->curve[k].n), off += run->curve[k].n;
  char err[1024];
  if (cal_forward(c, run, run->reference, p, dir) || cal_run_residual(run, dir, r, err, sizeof err)) worst = NAN;
  off = 0;
  for (int k = 0; k < run->ncurve && !isnan(worst); k++) {
    CalCurve *cv = &run->curve[k];
    double    rc = 0, rf = 0;
    for (int i = 0; cv->relative && i < cv->n; i++) rc += cheap[off + i] / cv->n, rf += cv->model[i] / cv->n;
    for (int i = 0; i < cv->n; i++) worst = fmax(worst, fabs((cheap[off + i] - rc) - (cv->model[i] - rf)) / cv->scale);
    off += cv->n;
  }
  off = 0; /* the cheap model's curves back, for curves.csv */
  for (int k = 0; k < run->ncurve; k++) memcpy(run->curve[k].model, cheap + off, sizeof(double) * run->curve[k].n), off += run->curve[k].n;
  free(cheap), free(r);
  return worst;
}

static void write_yaml(Calib *c, FILE *fp, const double *u, const double *se, const double *cov, double ssr, PetscInt its,
                       const char *reason, const double *referr) {
  int n = c->np;
  fprintf(fp, "# calibrate %s: TAO %s, %d iterations (%s), %d evaluations (%d rejected), %d forward runs, wall %.1f s\n",
          c->name, c->tao_type, (int)its, reason, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0);
  fprintf(fp, "# standard errors: s^2 (J^T J)^-1, s^2 = SSR/(m - n), J by central differences at the fit\n");
  fprintf(fp, "parameters:\n");
  for (int k = 0; k < n; k++) {
    double v = cal_param(&c->p[k], u[k]);
    fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, relative_std_error: %.3g, start: %.6g, min: %.6g, max: %.6g, "
                "scale: %s%s}\n", c->p[k].name, v, se[k], se[k] / fabs(v), c->p[k].start, c->p[k].lo, c->p[k].hi,
            c->p[k].log ? "log" : "linear", u[k] <= 0 || u[k] >= 1 ? ", at_bound: true" : "");
  }
  fprintf(fp, "correlation:\n");
  for (int i = 0; i < n; i++) {
    fprintf(fp, "  - [");
    for (int j = 0; j < n; j++) fprintf(fp, "%s%.4f", j ? ", " : "", cov[i * n + j] / sqrt(cov[i * n + i] * cov[j * n + j]));
    fprintf(fp, "]\n");
  }
  fprintf(fp, "misfit: {sum_of_squares: %.6e, residuals: %d, rms: %.4e}\n", ssr, c->m, sqrt(ssr / c->m));
  fprintf(fp, "cost: {iterations: %d, evaluations: %d, rejected: %d, forward_runs: %d, forward_wall: %.1f, wall: %.1f}\n",
          (int)its, c->nevals, c->nrejected, c->nforward, c->forward_wall, MPI_Wtime() - c->wall0);
  fprintf(fp, "forward_models:\n");
  for (int j = 0; j < c->nrun; j++) {
    fprintf(fp, "  - {run: %s, scene: %s", c->run[j].name, c->run[j].scene);
    if (referr[j] >= 0 || isnan(referr[j]))
      fprintf(fp, ", reference: %s, max_error_vs_reference: %.3g", c->run[j].reference, referr[j]);
    fprintf(fp, "}\n");
  }
  fprintf(fp, "# paste into a scene's material block:\nset: {");
  for (int k = 0; k < n; k++) fprintf(fp, "%s%s: %.6g", k ? ", " : "", c->p[k].name, cal_param(&c->p[k], u[k]));
  fprintf(fp, "}\n");
}

int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen) {
  int     n = c->np, m = c->m;
  double *J = malloc(sizeof(double) * m * n), *r = malloc(sizeof(double) * m), ssr = 0;
  double  JtJ[CAL_MAX_PARAMS * CAL_MAX_PARAMS], inv[CAL_MAX_PARAMS * CAL_MAX_PARAMS], cov[CAL_MAX_PARAMS * CAL_MAX_PARAMS];
  double  se[CAL_MAX_PARAMS], p[CAL_MAX_PARAMS], referr[CAL_MAX_RUNS];
  PetscPrintf(PETSC_COMM_SELF, "TAO %s: %s after %d iterations; the Jacobian at the fit by central differences (%d runs)\n",
              c->tao_type, reason, (int)its, 2 * n * c->nrun);
  if (jacobian(c, u, J, err, errlen)) return free(J), free(r), 1;
  if (cal_evaluate(c, u, r, "fit", err, errlen)) return free(J), free(r), 1;
  for (int i = 0; i < m; i++) ssr += r[i] * r[i];
  for (int a = 0; a < n; a++)
    for (int b = 0; b < n; b++) {
      JtJ[a * n + b] = 0;
      for (int i = 0; i < m; i++) JtJ[a * n + b] += J[a * m + i] * J[b * m + i];
    }
  double s2 = m > n ? ssr / (m - n) : NAN;
  if (invert(n, JtJ, inv))
    for (int i = 0; i < n * n; i++) inv[i] = NAN; /* a parameter the data do not see */
  for (int a = 0; a < n; a++) {
    for (int b = 0; b < n; b++) cov[a * n + b] = s2 * inv[a * n + b];
    p[a]  = cal_param(&c->p[a], u[a]);
    se[a] = sqrt(cov[a * n + a]) * cal_dparam(&c->p[a], u[a]);
  }
  for (int j = 0; j < c->nrun; j++) referr[j] = reference_error(c, &c->run[j], p);
  if (write_curves(c, err, errlen)) return free(J), free(r), 1;
  char file[PATH_MAX + 32];
  snprintf(file, sizeof file, "%s/fit.yaml", c->outdir);
  FILE *fp = fopen(file, "w");
  if (!fp) return free(J), free(r), snprintf(err, errlen, "calibrate: cannot write %s", file), 1;
  write_yaml(c, fp, u, se, cov, ssr, its, reason, referr);
  fclose(fp);
  for (int k = 0; k < n; k++)
    PetscPrintf(PETSC_COMM_SELF, "  %-14s = %.6g +- %.2g (%.2g %%)\n", c->p[k].name, p[k], se[k], 100 * se[k] / fabs(p[k]));
  for (int j = 0; j < c->nrun; j++)
    if (referr[j] >= 0 || isnan(referr[j]))
      PetscPrintf(PETSC_COMM_SELF, "  run %s: forward model %s against the reference %s: largest difference %.3g of the data range\n",
                  c->run[j].name, c->run[j].scene, c->run[j].reference, referr[j]);
  PetscPrintf(PETSC_COMM_SELF, "calibrate %s: misfit %.6e, %d evaluations (%d rejected), %d forward runs, wall %.1f s -> %s/fit.yaml\n",
              c->name, ssr, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0, c->outdir);
  free(J), free(r);
  return 0;
}
