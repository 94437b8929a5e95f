/* Checks that catch a wrong fit before it runs (docs/calibrate.md): data rows the forward run does not cover
 * or that fall in a block of another kind (the forward scene's protocol is not the data's), and data whose
 * scale is a factor of 10 from the first forward run's (a unit). Each names the key, the numbers, and the way
 * out; a user who means it lists the check under the calibrate scene's accept:. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_check.h"
#include "calibrate_residual.h"
#include "calibrate_units.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define SCALE_APART 10.0 /* data and model a factor of 10 apart: a unit */

static const char *HOW = "give drive: data (the forward runs follow the data's own history), or a forward scene whose "
                         "stages are the data's";

/* The data row of time t (the data's times increase), or -1. */
static int row_of(const CalRun *run, double t) {
  int lo = 0, hi = run->rows - 1;
  while (lo <= hi) {
    int    mid = (lo + hi) / 2;
    double tm  = run->data[mid * run->ncol + run->col_time];
    if (tm == t) return mid;
    if (tm < t) lo = mid + 1;
    else hi = mid - 1;
  }
  return -1;
}

/* Data rows before the forward run's start or after its end. */
static int check_outside(const CalRun *run, const char *dir, char *err, size_t errlen) {
  const char *names[4] = {"time", "stage", "time", "time"};
  double     *h;
  int         rows, out = 0;
  if (cal_read_history(run, dir, names, &h, &rows, err, errlen)) return 1;
  double t0 = h[0], t1 = h[4 * (rows - 1)], a = INFINITY, b = -INFINITY, tol = 1e-9 * fabs(t1);
  free(h);
  for (int i = 0; i < run->rows; i++) {
    double t = run->data[i * run->ncol + run->col_time];
    if (t < t0 - tol || t > t1 + tol) out++, a = fmin(a, t), b = fmax(b, t);
  }
  if (out)
    FAIL("%s:%d: key 'runs[%d].data': %d of the %d data rows (times %g to %g s in the forward run's time) lie outside the "
         "forward run (%g to %g s): the forward scene's protocol is not the data's: %s; accept: [rows] fits the rows "
         "inside only", run->file, run->line, run->index, out, run->rows, a, b, t0, t1, HOW);
  return 0;
}

/* Each loading, hold or unloading block against the data's own stages: rows of another kind in it, or the
 * data's rows of its kind left out of it. */
static int check_kinds(const CalRun *run, char *err, size_t errlen) {
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c = &run->curve[k];
    int             foreign = 0, kinds = 0, same = 0, mine = 0;
    char            which[64] = "";
    double          a = INFINITY, b = -INFINITY;
    if (c->kind == CAL_SERIES) continue;
    for (int i = 0; i < c->n; i++) {
      int r = row_of(run, c->t[i]);
      if (r < 0) continue;
      CalKind kd = run->stage[run->row_stage[r]].kind;
      if (kd != c->kind) foreign++, kinds |= 1 << kd, a = fmin(a, c->t[i]), b = fmax(b, c->t[i]);
      else mine++;
    }
    for (int kd = 0; kd < 3; kd++)
      if (kinds & 1 << kd) {
        size_t len = strlen(which);
        snprintf(which + len, sizeof which - len, "%s%s", len ? " and " : "", cal_kind_name((CalKind)kd));
      }
    if (foreign > 2 && foreign > 0.05 * c->n)
      FAIL("%s:%d: key 'runs[%d].residuals[%d]' (%s in stage '%s'): %d of its %d data rows (times %g to %g s) are the data's "
           "%s rows: the forward scene's protocol is not the data's: %s; accept: [rows] to fit them so", run->file, c->line,
           run->index, c->index, cal_kind_name(c->kind), c->stage_name, foreign, c->n, a, b, which, HOW);
    for (int j = 0; j < run->ncurve; j++) same += run->curve[j].kind == c->kind;
    int total = 0;
    for (int i = 0; i < run->rows; i++) total += run->stage[run->row_stage[i]].kind == c->kind;
    if (same == 1 && total - mine > 2 && total - mine > 0.10 * total)
      FAIL("%s:%d: key 'runs[%d].residuals[%d]' (%s in stage '%s'): it uses %d of the data's %d %s rows; the others lie "
           "outside the forward stage: the forward scene's protocol is not the data's: %s; accept: [rows] to fit so",
           run->file, c->line, run->index, c->index, cal_kind_name(c->kind), c->stage_name, mine, total,
           cal_kind_name(c->kind), HOW);
  }
  return 0;
}

