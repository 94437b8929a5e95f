/* A calibrate scene's runs: the forward scene (and its full model), whose protocol the forward runs follow,
 * the data (columns, factors), the residual blocks. Every error names the calibrate scene, the line, the key
 * path and the value (docs/calibrate.md). */
#include "calibrate_data.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../io/csv_table.h"
#include "../io/paths.h"
#include "calibrate_drift.h"
#include "calibrate_load.h"
#include "calibrate_protocol.h"
#include "calibrate_units.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

/* The forward scene's kind: 0 point, 1 fe, 2 fe with an indenter; -1 with err naming the key (another kind). */
static int forward_kind(const YdDoc *doc, const char *key, int line, const char *scene, char *err, size_t errlen) {
  YdDoc       fwd;
  const char *kind = "";
  char        msg[1024];
  if (yd_load(scene, &fwd, msg, sizeof msg)) {
    snprintf(err, errlen, "%s:%d: key '%s': the forward scene cannot be read: %s", doc->file, line, key, msg);
    return -1;
  }
  YdNode *k = yd_get(fwd.root, "scene");
  if (k && k->kind == YD_SCALAR) kind = k->text;
  int r = !strcmp(kind, "point") ? 0 : !strcmp(kind, "fe") ? (yd_get(fwd.root, "indenter") ? 2 : 1) : -1;
  if (r < 0)
    snprintf(err, errlen, "%s:%d: key '%s': the forward scene %s is a scene of kind '%s': expected a point or fe scene "
             "(one forward run)", doc->file, line, key, scene, kind);
  yd_free(&fwd);
  return r;
}

/* The index of a named stage (segment) of the forward scene, or -1 (-2: unreadable). */
static int forward_stage(const CalRun *run, const char *name) {
  YdDoc fwd;
  char  msg[1024];
  int   idx = -1;
  if (yd_load(run->scene, &fwd, msg, sizeof msg)) return -2;
  YdNode *stages = yd_get(fwd.root, run->point ? "segments" : "stages");
  for (size_t i = 0; stages && stages->kind == YD_SEQUENCE && i < stages->n; i++) {
    YdNode *nm = stages->items[i]->kind == YD_MAPPING ? yd_get(stages->items[i], "name") : NULL;
    if (nm && nm->kind == YD_SCALAR && !strcmp(nm->text, name)) idx = (int)i;
  }
  yd_free(&fwd);
  return idx;
}

/* The data stage named 'name', or -1. */
static int data_stage(const CalRun *run, const char *name) {
  for (int j = 0; j < run->nstage; j++)
    if (!strcmp(run->stage[j].name, name)) return j;
  return -1;
}

static void data_stage_list(const CalRun *run, char *buf, size_t n) {
  buf[0] = '\0';
  for (int j = 0; j < run->nstage; j++) {
    size_t len = strlen(buf);
    snprintf(buf + len, n - len, "%s%s (%s)", j ? ", " : "", run->stage[j].name, cal_kind_name(run->stage[j].kind));
  }
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
  if (run->drive)
    FAIL("%s:%d: key '%s': '%s' with drive: data: the forward run's time is the data's own (time_from is for a forward "
         "scene's own stages, drive: scene)", doc->file, v->line, sub, s);
  snprintf(run->time_from, sizeof run->time_from, "%s", s);
  if ((run->time_stage = forward_stage(run, s)) < 0)
    FAIL("%s:%d: key '%s': the forward scene %s has no stage (segment) named '%s'", doc->file, v->line, sub, run->scene, s);
  return 0;
}

/* data.factors: each for a column that is given; time, load and depth > 0, value not 0 (negative: a sign convention). */
static int read_factors(const YdDoc *doc, YdNode *fac, CalRun *run, const char *path, char *err, size_t errlen) {
  static const char *roles[4] = {"time", "load", "depth", "value"};
  const int          col[4]   = {run->col_time, run->col_load, run->col_depth, run->col_value};
  char               sub[256];
  for (int r = 0; r < 4; r++) run->factor[r] = 1;
  if (!fac) return 0;
  snprintf(sub, sizeof sub, "%s.factors", path);
  if (yd_expect(doc, fac, YD_MAPPING, sub, err, errlen)) return 1;
  for (int r = 0; r < 4; r++) {
    YdNode *fr = yd_get(fac, roles[r]);
    if (!fr) continue;
    snprintf(sub, sizeof sub, "%s.factors.%s", path, roles[r]);
    if (col[r] < 0)
      FAIL("%s:%d: key '%s': a factor for a column that is not given (%s.columns.%s is missing)", doc->file, fr->line, sub,
           path, roles[r]);
    if (yd_double(doc, fr, sub, &run->factor[r], err, errlen)) return 1;
    run->declared[r] = 2;
    if (r < 3 ? !(run->factor[r] > 0) : run->factor[r] == 0)
      FAIL("%s:%d: key '%s': expected a factor %s (the data's unit in the forward scene's units, e.g. 0.001 for nm to "
           "um%s), got %s", doc->file, fr->line, sub, r < 3 ? "> 0" : "other than 0",
           r < 3 ? "" : "; negative: the other sign convention, e.g. -0.01 for a compression strain in %", fr->text);
  }
  snprintf(sub, sizeof sub, "%s.factors", path);
  return yd_check_unused(doc, fac, sub, "time, load, depth, value", err, errlen);
}

