#include "calibrate_data.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "../io/paths.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

static const char *kind_names[] = {"loading", "hold", "unloading", "series"};
const char        *cal_kind_name(CalKind k) { return kind_names[k]; }

/* The index of a named stage (segment) of the forward scene, or -1; *point set for a point scene. */
static int forward_stage(const char *scene, const char *name, int *point, char *err, size_t errlen) {
  YdDoc       doc;
  const char *kind = "";
  int         idx = -1;
  if (yd_load(scene, &doc, err, errlen)) return -2;
  YdNode *k = yd_get(doc.root, "scene");
  if (k && k->kind == YD_SCALAR) kind = k->text;
  *point         = !strcmp(kind, "point");
  YdNode *stages = yd_get(doc.root, *point ? "segments" : "stages");
  for (size_t i = 0; stages && stages->kind == YD_SEQUENCE && i < stages->n; i++) {
    YdNode *nm = stages->items[i]->kind == YD_MAPPING ? yd_get(stages->items[i], "name") : NULL;
    if (nm && nm->kind == YD_SCALAR && !strcmp(nm->text, name)) idx = (int)i;
  }
  if (strcmp(kind, "point") && strcmp(kind, "fe")) {
    snprintf(err, errlen, "forward scene '%s': expected scene: point or fe, got '%s'", scene, kind);
    idx = -2;
  }
  yd_free(&doc);
  return idx;
}

/* data.time_from: STAGE: the data's time 0 is that stage's start in the forward run (a lab creep record's
 * time from the load). */
static int read_time_from(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  const char *s;
  char        sub[256];
  YdNode     *v = yd_get(nd, "time_from");
  run->time_stage = -1;
  if (!v) return 0;
  snprintf(sub, sizeof sub, "%s.time_from", path);
  if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
  snprintf(run->time_from, sizeof run->time_from, "%s", s);
  run->time_stage = forward_stage(run->scene, s, &run->point, err, errlen);
  if (run->time_stage == -2) return 1;
  if (run->time_stage < 0)
    FAIL("%s:%d: key '%s': the forward scene %s has no stage (segment) named '%s'", doc->file, v->line, sub, run->scene, s);
  return 0;
}

