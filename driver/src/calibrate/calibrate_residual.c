/* The residuals of a calibrate run: the data rows assigned to the residual blocks (by the forward run's stage
 * times, or by the data's own stages when the forward run follows them), and each forward run's history.csv
 * interpolated at the data (docs/calibrate.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "calibrate_load.h"
#include "calibrate_residual.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

/* "FILE:LINE: key 'runs[k].residuals[i]' (KIND in stage 'S')", for messages. */
static const char *block(const CalRun *run, const CalCurve *c, char *buf, size_t n) {
  snprintf(buf, n, "%s:%d: key 'runs[%d].residuals[%d]' (%s in stage '%s')", run->file, c->line, run->index, c->index,
           cal_kind_name(c->kind), c->stage_name);
  return buf;
}

int cal_run_size(const CalRun *run) {
  int m = 0;
  for (int c = 0; c < run->ncurve; c++) m += run->curve[c].n;
  return m;
}

int cal_read_history(const CalRun *run, const char *dir, const char *const names[4], double **h, int *rows, char *err,
                     size_t errlen) {
  char file[PATH_MAX + 16];
  snprintf(file, sizeof file, "%s/history.csv", dir);
  return csv_read_columns(file, run->name, names, 4, -1, h, rows, err, errlen);
}

/* The model's columns (time, stage, the interpolation column, y) of one history. */
static int read_history(const CalRun *run, const CalCurve *c, const char *dir, double **h, int *rows, char *err,
                        size_t errlen) {
  const char *names[4] = {"time", "stage", c->mcol, c->ycol};
  return cal_read_history(run, dir, names, h, rows, err, errlen);
}

int cal_stage_span(const double *h, int rows, int stage, int *i0, int *i1) {
  *i0 = -1, *i1 = -1;
  for (int i = 0; i < rows; i++)
    if ((int)h[4 * i + 1] == stage) {
      if (*i0 < 0) *i0 = i > 0 ? i - 1 : i;
      *i1 = i;
    }
  return *i0 < 0 || *i1 <= *i0;
}

/* Every model column a block asks for is in the forward run's history (a series' 'model' is the user's word). */
static int check_columns(const CalRun *run, const char *dir, char *err, size_t errlen) {
  char  file[PATH_MAX + 16], head[8192], where[PATH_MAX + 128];
  FILE *fp;
  snprintf(file, sizeof file, "%s/history.csv", dir);
  if (!(fp = fopen(file, "r")) || !fgets(head, sizeof head, fp)) {
    if (fp) fclose(fp);
    FAIL("%s:%d: key 'runs[%d].scene': the forward run wrote no history (%s)", run->file, run->line, run->index, file);
  }
  fclose(fp);
  head[strcspn(head, "\r\n")] = '\0';
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c = &run->curve[k];
    char            pad[8200], want[80];
    snprintf(pad, sizeof pad, ",%s,", head), snprintf(want, sizeof want, ",%s,", c->ycol);
    if (strstr(pad, want)) continue;
    block(run, c, where, sizeof where);
    if (c->kind == CAL_SERIES)
      FAIL("%s:%d: key 'runs[%d].residuals[%d].model': the forward run's history has no column '%s' (its columns: %s)",
           run->file, c->line, run->index, c->index, c->ycol, head);
    FAIL("%s: the forward run's history has no column '%s' (an indentation block needs an indentation forward scene; "
         "its columns: %s)", where, c->ycol, head);
  }
  return 0;
}

/* data.time_from: shift the data's times by the named stage's start in the first forward run (once). */
static int shift_time(CalRun *run, const char *dir, char *err, size_t errlen) {
  double *h;
  int     rows, i0, i1;
  if (run->time_stage < 0 || run->time_shifted) return 0;
  if (read_history(run, &run->curve[0], dir, &h, &rows, err, errlen)) return 1;
  int empty = cal_stage_span(h, rows, run->time_stage, &i0, &i1);
  run->time_shift = empty ? 0 : h[4 * i0];
  free(h);
  if (empty)
    FAIL("%s: key 'runs[%d].data.time_from': the forward run %s/history.csv has no steps in stage '%s'", run->file,
         run->index, dir, run->time_from);
  for (int i = 0; i < run->rows; i++) run->data[i * run->ncol + run->col_time] += run->time_shift;
  run->time_shifted = 1;
  return 0;
}

