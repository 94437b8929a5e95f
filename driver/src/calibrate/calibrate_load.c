/* The load history a forward run follows, drive: data (docs/calibrate.md, "A noisy load"). A measured load carries
 * the instrument's noise; a forward run that follows it row by row chases the noise with its adaptive steps (a
 * record with 0.5 % load noise at 10 Hz: 74 000 steps instead of 670, 60 times the CPU). When the load is noisy
 * (load_history: auto, the default) or always (fitted), the forward runs follow a fitted history instead: a
 * continuous, piecewise-linear least-squares fit of the load against time, with a knot at each stage's end and
 * pieces halved where the data's residuals about them have more offset, slope and curvature than their noise
 * allows (the three projections' sum of squares above sigma^2 times chi-square(3) at the 3-sigma level), down to
 * 8 rows a piece. The noise sigma comes from the
 * load's second differences, p[i+1] - 2 p[i] + p[i-1], whose variance is 6 sigma^2 for independent errors and
 * which a smooth load hardly moves: sigma = 1.4826 median|d2| / sqrt(6) (the median's robust scale). A load is
 * noisy when sigma exceeds 1e-4 of its peak (a clean record written with 10 digits: below 1e-5). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_load.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define NOISY 1.0e-4     /* the load's noise, relative to its peak, above which auto fits the history */
#define PIECE_ROWS 8     /* a piece is halved only when it holds at least this many rows */
#define CHI2_3 14.16     /* chi-square, 3 degrees of freedom, at the 3-sigma level (p = 0.0027) */
#define ROUNDS 40

static double T(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_time]; }
static double P(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_load]; }