/* data: {file, columns: {time, load, depth, value}, factors: {time, load, depth, value}, time_from} */
static int read_data(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  static const char *roles[4] = {"time", "load", "depth", "value"};
  const char        *file, *names[4];
  double             factor[4] = {1, 1, 1, 1};
  int               *col[4]    = {&run->col_time, &run->col_load, &run->col_depth, &run->col_value};
  char               sub[256], where[PATH_MAX + 64];
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.file", path);
  YdNode *f = yd_require(doc, nd, "file", YD_SCALAR, sub, err, errlen);
  if (!f || yd_string(doc, f, sub, &file, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, f->line, sub);
  if (path_input(doc->file, where, file, run->data_file, sizeof run->data_file, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.columns", path);
  YdNode *cols = yd_require(doc, nd, "columns", YD_MAPPING, sub, err, errlen), *fac = yd_get(nd, "factors");
  if (!cols) return 1;
  run->ncol = 0;
  for (int r = 0; r < 4; r++) {
    YdNode *c = yd_get(cols, roles[r]);
    *col[r]   = -1;
    if (!c) continue;
    snprintf(sub, sizeof sub, "%s.columns.%s", path, roles[r]);
    if (yd_string(doc, c, sub, &names[run->ncol], err, errlen)) return 1;
    *col[r] = run->ncol++;
    YdNode *fr = fac ? yd_get(fac, roles[r]) : NULL;
    snprintf(sub, sizeof sub, "%s.factors.%s", path, roles[r]);
    if (fr && (yd_double(doc, fr, sub, &factor[r], err, errlen))) return 1;
  }
  snprintf(sub, sizeof sub, "%s.columns", path);
  if (yd_check_unused(doc, cols, sub, "time, load, depth, value", err, errlen)) return 1;
  if (read_time_from(doc, nd, run, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.factors", path);
  if (fac && yd_check_unused(doc, fac, sub, "time, load, depth, value", err, errlen)) return 1;
  if (run->col_time < 0) FAIL("%s:%d: key '%s.columns.time' is missing: the data rows are assigned to the forward "
                              "run's stages by their time", doc->file, cols->line, path);
  snprintf(where, sizeof where, "%s:%d: key '%s.file'", doc->file, f->line, path);
  if (csv_read_columns(run->data_file, where, names, run->ncol, run->col_time, &run->data, &run->rows, err, errlen))
    return 1;
  for (int i = 0; i < run->rows; i++)
    for (int r = 0; r < 4; r++)
      if (*col[r] >= 0) run->data[i * run->ncol + *col[r]] *= factor[r];
  return yd_check_unused(doc, nd, path, "file, columns, factors, time_from", err, errlen);
}

/* residuals: [{kind: loading | hold | unloading | series, stage, weight, model, relative}] */
static int read_curve(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  CalCurve   *c = &run->curve[run->ncurve];
  const char *s, *stage;
  char        sub[256];
  memset(c, 0, sizeof *c);
  c->weight = 1, c->line = nd->line;
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.kind", path);
  YdNode *k = yd_require(doc, nd, "kind", YD_SCALAR, sub, err, errlen), *v;
  if (!k || yd_string(doc, k, sub, &s, err, errlen)) return 1;
  int kind = -1;
  for (int i = 0; i < 4; i++)
    if (!strcmp(s, kind_names[i])) kind = i;
  if (kind < 0) FAIL("%s:%d: key '%s': expected loading, hold, unloading or series, got '%s'", doc->file, k->line, sub, s);
  c->kind = (CalKind)kind;
  snprintf(sub, sizeof sub, "%s.stage", path);
  YdNode *st = yd_require(doc, nd, "stage", YD_SCALAR, sub, err, errlen);
  if (!st || yd_string(doc, st, sub, &stage, err, errlen)) return 1;
  snprintf(c->stage_name, sizeof c->stage_name, "%s", stage);
  c->stage = forward_stage(run->scene, stage, &run->point, err, errlen);
  if (c->stage == -2) return 1;
  if (c->stage < 0)
    FAIL("%s:%d: key '%s': the forward scene %s has no stage (segment) named '%s'", doc->file, st->line, sub, run->scene, stage);
  snprintf(sub, sizeof sub, "%s.weight", path);
  if ((v = yd_get(nd, "weight")) && (yd_double(doc, v, sub, &c->weight, err, errlen) || !(c->weight > 0)))
    FAIL("%s:%d: key '%s': expected a weight > 0, got '%s'", doc->file, v->line, sub, v->text ? v->text : "");
  snprintf(sub, sizeof sub, "%s.relative", path);
  if ((v = yd_get(nd, "relative")) && yd_bool(doc, v, sub, &c->relative, err, errlen)) return 1;
  int need[2]; /* data columns: x, y */
  if (c->kind == CAL_SERIES) {
    snprintf(sub, sizeof sub, "%s.model", path);
    YdNode *m = yd_require(doc, nd, "model", YD_SCALAR, sub, err, errlen);
    if (!m || yd_string(doc, m, sub, &s, err, errlen)) return 1;
    snprintf(c->xcol, sizeof c->xcol, "time"), snprintf(c->ycol, sizeof c->ycol, "%s", s);
    need[0] = run->col_time, need[1] = run->col_value;
  } else {
    snprintf(c->xcol, sizeof c->xcol, "%s", c->kind == CAL_HOLD ? "time" : "load");
    snprintf(c->ycol, sizeof c->ycol, "depth");
    need[0] = c->kind == CAL_HOLD ? run->col_time : run->col_load, need[1] = run->col_depth;
    if (c->kind == CAL_HOLD) c->relative = 1; /* the creep depth over the hold */
  }
  if (need[0] < 0 || need[1] < 0)
    FAIL("%s:%d: key '%s': a %s residual needs the data columns %s and %s (data.columns)", doc->file, nd->line, path,
         kind_names[kind], c->kind == CAL_SERIES ? "time" : c->kind == CAL_HOLD ? "time" : "load",
         c->kind == CAL_SERIES ? "value" : "depth");
  run->ncurve++;
  return yd_check_unused(doc, nd, path, "kind, stage, weight, model, relative", err, errlen);
}

/* set: {NAME: value} as NAME=VALUE,... for -material_set (the forward run checks the names). */
static int read_set(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  for (size_t i = 0; i < nd->n; i++) {
    double v;
    char   sub[256];
    snprintf(sub, sizeof sub, "%s.%s", path, nd->keys[i]);
    nd->used[i] = 1;
    if (yd_double(doc, nd->items[i], sub, &v, err, errlen)) return 1;
    size_t len = strlen(run->set);
    snprintf(run->set + len, sizeof run->set - len, "%s%s=%.17g", len ? "," : "", nd->keys[i], v);
  }
  return 0;
}

int cal_run_read(const YdDoc *doc, YdNode *item, int k, CalRun *run, char *err, size_t errlen) {
  char        path[64], sub[128], where[PATH_MAX + 64];
  const char *s;
  YdNode     *v;
  memset(run, 0, sizeof *run);
  snprintf(path, sizeof path, "runs[%d]", k);
  if (yd_expect(doc, item, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(run->name, sizeof run->name, "run%d", k);
  snprintf(sub, sizeof sub, "%s.name", path);
  if ((v = yd_get(item, "name")) && !yd_string(doc, v, sub, &s, err, errlen)) snprintf(run->name, sizeof run->name, "%s", s);
  else if (v) return 1;
  snprintf(sub, sizeof sub, "%s.scene", path);
  if (!(v = yd_require(doc, item, "scene", YD_SCALAR, sub, err, errlen)) || yd_string(doc, v, sub, &s, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, v->line, sub);
  if (path_input(doc->file, where, s, run->scene, sizeof run->scene, err, errlen)) return 1;
  if ((v = yd_get(item, "reference"))) {
    snprintf(sub, sizeof sub, "%s.reference", path);
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, v->line, sub);
    if (path_input(doc->file, where, s, run->reference, sizeof run->reference, err, errlen)) return 1;
  }
  snprintf(sub, sizeof sub, "%s.options", path);
  if ((v = yd_get(item, "options")) && (yd_string(doc, v, sub, &s, err, errlen) ||
                                        snprintf(run->options, sizeof run->options, "%s", s) < 0))
    return 1;
  snprintf(sub, sizeof sub, "%s.set", path);
  if ((v = yd_get(item, "set")) && read_set(doc, v, run, sub, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.data", path);
  if (!(v = yd_require(doc, item, "data", YD_MAPPING, sub, err, errlen)) || read_data(doc, v, run, sub, err, errlen))
    return 1;
  snprintf(sub, sizeof sub, "%s.residuals", path);
  YdNode *res = yd_require(doc, item, "residuals", YD_SEQUENCE, sub, err, errlen);
  if (!res) return 1;
  if (res->n < 1 || res->n > CAL_MAX_CURVES)
    FAIL("%s:%d: key '%s': expected 1 to %d residual blocks, got %zu", doc->file, res->line, sub, CAL_MAX_CURVES, res->n);
  for (size_t i = 0; i < res->n; i++) {
    snprintf(sub, sizeof sub, "%s.residuals[%zu]", path, i);
    if (read_curve(doc, res->items[i], run, sub, err, errlen)) return 1;
  }
  return yd_check_unused(doc, item, path, "name, scene, reference, options, set, data, residuals", err, errlen);
}

void cal_run_free(CalRun *run) {
  free(run->data);
  for (int c = 0; c < run->ncurve; c++) {
    free(run->curve[c].x), free(run->curve[c].y), free(run->curve[c].t), free(run->curve[c].model);
  }
}

int cal_run_size(const CalRun *run) {
  int m = 0;
  for (int c = 0; c < run->ncurve; c++) m += run->curve[c].n;
  return m;
}

/* The model's columns (time, stage, x, y) of one history. */
static int read_history(const CalRun *run, const CalCurve *c, const char *dir, double **h, int *rows, char *err,
                        size_t errlen) {
  char        file[PATH_MAX + 16];
  const char *names[4] = {"time", run->point ? "segment" : "stage", c->xcol, c->ycol};
  snprintf(file, sizeof file, "%s/history.csv", dir);
  return csv_read_columns(file, run->name, names, 4, -1, h, rows, err, errlen);
}

/* Time span (t0, t1] of the stage in a history (its first point: the last row before it). */
static int stage_span(const double *h, int rows, int stage, int *i0, int *i1) {
  *i0 = -1, *i1 = -1;
  for (int i = 0; i < rows; i++)
    if ((int)h[4 * i + 1] == stage) {
      if (*i0 < 0) *i0 = i > 0 ? i - 1 : i;
      *i1 = i;
    }
  return *i0 < 0 || *i1 <= *i0;
}

/* data.time_from: shift the data's times by the named stage's start in the first forward run (once). */
static int shift_time(CalRun *run, const char *dir, char *err, size_t errlen) {
  double *h;
  int     rows, i0, i1;
  if (run->time_stage < 0 || run->time_shifted) return 0;
  if (read_history(run, &run->curve[0], dir, &h, &rows, err, errlen)) return 1;
  int empty = stage_span(h, rows, run->time_stage, &i0, &i1);
  run->time_shift = empty ? 0 : h[4 * i0];
  free(h);
  if (empty) FAIL("run '%s': data.time_from: the forward run %s/history.csv has no steps in stage '%s'", run->name, dir,
                  run->time_from);
  for (int i = 0; i < run->rows; i++) run->data[i * run->ncol + run->col_time] += run->time_shift;
  run->time_shifted = 1;
  return 0;
}

int cal_run_setup(CalRun *run, const char *dir, char *err, size_t errlen) {
  if (shift_time(run, dir, err, errlen)) return 1;
  for (int k = 0; k < run->ncurve; k++) {
    CalCurve *c = &run->curve[k];
    double   *h;
    int       rows, i0, i1, xc = c->kind == CAL_HOLD || c->kind == CAL_SERIES ? run->col_time
                                   : run->col_load, yc = c->kind == CAL_SERIES ? run->col_value : run->col_depth;
    if (read_history(run, c, dir, &h, &rows, err, errlen)) return 1;
    if (stage_span(h, rows, c->stage, &i0, &i1)) {
      free(h);
      FAIL("run '%s': the forward run %s/history.csv has no steps in stage '%s'", run->name, dir, c->stage_name);
    }
    double t0 = h[4 * i0], t1 = h[4 * i1];
    free(h);
    c->x = malloc(sizeof(double) * run->rows), c->y = malloc(sizeof(double) * run->rows);
    c->t = malloc(sizeof(double) * run->rows), c->model = malloc(sizeof(double) * run->rows);
    double lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < run->rows; i++) {
      const double *row = &run->data[i * run->ncol];
      double        t   = row[run->col_time];
      if (!(t > t0 || (c->stage == 0 && t >= t0)) || t > t1 + 1e-9 * fabs(t1)) continue;
      c->t[c->n] = t, c->x[c->n] = row[xc], c->y[c->n++] = row[yc];
      lo = fmin(lo, row[yc]), hi = fmax(hi, row[yc]);
    }
    if (c->n < 2)
      FAIL("run '%s': residual '%s' (line %d): %d data rows of %s lie in stage '%s' of the forward run (time %g to %g): "
           "at least 2 needed (data outside the forward run's range?)", run->name, kind_names[c->kind], c->line, c->n,
           run->data_file, c->stage_name, t0, t1);
    c->scale = hi - lo > 0 ? hi - lo : fmax(fabs(hi), 1e-300);
  }
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
  int m = 0;
  for (int k = 0; k < run->ncurve; k++) {
    CalCurve *c = &run->curve[k];
    double   *h, ref = 0, ref_data = 0;
    int       rows, i0, i1;
    if (read_history(run, c, dir, &h, &rows, err, errlen)) return 1;
    if (stage_span(h, rows, c->stage, &i0, &i1)) {
      free(h);
      FAIL("run '%s': the forward run has no steps in stage '%s'", run->name, c->stage_name);
    }
    for (int i = 0; i < c->n; i++)
      if (interp(h, i0, i1, c->x[i], &c->model[i])) {
        double xa = h[4 * i0 + 2], xb = h[4 * i1 + 2];
        free(h);
        FAIL("run '%s': residual '%s': the data's %s = %g lies outside the forward run's range in stage '%s' (%g to %g)",
             run->name, kind_names[c->kind], c->xcol, c->x[i], c->stage_name, xa, xb);
      }
    free(h);
    if (c->relative) ref = block_mean(c->model, c->n), ref_data = block_mean(c->y, c->n);
    for (int i = 0; i < c->n; i++) r[m++] = c->weight * ((c->model[i] - ref) - (c->y[i] - ref_data)) / c->scale;
  }
  return 0;
}

int cal_run_write_curves(const CalRun *run, FILE *fp) {
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c   = &run->curve[k];
    double          ref = c->relative ? block_mean(c->model, c->n) : 0, ref_data = c->relative ? block_mean(c->y, c->n) : 0;
    double          x0  = strcmp(c->xcol, "time") ? 0 : run->time_shift; /* times as in the data file */
    for (int i = 0; i < c->n; i++)
      fprintf(fp, "%s,%s,%s,%s,%.10g,%.10g,%.10g\n", run->name, kind_names[c->kind], c->xcol, c->ycol, c->x[i] - x0,
              c->y[i] - ref_data, c->model[i] - ref);
  }
  return 0;
}
