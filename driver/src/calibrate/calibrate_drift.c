/* Thermal drift of an indentation record's depth (docs/calibrate.md, "Thermal drift"): the depth sensor's zero
 * moves at a constant rate d over the test, h_measured(t) = h(t) + d (t - t_0), t_0 the record's first row (its
 * contact). Two standard treatments:
 *
 *  - drift: {measured_in: STAGE}: the rate measured in a hold of the record where the material is taken to be at
 *    rest (a least-squares line through depth against time over the stage's rows) and removed from every depth,
 *    as ISO 14577-1 and Oliver & Pharr (1992, J. Mater. Res. 7, 1564: a 100 s hold at 10 % of the peak load on
 *    final unloading) do. The material is not at rest there under a viscous model; the report compares the
 *    model's own rate over that stage with the drift measured.
 *  - drift: fit: d a nuisance parameter beside the material's. The residuals are linear in d, so it is profiled
 *    out at each evaluation (variable projection, Golub & Pereyra 1973, SIAM J. Numer. Anal. 10, 413): with a the
 *    residuals' change per unit d, d*(u) = -a.r(u) / a.a and the residuals r + d* a are TAO's; their Jacobian is
 *    the projected one, whose (J^T J)^-1 is the material parameters' covariance with d free.
 *
 * And a check at the fit: a trend left in a hold's residuals that the fitted parameters cannot take up (the
 * hold's time, centred, projected out of the Jacobian's columns), in depth per s with its z value. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_drift.h"
#include "calibrate_residual.h"
#include "calibrate_stats.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define TREND_Z 4.0          /* a hold's trend this many standard errors from 0 ... */
#define TREND_SIZE 0.05      /* ... and over the hold at least this fraction of the hold's data range: warned (a drift
                                of 0.05 nm/s over the nano record's 60 s hold left 18 %; nano_mid's own error against
                                nano_reference on the own curve, 2 %) */
#define REST_SE 1.0          /* drift measured: the model's own rate over that stage above this many standard errors of
                                the rate measured there: warned (the correction's bias exceeds its own uncertainty) */

static double T(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_time]; }
static double H(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_depth]; }

/* Slope of y against x by least squares over n points. */
static double slope(const double *x, const double *y, int n, int sx, int sy) {
  double mx = 0, my = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; i++) mx += x[i * sx] / n, my += y[i * sy] / n;
  for (int i = 0; i < n; i++) sxx += (x[i * sx] - mx) * (x[i * sx] - mx), sxy += (x[i * sx] - mx) * (y[i * sy] - my);
  return sxx > 0 ? sxy / sxx : 0;
}