int cal_check_rows(const CalRun *run, const char *dir, int accept, char *err, size_t errlen) {
  if (!run->drive && !(accept & CAL_ACCEPT_ROWS)) { /* drive: data: the blocks are the data's own stages */
    if (check_outside(run, dir, err, errlen)) return 1;
    if (run->row_stage && check_kinds(run, err, errlen)) return 1;
  }
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c = &run->curve[k];
    if (c->n < 2)
      FAIL("%s:%d: key 'runs[%d].residuals[%d]' (%s in stage '%s'): %d data rows of %s lie in that stage of the forward "
           "run: at least 2 needed (data outside the forward run's range?)", run->file, c->line, run->index, c->index,
           cal_kind_name(c->kind), c->stage_name, c->n, run->data_file);
  }
  return 0;
}

/* max |v| (or its range, relative) over n values with stride s. */
static double size_of(const double *v, int n, int s, int range) {
  double lo = INFINITY, hi = -INFINITY, big = 0;
  for (int i = 0; i < n; i++) lo = fmin(lo, v[i * s]), hi = fmax(hi, v[i * s]), big = fmax(big, fabs(v[i * s]));
  return range ? hi - lo : big;
}

/* Data and model of one quantity a factor of 10 apart? The message blames the data column's factor. */
static int compare(const CalRun *run, const CalCurve *c, int role, const char *what, double data, double model, char *err,
                   size_t errlen) {
  char key[96], how[96];
  if (!(data > 0 && model > 0)) return 0;
  double ratio = data / model;
  if (ratio <= SCALE_APART && ratio >= 1 / SCALE_APART) return 0;
  cal_unit_how(run, role, how, sizeof how);
  FAIL("%s:%d: key '%s' (column '%s', %s): the data's %s reach %.4g where the first forward run's reach %.4g in stage "
       "'%s' (residuals[%d]), %.3g times as much: a unit? The %s converts the data to the units of the forward scene %s; "
       "accept: [scale] if the start is meant to be that far off", run->file, run->data_line ? run->data_line : run->line,
       cal_unit_key(run, role, key, sizeof key), run->col_name[role], how, what, data, model, c->stage_name, c->index,
       ratio, run->declared[role] == 2 ? "factor" : "unit", run->scene);
}

int cal_check_scale(const CalRun *run, const char *dir, int accept, int models, char *err, size_t errlen) {
  if (accept & CAL_ACCEPT_SCALE) return 0;
  for (int k = 0; k < run->ncurve; k++) {
    const CalCurve *c = &run->curve[k];
    if (models) { /* the model's y at the data's x, against the data's y: a depth's size (the creep over a hold
                     moves with the parameters, a factor of 10 at a hold at low load); a relative series' range */
      int yrole = c->kind == CAL_SERIES ? 3 : 2, range = c->relative && c->kind == CAL_SERIES;
      if (compare(run, c, yrole, c->kind == CAL_SERIES ? "values" : "depths", size_of(c->y, c->n, 1, range),
                  size_of(c->model, c->n, 1, range), err, errlen))
        return 1;
      continue;
    }
    const char *names[4] = {"time", "stage", c->xcol, c->ycol};
    double     *h;
    int         rows, i0, i1;
    if (strcmp(c->xcol, "load") || run->drive) continue; /* drive: data: the forward run's loads are the data's */
    if (cal_read_history(run, dir, names, &h, &rows, err, errlen)) return 1;
    int    empty = cal_stage_span(h, rows, c->stage, &i0, &i1);
    double mx    = empty ? 0 : size_of(h + 4 * i0 + 2, i1 - i0 + 1, 4, 0);
    free(h);
    if (compare(run, c, 1, "loads", size_of(c->x, c->n, 1, 0), mx, err, errlen)) return 1;
  }
  return 0;
}
