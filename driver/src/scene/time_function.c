/* Stage time functions (time_function.h). */
#include "time_function.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "../io/keydecl.h"
#include "../io/paths.h"

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

int time_fn_table_read(const YdDoc *doc, YdNode *x, const char *path, double **t, double **v, int *n, char *err, size_t errlen) {
  const char *file, *tc, *vc;
  double      tf = 1, vf = 1;
  YdNode     *y;
  char        sub[256];
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.file", path);
  if (yd_string(doc, yd_require(doc, x, "file", YD_SCALAR, sub, err, errlen), sub, &file, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.time", path);
  if (yd_string(doc, yd_require(doc, x, "time", YD_SCALAR, sub, err, errlen), sub, &tc, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.value", path);
  if (yd_string(doc, yd_require(doc, x, "value", YD_SCALAR, sub, err, errlen), sub, &vc, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.time_factor", path);
  if ((y = yd_get(x, "time_factor")) && (yd_double(doc, y, sub, &tf, err, errlen) || !(tf > 0)))
    FAIL("%s:%d: key '%s': expected a factor > 0 (the table's time unit in s), got '%s'", doc->file, y->line, sub, y->text ? y->text : "");
  if (keys_number(doc, x, "factor", &vf, NULL, err, errlen) || keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  char resolved[1024], where[1200];
  snprintf(where, sizeof where, "%s:%d: key '%s.file'", doc->file, yd_key_line(x, "file"), path);
  if (path_input(doc->file, where, file, resolved, sizeof resolved, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, x->line, path);
  const char *want[2] = {tc, vc};
  double     *data;
  if (csv_read_columns(resolved, where, want, 2, 0, &data, n, err, errlen)) return 1;
  *t = malloc(sizeof(double) * *n), *v = malloc(sizeof(double) * *n);
  for (int r = 0; r < *n; r++) (*t)[r] = data[2 * r] * tf, (*v)[r] = data[2 * r + 1] * vf;
  free(data);
  return 0;
}

int time_fn_read(const YdDoc *doc, YdNode *nd, const char *path, unsigned allowed, const char *expected, TimeFn *f, char *err,
                 size_t errlen) {
  YdNode *x;
  char    sub[256];
  memset(f, 0, sizeof *f);
  f->kind = TF_RAMP;
  if (nd->kind == YD_SCALAR && (allowed & TF_ALLOW_HOLD) && !strcmp(nd->text, "hold")) {
    f->kind = TF_HOLD;
    return 0;
  }
  if (nd->kind == YD_SCALAR && (allowed & TF_ALLOW_NUMBER)) return yd_double(doc, nd, path, &f->target, err, errlen);
  if (nd->kind == YD_MAPPING && (allowed & TF_ALLOW_EXP) && (x = yd_get(nd, "exp"))) {
    f->kind = TF_EXP;
    snprintf(sub, sizeof sub, "%s.exp", path);
    if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen) || keys_number(doc, x, "P0", &f->P0, NULL, err, errlen) ||
        keys_number(doc, x, "k", &f->k, NULL, err, errlen) || keys_check_unused(doc, x, NULL, err, errlen))
      return 1;
  } else if (nd->kind == YD_MAPPING && (allowed & TF_ALLOW_TABLE) && (x = yd_get(nd, "table"))) {
    f->kind = TF_TABLE;
    snprintf(sub, sizeof sub, "%s.table", path);
    if (time_fn_table_read(doc, x, sub, &f->t, &f->v, &f->n, err, errlen)) return 1;
  } else {
    FAIL("%s:%d: key '%s': expected %s", doc->file, nd->line, path, expected);
  }
  return keys_check_unused(doc, nd, "give one of its forms", err, errlen);
}

double time_fn_table_value(const double *t, const double *v, int n, double ts) {
  int j = 0;
  if (ts <= t[0]) return v[0];
  if (ts >= t[n - 1]) return v[n - 1];
  while (t[j + 1] < ts) j++;
  return v[j] + (v[j + 1] - v[j]) * (ts - t[j]) / (t[j + 1] - t[j]);
}

double time_fn_value(const TimeFn *f, double start, double lambda, double ts) {
  switch (f->kind) {
  case TF_EXP: return f->P0 * exp(f->k * ts);
  case TF_HOLD: return start;
  case TF_TABLE: return time_fn_table_value(f->t, f->v, f->n, ts);
  default: return start + lambda * (f->target - start);
  }
}

double time_fn_time_of(const TimeFn *f, double start, double duration, double P) {
  double te = -1;
  if (f->kind == TF_EXP) te = log(P / f->P0) / f->k;
  else if (f->kind == TF_RAMP && f->target != start) te = duration * (P - start) / (f->target - start);
  else if (f->kind == TF_TABLE) { /* the first crossing; a table that starts above P: its start */
    const double *t = f->t, *v = f->v;
    if (v[0] >= P) te = 0;
    for (int j = 0; te < 0 && j + 1 < f->n; j++)
      if (v[j + 1] >= P) te = t[j] + (t[j + 1] - t[j]) * (P - v[j]) / (v[j + 1] - v[j]);
  }
  return te >= 0 && te <= duration ? te : -1;
}

void time_fn_share(TimeFn *f, double copies) {
  f->target /= copies, f->P0 /= copies;
  for (int r = 0; r < f->n; r++) f->v[r] /= copies;
}