int cal_drift_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen) {
  char        sub[160], list[1024] = "";
  const char *s;
  YdNode     *v = yd_get(item, "drift");
  run->drift = CAL_DRIFT_NONE, run->drift_stage = -1;
  if (!v) return 0;
  snprintf(sub, sizeof sub, "%s.drift", path);
  run->drift_line = v->line;
  if (v->kind == YD_SCALAR) {
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    if (!strcmp(s, "none")) return 0;
    if (strcmp(s, "fit"))
      FAIL("%s:%d: key '%s': expected none, fit (the drift rate fitted beside the parameters) or {measured_in: STAGE} "
           "(measured in a hold of the data and removed), got '%s'", doc->file, v->line, sub, s);
    if (run->col_depth < 0)
      FAIL("%s:%d: key '%s': a drift of the depth needs the data's depth column (data.columns.depth)", doc->file, v->line, sub);
    run->drift = CAL_DRIFT_FIT;
    return 0;
  }
  if (yd_expect(doc, v, YD_MAPPING, sub, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.drift.measured_in", path);
  YdNode *st = yd_require(doc, v, "measured_in", YD_SCALAR, sub, err, errlen);
  if (!st || yd_string(doc, st, sub, &s, err, errlen)) return 1;
  if (run->col_depth < 0 || run->nstage < 1)
    FAIL("%s:%d: key '%s': a drift measured in a stage needs indentation data with load and depth columns (the data's "
         "stages)", doc->file, st->line, sub);
  for (int j = 0; j < run->nstage; j++) {
    size_t len = strlen(list);
    snprintf(list + len, sizeof list - len, "%s%s (%s)", j ? ", " : "", run->stage[j].name, cal_kind_name(run->stage[j].kind));
    if (!strcmp(run->stage[j].name, s)) run->drift_stage = j;
  }
  if (run->drift_stage < 0) FAIL("%s:%d: key '%s': the data have no stage named '%s' (their stages: %s)", doc->file, st->line, sub, s, list);
  const CalStage *g = &run->stage[run->drift_stage];
  if (g->kind != CAL_HOLD || g->row1 - g->row0 < 2)
    FAIL("%s:%d: key '%s': the stage '%s' is a %s of %d rows: the drift is measured in a hold (the load held, at least 3 "
         "rows), e.g. at 10 %% of the peak load on unloading (Oliver & Pharr 1992) or at the contact", doc->file,
         st->line, sub, s, cal_kind_name(g->kind), g->row1 - g->row0 + 1);
  if (yd_check_unused(doc, v, sub, "measured_in", err, errlen)) return 1;
  int n = g->row1 - g->row0 + 1;
  run->drift          = CAL_DRIFT_MEASURED;
  run->drift_rows     = n;
  run->drift_rate     = slope(&run->data[g->row0 * run->ncol + run->col_time], &run->data[g->row0 * run->ncol + run->col_depth],
                              n, run->ncol, run->ncol);
  double ssr = 0, mt = 0, stt = 0, mh = 0; /* the line's standard error, from its scatter */
  for (int i = g->row0; i <= g->row1; i++) mt += T(run, i) / n, mh += H(run, i) / n;
  for (int i = g->row0; i <= g->row1; i++) {
    double e = H(run, i) - mh - run->drift_rate * (T(run, i) - mt);
    ssr += e * e, stt += (T(run, i) - mt) * (T(run, i) - mt);
  }
  run->drift_se = stt > 0 && n > 2 ? sqrt(ssr / (n - 2) / stt) : NAN;
  double t0 = T(run, 0);
  for (int i = 0; i < run->rows; i++) run->data[i * run->ncol + run->col_depth] -= run->drift_rate * (T(run, i) - t0);
  return 0;
}

void cal_drift_regressor(const CalRun *run, double *a) {
  double t0 = T(run, 0); /* the data's first row, in the same (shifted) time as the blocks' */
  int    m  = 0;
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c    = &run->curve[k];
    double          mean = 0;
    for (int i = 0; c->relative && i < c->n; i++) mean += (c->t[i] - t0) / c->n;
    for (int i = 0; i < c->n; i++) a[m++] = c->kind == CAL_SERIES ? 0 : c->weight * (c->t[i] - t0 - mean) / c->scale;
  }
}

void cal_drift_project(CalRun *run, double *r) {
  if (run->drift != CAL_DRIFT_FIT) return;
  int     m = cal_run_size(run);
  double *a = malloc(sizeof(double) * (m ? m : 1)), ar = 0, aa = 0;
  cal_drift_regressor(run, a);
  for (int i = 0; i < m; i++) ar += a[i] * r[i], aa += a[i] * a[i];
  run->drift_rate = aa > 0 ? -ar / aa : 0;
  for (int i = 0; i < m; i++) r[i] += run->drift_rate * a[i];
  free(a);
}

/* Each hold block's residual trend that the fit's columns X (q of them, each m long) cannot take up; warnings into
 * the log and the findings into fit (CalTrend, one per hold block). */
int cal_hold_trends(const CalRun *runs, int nrun, int m, const double *X, int q, const double *r, CalTrend *out, int max) {
  int     nout = 0;
  double *g = malloc(sizeof(double) * m), inv[(CAL_MAX_PARAMS + CAL_MAX_RUNS) * (CAL_MAX_PARAMS + CAL_MAX_RUNS)];
  int     singular = cal_normal_inverse(q, m, X, inv);
  for (int j = 0, off = 0; j < nrun; j++)
    for (int k = 0; k < runs[j].ncurve; k++) {
      const CalRun   *run = &runs[j];
      const CalCurve *cv  = &run->curve[k];
      int             b0 = off;
      off += cv->n;
      if (cv->kind != CAL_HOLD || cv->n < 4 || nout >= max) continue;
      double mean = 0, gg = 0, gr = 0, dd = 0;
      for (int i = 0; i < m; i++) g[i] = 0;
      for (int i = 0; i < cv->n; i++) mean += cv->t[i] / cv->n;
      for (int i = 0; i < cv->n; i++) g[b0 + i] = cv->weight * (cv->t[i] - mean) / cv->scale;
      if (!singular) { /* g less its projection on X's columns */
        double coef[CAL_MAX_PARAMS + CAL_MAX_RUNS];
        cal_normal_coef(q, m, X, inv, g, coef);
        for (int i = 0; i < m; i++)
          for (int a = 0; a < q; a++) g[i] -= X[a * m + i] * coef[a];
      }
      for (int i = 0; i < m; i++) gg += g[i] * g[i], gr += g[i] * r[i];
      for (int i = b0; i + 1 < b0 + cv->n; i++) dd += (r[i + 1] - r[i]) * (r[i + 1] - r[i]);
      double sigma = sqrt(dd / (2.0 * (cv->n - 1))); /* the residuals' scatter from their differences: a trend hardly moves it */
      CalTrend *t  = &out[nout++];
      t->run = j, t->block = k;
      /* the data's depth rises by rate per s more than the model's: residual (model - data) falls by rate * g */
      t->rate = gg > 0 ? -gr / gg : 0;
      t->se   = gg > 0 ? sigma / sqrt(gg) : NAN;
      t->z    = t->se > 0 ? t->rate / t->se : 0;
      double lo = INFINITY, hi = -INFINITY;
      for (int i = 0; i < cv->n; i++) lo = fmin(lo, cv->y[i]), hi = fmax(hi, cv->y[i]);
      t->size = fabs(t->rate) * (cv->t[cv->n - 1] - cv->t[0]) / (hi > lo ? hi - lo : 1);
      t->warn = fabs(t->z) > TREND_Z && t->size > TREND_SIZE;
      t->model_rate = NAN;
    }
  /* drift measured in a stage: the model's own rate there at the fit, against the drift measured */
  for (int j = 0; j < nrun; j++) {
    const CalRun *run = &runs[j];
    if (run->drift != CAL_DRIFT_MEASURED) continue;
    for (int k = 0; k < run->ncurve; k++)
      if (run->curve[k].stage == run->drift_stage && run->drift && run->curve[k].kind == CAL_HOLD && run->drift_rows > 2) {
        const CalCurve *cv = &run->curve[k];
        for (int o = 0; o < nout; o++)
          if (out[o].run == j && out[o].block == k) out[o].model_rate = slope(cv->t, cv->model, cv->n, 1, 1);
      }
  }
  free(g);
  return nout;
}

int cal_rest_warning(const CalRun *run, const CalTrend *t) {
  return t->run >= 0 && !isnan(t->model_rate) && fabs(t->model_rate) > REST_SE * run->drift_se;
}