/* data: {file, columns: {time, load, depth, value, stage}, factors: {time, load, depth, value}, time_from} */
static int read_data(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  static const char *roles[4] = {"time", "load", "depth", "value"};
  const char        *file, *names[4];
  int               *col[4] = {&run->col_time, &run->col_load, &run->col_depth, &run->col_value};
  char               sub[256], where[PATH_MAX + 64];
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.file", path);
  YdNode *f = yd_require(doc, nd, "file", YD_SCALAR, sub, err, errlen);
  if (!f || yd_string(doc, f, sub, &file, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, f->line, sub);
  if (path_input(doc->file, where, file, run->data_file, sizeof run->data_file, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.columns", path);
  YdNode *cols = yd_require(doc, nd, "columns", YD_MAPPING, sub, err, errlen), *v;
  if (!cols) return 1;
  run->ncol = 0;
  for (int r = 0; r < 4; r++) {
    YdNode *c = yd_get(cols, roles[r]);
    *col[r]   = -1;
    if (!c) continue;
    snprintf(sub, sizeof sub, "%s.columns.%s", path, roles[r]);
    if (yd_string(doc, c, sub, &names[run->ncol], err, errlen)) return 1;
    snprintf(run->col_name[r], sizeof run->col_name[r], "%s", names[run->ncol]);
    *col[r] = run->ncol++;
  }
  if ((v = yd_get(cols, "stage"))) {
    const char *s;
    snprintf(sub, sizeof sub, "%s.columns.stage", path);
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    snprintf(run->stage_col, sizeof run->stage_col, "%s", s);
  }
  snprintf(sub, sizeof sub, "%s.columns", path);
  if (yd_check_unused(doc, cols, sub, "time, load, depth, value, stage", err, errlen)) return 1;
  if (run->col_time < 0)
    FAIL("%s:%d: key '%s.columns.time' is missing: the data rows are assigned to the forward run's stages by their time",
         doc->file, cols->line, path);
  if (read_factors(doc, yd_get(nd, "factors"), run, path, err, errlen)) return 1;
  if (cal_units_read(doc, nd, run, path, err, errlen)) return 1;
  if (read_time_from(doc, nd, run, path, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s.file'", doc->file, f->line, path);
  if (csv_read_columns(run->data_file, where, names, run->ncol, run->col_time, &run->data, &run->rows, err, errlen))
    return 1;
  for (int i = 0; i < run->rows; i++)
    for (int r = 0; r < 4; r++)
      if (*col[r] >= 0) run->data[i * run->ncol + *col[r]] *= run->factor[r];
  return yd_check_unused(doc, nd, path, "file, columns, units, factors, time_from", err, errlen);
}

/* residuals[i].stage: a stage of the forward scene (drive: scene) or of the data (drive: data; when left out,
 * the data's first stage of the block's kind that no earlier block took). */
static int read_curve_stage(const YdDoc *doc, YdNode *nd, CalRun *run, CalCurve *c, const char *path, char *err,
                            size_t errlen) {
  char        sub[256], list[1024];
  const char *stage = NULL;
  YdNode     *st    = yd_get(nd, "stage");
  snprintf(sub, sizeof sub, "%s.stage", path);
  if (st && yd_string(doc, st, sub, &stage, err, errlen)) return 1;
  if (!run->drive) {
    if (!st && !(st = yd_require(doc, nd, "stage", YD_SCALAR, sub, err, errlen))) return 1;
    c->stage = forward_stage(run, stage);
    if (c->stage < 0)
      FAIL("%s:%d: key '%s': the forward scene %s has no stage (segment) named '%s'", doc->file, st->line, sub, run->scene, stage);
  } else if (stage) {
    data_stage_list(run, list, sizeof list);
    if ((c->stage = data_stage(run, stage)) < 0)
      FAIL("%s:%d: key '%s': the data have no stage named '%s' (drive: data: the stages are the data's: %s)", doc->file,
           st->line, sub, stage, list);
  } else {
    c->stage = -1;
    for (int j = 0; j < run->nstage && c->stage < 0; j++) {
      int taken = 0;
      for (int b = 0; b < run->ncurve; b++) taken |= run->curve[b].stage == j;
      if (run->stage[j].kind == c->kind && !taken) c->stage = j;
    }
    data_stage_list(run, list, sizeof list);
    if (c->stage < 0)
      FAIL("%s:%d: key '%s': the data have no (further) stage of kind %s for this block: give its stage (the data's "
           "stages: %s)", doc->file, nd->line, path, cal_kind_name(c->kind), list);
    stage = run->stage[c->stage].name;
  }
  snprintf(c->stage_name, sizeof c->stage_name, "%s", stage);
  return 0;
}

/* residuals: [{kind: loading | hold | unloading | series, stage, weight, model, relative}] */
static int read_curve(const YdDoc *doc, YdNode *nd, CalRun *run, const char *path, char *err, size_t errlen) {
  CalCurve   *c = &run->curve[run->ncurve];
  const char *s;
  char        sub[256];
  memset(c, 0, sizeof *c);
  c->weight = 1, c->line = nd->line, c->index = run->ncurve;
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.kind", path);
  YdNode *k = yd_require(doc, nd, "kind", YD_SCALAR, sub, err, errlen), *v;
  if (!k || yd_string(doc, k, sub, &s, err, errlen)) return 1;
  int kind = -1;
  for (int i = 0; i < 4; i++)
    if (!strcmp(s, cal_kind_name((CalKind)i))) kind = i;
  if (kind < 0) FAIL("%s:%d: key '%s': expected loading, hold, unloading or series, got '%s'", doc->file, k->line, sub, s);
  c->kind = (CalKind)kind;
  if (read_curve_stage(doc, nd, run, c, path, err, errlen)) return 1;
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
  /* drive: data: the forward run's load follows the data's in time, so model and data meet at the data's times */
  snprintf(c->mcol, sizeof c->mcol, "%s", run->drive ? "time" : c->xcol);
  if (need[0] < 0 || need[1] < 0)
    FAIL("%s:%d: key '%s': a %s residual needs the data columns %s and %s (data.columns)", doc->file, nd->line, path,
         cal_kind_name((CalKind)kind), c->kind == CAL_SERIES ? "time" : c->kind == CAL_HOLD ? "time" : "load",
         c->kind == CAL_SERIES ? "value" : "depth");
  run->ncurve++;
  return yd_check_unused(doc, nd, path, "kind, stage, weight, model, relative", err, errlen);
}

/* residuals, or (drive: data, none given) a block per data stage of its kind. */
static int read_residuals(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen) {
  char    sub[128];
  YdNode *res = yd_get(item, "residuals");
  snprintf(sub, sizeof sub, "%s.residuals", path);
  if (!res && run->drive) {
    if (run->nstage > CAL_MAX_CURVES)
      FAIL("%s:%d: key '%s': the data have %d stages, more than %d residual blocks: give the residuals", doc->file,
           item->line, sub, run->nstage, CAL_MAX_CURVES);
    for (int j = 0; j < run->nstage; j++) {
      CalCurve *c = &run->curve[run->ncurve];
      memset(c, 0, sizeof *c);
      c->kind = run->stage[j].kind, c->stage = j, c->weight = 1, c->line = item->line, c->index = run->ncurve;
      c->relative = c->kind == CAL_HOLD;
      snprintf(c->stage_name, sizeof c->stage_name, "%s", run->stage[j].name);
      snprintf(c->xcol, sizeof c->xcol, "%s", c->kind == CAL_HOLD ? "time" : "load");
      snprintf(c->ycol, sizeof c->ycol, "depth"), snprintf(c->mcol, sizeof c->mcol, "time");
      run->ncurve++;
    }
    return 0;
  }
  if (!(res = yd_require(doc, item, "residuals", YD_SEQUENCE, sub, err, errlen))) return 1;
  if (res->n < 1 || res->n > CAL_MAX_CURVES)
    FAIL("%s:%d: key '%s': expected 1 to %d residual blocks, got %zu", doc->file, res->line, sub, CAL_MAX_CURVES, res->n);
  for (size_t i = 0; i < res->n; i++) {
    snprintf(sub, sizeof sub, "%s.residuals[%zu]", path, i);
    if (read_curve(doc, res->items[i], run, sub, err, errlen)) return 1;
  }
  return 0;
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

/* reference: FILE | none; left out, the full model beside the forward scene: X_fast.yaml, X_mid.yaml -> X_reference.yaml. */
static int read_reference(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen) {
  char        sub[128], where[PATH_MAX + 64];
  const char *s;
  YdNode     *v = yd_get(item, "reference");
  snprintf(sub, sizeof sub, "%s.reference", path);
  if (v) {
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    if (!strcmp(s, "none")) return 0;
    snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, v->line, sub);
    if (path_input(doc->file, where, s, run->reference, sizeof run->reference, err, errlen)) return 1;
    return forward_kind(doc, sub, v->line, run->reference, err, errlen) < 0;
  }
  size_t n = strlen(run->scene);
  for (int k = 0; k < 2; k++) {
    const char *tail = k ? "_mid.yaml" : "_fast.yaml";
    size_t      t    = strlen(tail);
    if (n > t && !strcmp(run->scene + n - t, tail)) {
      snprintf(run->reference, sizeof run->reference, "%.*s_reference.yaml", (int)(n - t), run->scene);
      if (access(run->reference, R_OK)) run->reference[0] = '\0';
      else run->reference_default = 1;
    }
  }
  return 0;
}

/* drive: data | scene. Default: data for an indentation forward scene (its load follows the data's), else scene. */
static int read_drive(const YdDoc *doc, YdNode *item, CalRun *run, int kind, const char *path, char *err, size_t errlen) {
  char        sub[128];
  const char *s;
  YdNode     *v = yd_get(item, "drive");
  run->drive    = kind == 2;
  run->point    = kind == 0;
  if (!v) return 0;
  snprintf(sub, sizeof sub, "%s.drive", path);
  if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
  if (strcmp(s, "data") && strcmp(s, "scene"))
    FAIL("%s:%d: key '%s': expected data (the forward runs follow the data's history) or scene (the forward scene's own "
         "stages), got '%s'", doc->file, v->line, sub, s);
  run->drive = !strcmp(s, "data");
  if (run->drive && kind != 2)
    FAIL("%s:%d: key '%s': data needs an indentation forward scene (its load follows the data's); %s is a %s scene: "
         "give drive: scene and a forward scene whose stages are the data's", doc->file, v->line, sub, run->scene,
         kind ? "fe scene without an indenter" : "point");
  return 0;
}

int cal_run_read(const YdDoc *doc, YdNode *item, int k, CalRun *run, char *err, size_t errlen) {
  char        path[64], sub[128], where[PATH_MAX + 64];
  const char *s;
  YdNode     *v;
  memset(run, 0, sizeof *run);
  snprintf(path, sizeof path, "runs[%d]", k);
  if (yd_expect(doc, item, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(run->file, sizeof run->file, "%s", doc->file);
  run->index = k, run->line = item->line;
  snprintf(run->name, sizeof run->name, "run%d", k);
  snprintf(sub, sizeof sub, "%s.name", path);
  if ((v = yd_get(item, "name")) && !yd_string(doc, v, sub, &s, err, errlen)) snprintf(run->name, sizeof run->name, "%s", s);
  else if (v) return 1;
  snprintf(sub, sizeof sub, "%s.scene", path);
  if (!(v = yd_require(doc, item, "scene", YD_SCALAR, sub, err, errlen)) || yd_string(doc, v, sub, &s, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, v->line, sub);
  if (path_input(doc->file, where, s, run->scene, sizeof run->scene, err, errlen)) return 1;
  int kind = forward_kind(doc, sub, v->line, run->scene, err, errlen);
  if (kind < 0 || read_drive(doc, item, run, kind, path, err, errlen) || read_reference(doc, item, run, path, err, errlen))
    return 1;
  snprintf(sub, sizeof sub, "%s.options", path);
  if ((v = yd_get(item, "options")) && (yd_string(doc, v, sub, &s, err, errlen) ||
                                        snprintf(run->options, sizeof run->options, "%s", s) < 0))
    return 1;
  snprintf(sub, sizeof sub, "%s.set", path);
  if ((v = yd_get(item, "set")) && read_set(doc, v, run, sub, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.data", path);
  if (!(v = yd_require(doc, item, "data", YD_MAPPING, sub, err, errlen)) || read_data(doc, v, run, sub, err, errlen))
    return 1;
  if (kind == 2 && run->col_load >= 0 && cal_protocol_find(doc, run, err, errlen)) return 1;
  if (run->drive && (run->col_load < 0 || run->col_depth < 0))
    FAIL("%s:%d: key '%s.data.columns': drive: data needs the data's load and depth columns (the forward run's load "
         "follows the data's; its depth is compared)", doc->file, v->line, path);
  if (cal_load_read(doc, item, run, path, err, errlen) || (run->drive && cal_load_fit(run, err, errlen)) ||
      cal_drift_read(doc, item, run, path, err, errlen))
    return 1;
  if (read_residuals(doc, item, run, path, err, errlen)) return 1;
  return yd_check_unused(doc, item, path, "name, scene, drive, reference, options, set, data, residuals, drift, load_history",
                         err, errlen);
}