/* The data rows of a block: those of its data stage (drive: data), or those whose time lies in its forward stage. */
static int block_rows(CalRun *run, CalCurve *c, double t0, double t1) {
  int xc = c->kind == CAL_HOLD || c->kind == CAL_SERIES ? run->col_time : run->col_load;
  int yc = c->kind == CAL_SERIES ? run->col_value : run->col_depth;
  free(c->x), free(c->y), free(c->t), free(c->model);
  c->x = malloc(sizeof(double) * run->rows), c->y = malloc(sizeof(double) * run->rows);
  c->t = malloc(sizeof(double) * run->rows), c->model = malloc(sizeof(double) * run->rows);
  c->n = 0;
  double lo = INFINITY, hi = -INFINITY;
  for (int i = 0; i < run->rows; i++) {
    const double *row = &run->data[i * run->ncol];
    double        t   = row[run->col_time];
    if (run->drive ? run->row_stage[i] != c->stage
                   : !(t > t0 || (c->stage == 0 && t >= t0)) || t > t1 + 1e-9 * fabs(t1))
      continue;
    c->t[c->n] = t, c->x[c->n] = row[xc], c->y[c->n++] = row[yc];
    lo = fmin(lo, row[yc]), hi = fmax(hi, row[yc]);
  }
  c->scale = c->range = hi - lo > 0 ? hi - lo : fmax(fabs(hi), 1e-300);
  return c->n;
}

/* weighting: noise: each block's residuals divided by the noise of its data column (depth or value), from the
 * second differences along each block of that column (pooled; cal_noise), in place of the block's range: the
 * residuals' sum of squares is then the chi-square of independent errors of that size, the maximum-likelihood
 * weighting, where the range weighs a block by its units (a hold of 12 nm against a loading of 140 nm: the
 * loading's rows counted 140 times less than the hold's). A column whose noise is below 1e-6 of its largest
 * block range (a clean record) keeps the ranges: noted as NAN. */
static void noise_scales(CalRun *run) {
  for (int role = 2; role <= 3; role++) {
    int     total = 0;
    double  big   = 0;
    for (int k = 0; k < run->ncurve; k++) total += ((run->curve[k].kind == CAL_SERIES) == (role == 3)) ? run->curve[k].n : 0;
    run->noise[role] = NAN;
    if (!total) continue;
    double *d2 = malloc(sizeof(double) * total);
    int     n  = 0;
    for (int k = 0; k < run->ncurve; k++) { /* within each block: none across two blocks */
      const CalCurve *c = &run->curve[k];
      if ((c->kind == CAL_SERIES) != (role == 3)) continue;
      big = fmax(big, c->range);
      for (int i = 1; i + 1 < c->n; i++) d2[n++] = c->y[i + 1] - 2 * c->y[i] + c->y[i - 1];
    }
    double sigma = n >= 3 ? cal_noise_d2(d2, n) : 0;
    free(d2);
    if (!(sigma > 1e-6 * big)) continue;
    run->noise[role] = sigma;
    for (int k = 0; k < run->ncurve; k++)
      if ((run->curve[k].kind == CAL_SERIES) == (role == 3)) run->curve[k].scale = sigma;
  }
}

int cal_run_setup(CalRun *run, const char *dir, char *err, size_t errlen) {
  char where[PATH_MAX + 256];
  if (check_columns(run, dir, err, errlen) || shift_time(run, dir, err, errlen)) return 1;
  for (int k = 0; k < run->ncurve; k++) {
    CalCurve *c = &run->curve[k];
    double   *h;
    int       rows, i0, i1;
    if (read_history(run, c, dir, &h, &rows, err, errlen)) return 1;
    int empty = cal_stage_span(h, rows, c->stage, &i0, &i1);
    double t0 = empty ? 0 : h[4 * i0], t1 = empty ? 0 : h[4 * i1];
    free(h);
    if (empty) FAIL("%s: the forward run %s/history.csv has no steps in that stage", block(run, c, where, sizeof where), dir);
    block_rows(run, c, t0, t1); /* a block with fewer than 2 rows: cal_check_rows */
  }
  if (run->weighting == CAL_WEIGHT_NOISE) noise_scales(run);
  return 0;
}

