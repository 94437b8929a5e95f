/* The forward model's bias and the two-fidelity refinement (docs/calibrate.md). The fit u* minimises the
 * forward (cheap) model's misfit |r(u)|^2; the full model's fit minimises |R(u)|^2, R the same residuals with
 * each run's reference. One full-model run at u* gives R(u*), and the Gauss-Newton step with the forward
 * model's Jacobian J,
 *     du = (J^T J)^-1 J^T R(u*),
 * is the bias of the forward fit to first order: u* - u_full = du (at u*, J^T r(u*) = 0, and R and r share
 * their Jacobian to first order). It is only as good as the forward model's Jacobian is the full model's: on
 * a fine-meshed full model and a coarse forward model with a loose step error, the first estimate was a third
 * of the bias (docs/calibrate.md). The refinement therefore goes on from the new point, one full-model run an
 * iteration, with J updated by Broyden's rank-one secant update from the full model's residuals,
 *     J += ((R_k - R_k-1) - J du) du^T / (du^T du),   du = u_k - u_k-1,
 * (for one parameter: the full model's secant slope; only along a step longer than 1e-3 of the value, as a
 * shorter one shows the full model's numerical noise rather than its slope), until the step is below a fifth
 * of the standard error
 * or 1e-4 of the value. Its fixed point is J^T R(u) = 0: the full model's fit. The last step, a bound on the
 * error it leaves (the steps of a secant method shrink faster than the errors), is the refined value's standard
 * error's model part; its data part is the Newey-West estimate (calibrate_stats.c) from the full model's residuals
 * and the updated J: what is left at the full model's fit is the data's noise and the full model's own error, the
 * latter smooth along a curve (a change of the adaptive steps shifts it as a whole), which the estimate's
 * bandwidth follows. The two are kept apart (fit.yaml, quote) and combined in quadrature. */
#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_refine.h"
#include "calibrate_stats.h"

#define REFINE_SE 0.2     /* converged: every step below this fraction of its standard error ... */
#define REFINE_REL 1.0e-4 /* ... or of the value */
#define SECANT_REL 1.0e-3 /* a step shorter than this (relative) shows the full model's numerical noise, not its slope */


/* Each run's largest difference of the full model from the forward model at the fit, relative to each block's data
 * range (the models' curves: cheap as left by the fit's evaluation, full after R), and its block. */
static void model_difference(Calib *c, const double *cheap, CalBias *b) {
  int off = 0;
  for (int j = 0; j < c->nrun; j++) {
    CalRun *run = &c->run[j];
    b->max_diff[j] = run->reference[0] ? 0 : -1, b->max_block[j] = 0;
    for (int k = 0; k < run->ncurve; k++) {
      CalCurve *cv = &run->curve[k];
      double    mc = 0, mf = 0;
      for (int i = 0; cv->relative && i < cv->n; i++) mc += cheap[off + i] / cv->n, mf += cv->model[i] / cv->n;
      for (int i = 0; run->reference[0] && i < cv->n; i++) {
        double d = fabs((cheap[off + i] - mc) - (cv->model[i] - mf)) / cv->range;
        if (d > b->max_diff[j]) b->max_diff[j] = d, b->max_block[j] = k;
      }
      off += cv->n;
    }
  }
}

/* Broyden's update of J (m x n, by parameter) from the step du (in u) and the residuals' change dR; then inv. */
static void broyden(const Calib *c, double *J, double *inv, const double *du, const double *dR) {
  int    n = c->np, m = c->m;
  double dd = 0;
  for (int a = 0; a < n; a++) dd += du[a] * du[a];
  if (!(dd > 0)) return;
  for (int i = 0; i < m; i++) {
    double e = dR[i];
    for (int a = 0; a < n; a++) e -= J[a * m + i] * du[a];
    for (int a = 0; a < n; a++) J[a * m + i] += e * du[a] / dd;
  }
  cal_normal_inverse(n, m, J, inv);
}

