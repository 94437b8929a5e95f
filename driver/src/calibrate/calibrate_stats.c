/* Standard errors for residuals correlated along a curve (docs/calibrate.md, "Standard errors"). An estimate is,
 * to first order, a linear function of the residuals' errors e: theta - theta_true = G e (G, q x m: for the
 * least-squares parameters G = -(J^T J)^-1 J^T). Its covariance G Cov(e) G^T is estimated with the errors taken as
 * stationary within each residual block (one curve of one sensor; blocks are separate curves, with no covariance
 * across them, each its own size):
 *
 *  1. prewhitening (Andrews & Monahan 1992, Econometrica 60, 953, here of the errors): an AR(1), r_i = rho r_i-1 +
 *     eta_i, rho pooled over the blocks (|rho| at most 0.99); then sum_i g_i r_i = sum_j h_j eta_j with the weights
 *     filtered backwards, h_j = g_j + rho h_j+1, the block's first row as Prais & Winsten's (its eta scaled by
 *     sqrt(1 - rho^2), its weight divided by it: the noise the block starts with);
 *  2. the innovations' autocovariance tapered by the Bartlett kernel, as Newey and West (1987, Econometrica 55, 703)
 *     weigh the lags:
 *
 *     Cov = m / (m - p) * sum_blocks sum_{i, j in the block} k(|i - j| / S) c_b(|i - j|) h_i h_j^T,
 *     c_b(l) = (1 / T) sum_i eta_i eta_i+l  over the block's T rows,   k(x) = 1 - x for x < 1, 0 beyond,
 *
 *     the bandwidth S of a block of T rows by Andrews' (1991, Econometrica 59, 817) AR(1) plug-in rule for that
 *     kernel, S = 1.1447 (alpha T)^(1/3), alpha = 4 a^2 / ((1 - a)^2 (1 + a)^2), a the innovations' lag-1 coefficient.
 *
 * White residuals give rho near 0, S near 1 and the usual s^2 (J^T J)^-1; a noise that wanders along the curve
 * (lag-1 0.9, 0.98), the misfit of a model, the full model's own error, widen it. On the nano record of
 * tests/calibrate/test_measured_curves.py with AR(1) noise (40 draws): lag-1 0.9: 88 % of the draws within 2 of these
 * standard errors (the white ones: 20 %); 0.98: 88 % (5 %), where the kernel alone, on the errors or on the scores
 * g_i r_i (Newey-West's own form), covered 80 %. The white estimate, s^2 sum_i g_i g_i^T with s^2 = SSR / (m - p), is
 * reported beside it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_stats.h"

#define RHO_MAX 0.99   /* the prewhitening's coefficient at most */
#define ALPHA_MAX 0.97 /* Andrews' plug-in: the innovations' lag-1 coefficient at most */

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

static double lag1(const double *x, const int *blocks, int nblock, double cap) {
  double sxy = 0, sxx = 0;
  for (int b = 0, off = 0; b < nblock; off += blocks[b++])
    for (int i = off + 1; i < off + blocks[b]; i++) sxy += x[i] * x[i - 1], sxx += x[i - 1] * x[i - 1];
  return sxx > 0 ? fmax(-cap, fmin(cap, sxy / sxx)) : 0;
}

