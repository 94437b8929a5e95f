/* Issue 37: the draws of a fitted load history's uncertainty (calibrate_load.c, cal_load_draw) have the knots'
 * least-squares covariance sigma^2 N^-1, N the hat functions' Gram matrix over the data's times.
 *
 * A noisy record (an exponential loading to 250, a hold, an unloading; 10 rows a second; normal noise of 1.25) is
 * fitted (cal_load_fit); N is built here on its own, densely, from the hat functions at the rows (its inverse by
 * calibrate_stats.c's cal_invert, which the draws do not use). Checked:
 *  1. every draw's move dc satisfies dc^T N dc = sigma^2 n exactly (n the knots): dc = sigma L^-T z with N = L L^T
 *     and z of random signs gives z^T z = n. A move by L^-1 z, by N^-1 z or by z, or another sigma, fails it;
 *  2. the draws' mean square along each knot, over 4 000 draws, is sigma^2 (N^-1)_qq within 10 % (the estimate's own
 *     spread is about 2 %): random signs, independent between draws and knots;
 *  3. another run's index gives other signs. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate/calibrate_load.h"
#include "calibrate/calibrate_stats.h"

#define ROWS 1800
#define DRAWS 4000

static double hat(const double *tau, int nk, int q, double t) {
  if (q > 0 && t >= tau[q - 1] && t <= tau[q]) return (t - tau[q - 1]) / (tau[q] - tau[q - 1]);
  if (q + 1 < nk && t >= tau[q] && t <= tau[q + 1]) return (tau[q + 1] - t) / (tau[q + 1] - tau[q]);
  return 0;
}

int main(void) {
  CalRun run;
  char   err[512];
  int    fails = 0;
  memset(&run, 0, sizeof run);
  run.rows = ROWS, run.ncol = 2, run.col_time = 0, run.col_load = 1, run.load_history = CAL_LOAD_FITTED;
  run.data = malloc(sizeof(double) * 2 * ROWS);
  srand(37);
  for (int i = 0; i < ROWS; i++) {
    double t = 0.1 * i, u1 = (rand() + 1.0) / (RAND_MAX + 2.0), u2 = (rand() + 1.0) / (RAND_MAX + 2.0);
    double p = t < 60 ? 250 * expm1(0.05 * t) / expm1(3.0) : t < 120 ? 250 : 250 * (180 - t) / 60;
    run.data[2 * i] = t, run.data[2 * i + 1] = p + 1.25 * sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
  }
  run.nstage   = 3;
  run.stage[0] = (CalStage){"loading", CAL_LOADING, 0, 599};
  run.stage[1] = (CalStage){"hold", CAL_HOLD, 600, 1199};
  run.stage[2] = (CalStage){"unloading", CAL_UNLOADING, 1200, ROWS - 1};
  if (cal_load_fit(&run, err, sizeof err) || !run.load_fitted) return printf("FAIL: the fit: %s\n", err), 1;
  int     nk = run.nknot;
  double  s2 = run.load_noise * run.load_noise, *N = calloc((size_t)nk * nk, sizeof(double));
  double *Ninv = malloc(sizeof(double) * nk * nk), *A = malloc(sizeof(double) * nk * nk);
  double *p = malloc(sizeof(double) * nk), *msq = calloc((size_t)nk, sizeof(double));
  printf("%d knots, the load's noise %.4f (1.25 drawn)\n", nk, run.load_noise);
  for (int i = 0; i < ROWS; i++)
    for (int a = 0; a < nk; a++)
      for (int b = 0; b < nk; b++) N[a * nk + b] += hat(run.knot_t, nk, a, run.data[2 * i]) * hat(run.knot_t, nk, b, run.data[2 * i]);
  memcpy(A, N, sizeof(double) * nk * nk);
  if (cal_invert(nk, A, Ninv)) return printf("FAIL: N is singular\n"), 1;
  double worst = 0;
  for (int d = 0; d < DRAWS; d++) {
    cal_load_draw(&run, d, p);
    double qf = 0;
    for (int a = 0; a < nk; a++)
      for (int b = 0; b < nk; b++) qf += (p[a] - run.knot_p[a]) * N[a * nk + b] * (p[b] - run.knot_p[b]);
    worst = fmax(worst, fabs(qf / (s2 * nk) - 1));
    for (int a = 0; a < nk; a++) msq[a] += pow(p[a] - run.knot_p[a], 2) / DRAWS;
  }
  printf("1. dc^T N dc / (sigma^2 n) - 1: at most %.2e over %d draws\n", worst, DRAWS);
  if (!(worst < 1e-8)) fails++, printf("FAIL: 1\n");
  double dev = 0;
  for (int a = 0; a < nk; a++) dev = fmax(dev, fabs(msq[a] / (s2 * Ninv[a * nk + a]) - 1));
  printf("2. mean square / sigma^2 (N^-1)_qq - 1: at most %.3f over the knots\n", dev);
  if (!(dev < 0.10)) fails++, printf("FAIL: 2\n");
  double *p1 = malloc(sizeof(double) * nk);
  cal_load_draw(&run, 0, p);
  run.index = 1;
  cal_load_draw(&run, 0, p1);
  int same = !memcmp(p, p1, sizeof(double) * nk);
  printf("3. another run's draw 0 %s\n", same ? "is the same" : "differs");
  if (same) fails++, printf("FAIL: 3\n");
  free(p1), free(N), free(Ninv), free(A), free(p), free(msq), free(run.data), free(run.knot_t), free(run.knot_p);
  printf(fails ? "FAILED\n" : "OK\n");
  return fails != 0;
}
