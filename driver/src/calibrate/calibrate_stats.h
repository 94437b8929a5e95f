/* Linear algebra and the standard errors of estimates from residuals correlated along a curve (Newey-West). */
#ifndef CALIBRATE_STATS_H
#define CALIBRATE_STATS_H

#include "calibrate_run.h"

/* The standard errors' estimate: the residuals' lag-1 coefficient (the prewhitening's), Andrews'
 * alpha (of the innovations), and the longest block's bandwidth S and lags. */
typedef struct {
  double alpha, rho, bandwidth;
  int    lags, longest;
} CalHacInfo;

/* Inverse of the n x n matrix a (row-major; overwritten) into b by Gauss-Jordan with partial pivoting; 1 if singular. */
int cal_invert(int n, double *a, double *b);
/* The covariance of estimates theta = G e (G: q x m, by row) from the residuals r in blocks (nblock
 * of them, their sizes), prewhitened by an AR(1) and then Newey-West; p fitted quantities; cov and white (q x q). */
void cal_hac(int q, int m, const double *G, const double *r, const int *blocks, int nblock, int p, double *cov, double *white,
             CalHacInfo *info);
/* Each residual block's size, the nrun runs' blocks in order. */
void cal_blocks(const CalRun *runs, int nrun, int *blocks, int *nblock);
/* inv = (J^T J)^-1 from J (n x m, by row; n <= CAL_MAX_PARAMS + CAL_MAX_RUNS); 1 if singular (inv NAN filled). */
int  cal_normal_inverse(int n, int m, const double *J, double *inv);
/* coef = inv J^T v: the least-squares coefficients of v (m) on J's n rows, inv from cal_normal_inverse. */
void cal_normal_coef(int n, int m, const double *J, const double *inv, const double *v, double *coef);
/* G = -(J^T J)^-1 J^T (n x m) and inv = (J^T J)^-1 from J (n x m, by parameter); 1 if singular (NAN filled). */
int  cal_influence(int n, int m, const double *J, double *G, double *inv);

#endif