int cal_bias(Calib *c, const double *u0, const double *J0, const double *inv0, const double *se, CalBias *b, char *err,
             size_t errlen) {
  int     n = c->np, m = c->m, refs = 0;
  double  u[CAL_MAX_PARAMS], du[CAL_MAX_PARAMS], step[CAL_MAX_PARAMS], p0[CAL_MAX_PARAMS];
  double  inv[CAL_MAX_PARAMS * CAL_MAX_PARAMS], moved[CAL_MAX_PARAMS];
  double *R = malloc(sizeof(double) * m), *cheap = malloc(sizeof(double) * m), *J = malloc(sizeof(double) * m * n);
  double *Rprev = malloc(sizeof(double) * m), *G = malloc(sizeof(double) * m * n), drift[CAL_MAX_RUNS];
  int     blocks[CAL_MAX_RUNS * CAL_MAX_CURVES], nblock, ndrift = 0;
  cal_blocks(c->run, c->nrun, blocks, &nblock);
  for (int j = 0; j < c->nrun; j++) drift[j] = c->run[j].drift_rate, ndrift += c->run[j].drift == CAL_DRIFT_FIT;
  memcpy(J, J0, sizeof(double) * m * n), memcpy(inv, inv0, sizeof(double) * n * n);
  memset(b, 0, sizeof *b);
  for (int j = 0; j < c->nrun; j++) refs += c->run[j].reference[0] != 0, b->max_diff[j] = -1;
  memcpy(u, u0, sizeof(double) * n);
  for (int a = 0; a < n; a++) p0[a] = b->p[a] = cal_param(&c->p[a], u0[a]), b->se[a] = se[a];
  cal_models(c, cheap, 1);
  int big = 0; /* the last step is long enough for a secant */
  for (int it = 0; refs && it < c->refine_runs; it++) {
    char tag[32];
    snprintf(tag, sizeof tag, "full%d", it);
    PetscPrintf(PETSC_COMM_SELF, "%s", it ? "" : "the full model at the fit (each run's reference) ...\n");
    if (cal_evaluate_full(c, u, R, tag, err, errlen)) {
      snprintf(b->failed, sizeof b->failed, "%s", err);
      break;
    }
    b->have = 1, b->nfull++;
    if (!it) model_difference(c, cheap, b);
    if (it && big) { /* the full model's secant along the last step, when the step is long enough to show it */
      for (int i = 0; i < m; i++) Rprev[i] = R[i] - Rprev[i];
      broyden(c, J, inv, moved, Rprev);
    }
    memcpy(Rprev, R, sizeof(double) * m);
    double ssr = 0, full_se[CAL_MAX_PARAMS], un[CAL_MAX_PARAMS], cov[CAL_MAX_PARAMS * CAL_MAX_PARAMS];
    double white[CAL_MAX_PARAMS * CAL_MAX_PARAMS], scratch[CAL_MAX_PARAMS * CAL_MAX_PARAMS];
    CalHacInfo hac;
    for (int i = 0; i < m; i++) ssr += R[i] * R[i];
    cal_influence(n, m, J, G, scratch); /* the full model's Newey-West covariance with the current J */
    cal_hac(n, m, G, R, blocks, nblock, n + ndrift, cov, white, &hac);
    cal_normal_coef(c->np, c->m, J, inv, R, du); /* the Gauss-Newton step du = inv J^T R */
    int want = c->refine == 2, small = 1;
    for (int a = 0; a < n; a++) {
      un[a]   = fmin(1, fmax(0, u[a] - du[a]));
      step[a] = cal_param(&c->p[a], un[a]) - cal_param(&c->p[a], u[a]);
      if (!it) b->first[a] = p0[a] - cal_param(&c->p[a], un[a]);
      full_se[a] = sqrt(cov[a * n + a]) * cal_dparam(&c->p[a], un[a]);
      want |= c->refine == 1 && fabs(b->first[a]) > se[a];
    }
    PetscPrintf(PETSC_COMM_SELF, "  full-model run %d: misfit %.6e; Gauss-Newton step", it + 1, ssr);
    for (int a = 0; a < n; a++) PetscPrintf(PETSC_COMM_SELF, " %s %+.4g (%+.2g %%)", c->p[a].name, step[a], 100 * step[a] / fabs(p0[a]));
    PetscPrintf(PETSC_COMM_SELF, "\n");
    if (!it && !want) break; /* the bias is below the standard error (or refine: no): the forward fit stands */
    b->refined = 1, big = 0;
    for (int a = 0; a < n; a++) { /* the error left after this step: at most the step itself (a secant method's
                                     steps shrink faster than the errors they leave) */
      moved[a]      = un[a] - u[a];
      big          |= fabs(step[a]) > SECANT_REL * fabs(b->p[a]);
      u[a]          = un[a];
      b->p[a]       = cal_param(&c->p[a], u[a]);
      b->se_data[a] = full_se[a], b->se_model[a] = fabs(step[a]);
      b->se[a]      = sqrt(full_se[a] * full_se[a] + step[a] * step[a]);
      b->steps[b->nsteps][a] = step[a] / fabs(b->p[a]);
      b->bias[a]    = p0[a] - b->p[a];
      b->bias_se[a] = b->se[a];
      small &= fabs(step[a]) <= fmax(REFINE_SE * full_se[a], REFINE_REL * fabs(b->p[a]));
    }
    b->nsteps++;
    if (small) {
      b->converged = 1;
      break;
    }
  }
  cal_models(c, cheap, 0); /* curves.csv: the forward model at its fit */
  for (int j = 0; j < c->nrun; j++) c->run[j].drift_rate = drift[j];
  free(R), free(cheap), free(J), free(Rprev), free(G);
  return b->failed[0] != 0;
}