int cal_load_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen) {
  char        sub[160];
  const char *s;
  YdNode     *v = yd_get(item, "load_history");
  run->load_history = CAL_LOAD_AUTO;
  if (!v) return 0;
  snprintf(sub, sizeof sub, "%s.load_history", path);
  if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
  if (strcmp(s, "auto") && strcmp(s, "data") && strcmp(s, "fitted"))
    FAIL("%s:%d: key '%s': expected auto (a fitted history when the load is noisy), fitted or data (the data's rows as "
         "they are), got '%s'", doc->file, v->line, sub, s);
  if (!run->drive)
    FAIL("%s:%d: key '%s': the load history is the one the forward runs follow with drive: data; this run's follow the "
         "forward scene's stages (drive: scene)", doc->file, v->line, sub);
  run->load_history = !strcmp(s, "data") ? CAL_LOAD_DATA : !strcmp(s, "fitted") ? CAL_LOAD_FITTED : CAL_LOAD_AUTO;
  return 0;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

double cal_noise_d2(double *d, int n) {
  if (n < 1) return 0;
  for (int i = 0; i < n; i++) d[i] = fabs(d[i]);
  qsort(d, (size_t)n, sizeof(double), cmp_double);
  double med = n % 2 ? d[n / 2] : 0.5 * (d[n / 2 - 1] + d[n / 2]);
  return 1.4826 * med / sqrt(6.0);
}

double cal_noise(const double *p, int n) {
  if (n < 3) return 0;
  double *d = malloc(sizeof(double) * (size_t)(n - 2));
  for (int i = 1; i + 1 < n; i++) d[i - 1] = p[i + 1] - 2 * p[i] + p[i - 1];
  double sigma = cal_noise_d2(d, n - 2);
  free(d);
  return sigma;
}

/* The normal equations of the continuous piecewise-linear least-squares fit over the knots tau (nk of them): the hat
 * functions' Gram matrix, tridiagonal (d its diagonal, e its off-diagonal), and b the load's projections. */
static void normal_knots(const CalRun *run, const double *tau, int nk, double *d, double *e, double *b) {
  double tr = 0;
  for (int q = 0; q < nk; q++) d[q] = e[q] = b[q] = 0;
  for (int i = 0, q = 0; i < run->rows; i++) {
    while (q < nk - 2 && T(run, i) >= tau[q + 1]) q++;
    double s = (T(run, i) - tau[q]) / (tau[q + 1] - tau[q]);
    d[q] += (1 - s) * (1 - s), e[q] += s * (1 - s), d[q + 1] += s * s;
    b[q] += (1 - s) * P(run, i), b[q + 1] += s * P(run, i);
  }
  for (int q = 0; q < nk; q++) tr += d[q];
  for (int q = 0; q < nk; q++) d[q] += 1e-12 * tr / nk; /* a knot with no row nearby: held, not singular */
}

/* The fit's knot values c, by elimination of the tridiagonal normal equations. */
static void fit_knots(const CalRun *run, const double *tau, int nk, double *c) {
  double *d = calloc((size_t)nk, sizeof(double)), *e = calloc((size_t)nk, sizeof(double)), *b = calloc((size_t)nk, sizeof(double));
  normal_knots(run, tau, nk, d, e, b);
  for (int q = 1; q < nk; q++) { /* forward elimination (e: the super- and sub-diagonal) */
    double f = e[q - 1] / d[q - 1];
    d[q] -= f * e[q - 1], b[q] -= f * b[q - 1];
  }
  c[nk - 1] = b[nk - 1] / d[nk - 1];
  for (int q = nk - 2; q >= 0; q--) c[q] = (b[q] - e[q] * c[q + 1]) / d[q];
  free(d), free(e), free(b);
}

/* A sign of +-1 from (draw, run, knot): SplitMix64's finaliser (Steele, Lea & Flood 2014) of their combination. */
static double rademacher(int draw, int run, int q) {
  uint64_t z = 0x9E3779B97F4A7C15ull * (uint64_t)(1 + draw) ^ 0xBF58476D1CE4E5B9ull * (uint64_t)(1 + run) ^ (uint64_t)q;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return (z ^ (z >> 31)) & 1 ? 1.0 : -1.0;
}

void cal_load_draw(const CalRun *run, int draw, double *p) {
  int     nk = run->nknot;
  double *d = calloc((size_t)nk, sizeof(double)), *e = calloc((size_t)nk, sizeof(double)), *b = calloc((size_t)nk, sizeof(double));
  normal_knots(run, run->knot_t, nk, d, e, b);
  for (int q = 0; q < nk; q++) { /* Cholesky, N = L L^T: L's diagonal into d, its sub-diagonal into e */
    d[q] = sqrt(d[q] - (q ? e[q - 1] * e[q - 1] : 0));
    if (q + 1 < nk) e[q] /= d[q];
  }
  double sigma = run->load_noise, dq = 0;
  for (int q = nk - 1; q >= 0; q--) { /* L^T dc = sigma z: dc has the covariance sigma^2 N^-1 */
    dq    = (sigma * rademacher(draw, run->index, q) - (q + 1 < nk ? e[q] * dq : 0)) / d[q];
    p[q]  = run->knot_p[q] + dq;
  }
  free(d), free(e), free(b);
}

/* The data's scatter about piece q (rows i0 to i1 - 1) along its offset, slope and curvature: the sum of squares
 * of the residuals' projections on 1, x and x^2 (Gram-Schmidt over the rows, x the position in the piece); for
 * independent errors sigma^2 chi-square with 3 degrees of freedom. A smooth misfit (a corner, a curved load) shows
 * in these modes long before it shows in the sum of all squares. */
static double misfit(const CalRun *run, const double *tau, const double *c, int q, int i0, int i1) {
  int     n = i1 - i0;
  double *b = malloc(sizeof(double) * 3 * n), *e = malloc(sizeof(double) * n), proj = 0;
  for (int i = i0; i < i1; i++) {
    double s = (T(run, i) - tau[q]) / (tau[q + 1] - tau[q]);
    e[i - i0] = P(run, i) - ((1 - s) * c[q] + s * c[q + 1]);
    b[i - i0] = 1, b[n + i - i0] = 2 * s - 1, b[2 * n + i - i0] = (2 * s - 1) * (2 * s - 1);
  }
  for (int k = 0; k < 3; k++) {
    double *v = b + k * n, vv = 0, ev = 0;
    for (int l = 0; l < k; l++) { /* orthogonal to the modes before it */
      double *w = b + l * n, vw = 0, ww = 0;
      for (int i = 0; i < n; i++) vw += v[i] * w[i], ww += w[i] * w[i];
      for (int i = 0; ww > 0 && i < n; i++) v[i] -= vw / ww * w[i];
    }
    for (int i = 0; i < n; i++) vv += v[i] * v[i], ev += e[i] * v[i];
    if (vv > 1e-12 * n) proj += ev * ev / vv;
  }
  free(b), free(e);
  return proj;
}

int cal_load_fit(CalRun *run, char *err, size_t errlen) {
  double *p = malloc(sizeof(double) * run->rows);
  for (int i = 0; i < run->rows; i++) p[i] = P(run, i), run->load_peak = fmax(run->load_peak, p[i]);
  run->load_noise = cal_noise(p, run->rows);
  free(p);
  if (run->load_history == CAL_LOAD_DATA || (run->load_history == CAL_LOAD_AUTO && !(run->load_noise > NOISY * run->load_peak)))
    return 0;
  int     cap = run->nstage + 1, nk = 0;
  double *tau = malloc(sizeof(double) * cap), *c = NULL, sigma = fmax(run->load_noise, 1e-6 * run->load_peak);
  tau[nk++] = T(run, 0);
  for (int j = 0; j < run->nstage; j++) tau[nk++] = T(run, run->stage[j].row1);
  for (int round = 0; round < ROUNDS; round++) {
    c = realloc(c, sizeof(double) * nk);
    fit_knots(run, tau, nk, c);
    double *next = malloc(sizeof(double) * 2 * nk);
    int     nn = 0, split = 0;
    for (int q = 0, i = 0; q + 1 < nk; q++) {
      int i0 = i;
      while (i < run->rows && (T(run, i) < tau[q + 1] || q + 2 == nk)) i++;
      next[nn++] = tau[q];
      if (i - i0 >= PIECE_ROWS && misfit(run, tau, c, q, i0, i) > CHI2_3 * sigma * sigma)
        next[nn++] = 0.5 * (tau[q] + tau[q + 1]), split++;
    }
    next[nn++] = tau[nk - 1];
    free(tau);
    tau = next, nk = nn;
    if (!split) break;
  }
  c = realloc(c, sizeof(double) * nk);
  fit_knots(run, tau, nk, c);
  double ssr = 0;
  for (int i = 0, q = 0; i < run->rows; i++) {
    while (q < nk - 2 && T(run, i) >= tau[q + 1]) q++;
    double s = (T(run, i) - tau[q]) / (tau[q + 1] - tau[q]), e = P(run, i) - ((1 - s) * c[q] + s * c[q + 1]);
    ssr += e * e;
  }
  run->load_rms = sqrt(ssr / run->rows);
  for (int j = 0, q = 0; j < run->nstage; j++) {
    double t1 = T(run, run->stage[j].row1);
    run->load_pieces[j] = 0;
    for (; q + 1 < nk && tau[q + 1] <= t1 * (1 + 1e-12) + 1e-12; q++) run->load_pieces[j]++;
  }
  run->knot_t = tau, run->knot_p = c, run->nknot = nk, run->load_fitted = 1;
  if (!(nk >= 2)) FAIL("%s: key 'runs[%d].load_history': no fitted history (%d knots)", run->file, run->index, nk);
  return 0;
}

void cal_load_describe(const CalRun *run, char *buf, size_t n) {
  const char *u = run->scene_unit[1][0] ? run->scene_unit[1] : "";
  if (!run->load_fitted) {
    snprintf(buf, n, "  load history: the data's rows as they are (the load's noise %.3g %s, %.2g of its peak, from its "
                     "second differences%s)", run->load_noise, u, run->load_noise / run->load_peak,
             run->load_history == CAL_LOAD_DATA ? "; load_history: data" : ": below 1e-4, not noisy");
    return;
  }
  snprintf(buf, n, "  load history: a fitted one (load_history: %s; the load's noise %.3g %s, %.2g %% of its peak, from its "
                   "second differences): continuous, linear between %d knots, pieces per stage", run->load_history == CAL_LOAD_FITTED
           ? "fitted" : "auto, the load is noisy", run->load_noise, u, 100 * run->load_noise / run->load_peak, run->nknot);
  for (int j = 0; j < run->nstage; j++) {
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s %s %d", j ? "," : "", run->stage[j].name, run->load_pieces[j]);
  }
  size_t len = strlen(buf);
  snprintf(buf + len, n - len, "; the data's rms about it %.3g %s. The forward runs follow it, not the noise "
                               "(load_history: data follows the rows)", run->load_rms, u);
}