/* y at x on the polyline (xs, ys) rows i0..i1 (either direction): the first bracketing segment. An x
 * beyond the ends by 1e-7 of the span (data written with 10 digits) is taken at the end. */
static int interp(const double *h, int i0, int i1, double x, double *y) {
  double lo = INFINITY, hi = -INFINITY;
  for (int i = i0; i <= i1; i++) lo = fmin(lo, h[4 * i + 2]), hi = fmax(hi, h[4 * i + 2]);
  if (x < lo && x >= lo - 1e-7 * (hi - lo)) x = lo;
  if (x > hi && x <= hi + 1e-7 * (hi - lo)) x = hi;
  for (int i = i0; i < i1; i++) {
    double xa = h[4 * i + 2], xb = h[4 * (i + 1) + 2];
    if ((x - xa) * (x - xb) <= 0 && xa != xb) {
      double s = (x - xa) / (xb - xa);
      *y       = h[4 * i + 3] + s * (h[4 * (i + 1) + 3] - h[4 * i + 3]);
      return 0;
    } else if (x == xa) {
      *y = h[4 * i + 3];
      return 0;
    }
  }
  return 1;
}

/* A relative block compares shapes: model and data each less their mean over the block (a noisy first
 * point would shift the whole block otherwise). */
static double block_mean(const double *v, int n) {
  double s = 0;
  for (int i = 0; i < n; i++) s += v[i];
  return s / n;
}

int cal_run_residual(CalRun *run, const char *dir, double *r, char *err, size_t errlen) {
  char where[PATH_MAX + 256];
  int  m = 0;
  for (int k = 0; k < run->ncurve; k++) {
    CalCurve *c = &run->curve[k];
    double   *h, ref = 0, ref_data = 0;
    int       rows, i0, i1;
    if (read_history(run, c, dir, &h, &rows, err, errlen)) return 1;
    if (cal_stage_span(h, rows, c->stage, &i0, &i1)) {
      free(h);
      FAIL("%s: the forward run %s has no steps in that stage", block(run, c, where, sizeof where), dir);
    }
    for (int i = 0; i < c->n; i++) {
      double x = strcmp(c->mcol, "time") ? c->x[i] : c->t[i];
      if (interp(h, i0, i1, x, &c->model[i])) {
        double xa = h[4 * i0 + 2], xb = h[4 * i1 + 2];
        free(h);
        FAIL("%s: the data's %s = %g lies outside the forward run's range in that stage (%g to %g)",
             block(run, c, where, sizeof where), c->mcol, x, xa, xb);
      }
    }
    free(h);
    if (c->relative) ref = block_mean(c->model, c->n), ref_data = block_mean(c->y, c->n);
    for (int i = 0; i < c->n; i++) r[m++] = c->weight * ((c->model[i] - ref) - (c->y[i] - ref_data)) / c->scale;
  }
  return 0;
}

int cal_run_write_curves(const CalRun *run, FILE *fp) {
  double t0 = run->data[run->col_time]; /* the drift counts from the data's first row */
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c   = &run->curve[k];
    double          ref = c->relative ? block_mean(c->model, c->n) : 0, ref_data = c->relative ? block_mean(c->y, c->n) : 0;
    double          x0  = strcmp(c->xcol, "time") ? 0 : run->time_shift; /* times as in the data file */
    double          mt  = c->relative ? block_mean(c->t, c->n) - t0 : 0;
    for (int i = 0; i < c->n; i++) {
      /* the drift in the depth at the row: added to the model (drift: fit), removed from the data (measured) */
      double d = run->drift && c->kind != CAL_SERIES ? run->drift_rate * (c->t[i] - t0 - mt) : 0;
      fprintf(fp, "%s,%s,%s,%s,%.10g,%.10g,%.10g,%.10g,%s\n", run->name, cal_kind_name(c->kind), c->xcol, c->ycol, c->x[i] - x0,
              c->y[i] - ref_data, c->model[i] - ref + (run->drift == CAL_DRIFT_FIT ? d : 0), d, c->stage_name);
    }
  }
  return 0;
}