void cal_hac(int q, int m, const double *G, const double *r, const int *blocks, int nblock, int p, double *cov, double *white,
             CalHacInfo *info) {
  double  ssr = 0, *eta = malloc(sizeof(double) * m), *h = malloc(sizeof(double) * q * m);
  memset(info, 0, sizeof *info);
  for (int i = 0; i < m; i++) ssr += r[i] * r[i];
  double rho = lag1(r, blocks, nblock, RHO_MAX), w0 = sqrt(1 - rho * rho);
  info->rho = rho;
  for (int b = 0, off = 0; b < nblock; off += blocks[b++]) { /* innovations and the filtered weights */
    int T = blocks[b];
    for (int i = off; i < off + T; i++) eta[i] = i > off ? r[i] - rho * r[i - 1] : w0 * r[i];
    for (int a = 0; a < q; a++) {
      double acc = 0;
      for (int i = off + T - 1; i >= off; i--) acc = G[a * m + i] + rho * acc, h[a * m + i] = i > off ? acc : acc / w0;
    }
  }
  double ai = lag1(eta, blocks, nblock, ALPHA_MAX);
  info->alpha = 4 * ai * ai / (pow(1 - ai, 2) * pow(1 + ai, 2));
  for (int a = 0; a < q * q; a++) cov[a] = 0, white[a] = 0;
  for (int b = 0, off = 0; b < nblock; off += blocks[b++]) {
    int    T = blocks[b];
    double S = 1.1447 * cbrt(info->alpha * T);
    int    L = (int)ceil(S) - 1; /* lags with a weight > 0 */
    if (L > T - 1) L = T - 1;
    if (L < 0) L = 0;
    if (T > info->longest) info->longest = T, info->bandwidth = S, info->lags = L;
    for (int l = 0; l <= L; l++) {
      double c = 0, w = l ? 1 - l / S : 1;
      for (int i = off; i + l < off + T; i++) c += eta[i] * eta[i + l];
      c *= w / T;
      for (int i = off; i + l < off + T; i++)
        for (int a = 0; a < q; a++)
          for (int d = 0; d < q; d++)
            cov[a * q + d] += c * (l ? h[a * m + i] * h[d * m + i + l] + h[d * m + i] * h[a * m + i + l] : h[a * m + i] * h[d * m + i]);
    }
  }
  double dof = m > p ? (double)m / (m - p) : NAN, s2 = m > p ? ssr / (m - p) : NAN;
  for (int a = 0; a < q; a++)
    for (int d = 0; d < q; d++) {
      double gg = 0;
      for (int i = 0; i < m; i++) gg += G[a * m + i] * G[d * m + i];
      cov[a * q + d] *= dof, white[a * q + d] = s2 * gg;
    }
  free(eta), free(h);
}

void cal_blocks(const CalRun *runs, int nrun, int *blocks, int *nblock) {
  *nblock = 0;
  for (int j = 0; j < nrun; j++)
    for (int k = 0; k < runs[j].ncurve; k++) blocks[(*nblock)++] = runs[j].curve[k].n;
}

int cal_normal_inverse(int n, int m, const double *J, double *inv) {
  double JtJ[(CAL_MAX_PARAMS + CAL_MAX_RUNS) * (CAL_MAX_PARAMS + CAL_MAX_RUNS)];
  for (int a = 0; a < n; a++)
    for (int b = 0; b < n; b++) {
      JtJ[a * n + b] = 0;
      for (int i = 0; i < m; i++) JtJ[a * n + b] += J[a * m + i] * J[b * m + i];
    }
  if (!cal_invert(n, JtJ, inv)) return 0;
  for (int i = 0; i < n * n; i++) inv[i] = NAN;
  return 1;
}

void cal_normal_coef(int n, int m, const double *J, const double *inv, const double *v, double *coef) {
  double g[CAL_MAX_PARAMS + CAL_MAX_RUNS];
  for (int a = 0; a < n; a++) {
    g[a] = 0;
    for (int i = 0; i < m; i++) g[a] += J[a * m + i] * v[i];
  }
  for (int a = 0; a < n; a++) {
    coef[a] = 0;
    for (int b = 0; b < n; b++) coef[a] += inv[a * n + b] * g[b];
  }
}

int cal_influence(int n, int m, const double *J, double *G, double *inv) {
  if (cal_normal_inverse(n, m, J, inv)) {
    for (int i = 0; i < n * m; i++) G[i] = NAN;
    return 1;
  }
  for (int a = 0; a < n; a++)
    for (int i = 0; i < m; i++) {
      double g = 0;
      for (int b = 0; b < n; b++) g -= inv[a * n + b] * J[b * m + i];
      G[a * m + i] = g;
    }
  return 0;
}
