/* The units of a calibrate run's data (docs/calibrate.md, "Units"): every data column's unit declared before a fit
 * runs (data.units, converted to the forward scene's units; data.factors; or units: scene), since a unit cannot be
 * seen in a curve (a time in minutes fits a viscosity 60 times off with a standard error as small as the right
 * one's). The data's ranges (time, load, depth, rates) beside the forward scene's own, for the dry run, and the
 * data's peak load against the forward scene's (drive: data: the forward run follows the data's loads, so a load
 * in the wrong unit shows only as the depth otherwise). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_units.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define SCALE_APART 10.0 /* as calibrate_check.c: a factor of 10 apart is a unit */

typedef struct {
  const char *name;
  double      si;
} Unit;

static const Unit TIME[]   = {{"s", 1}, {"ms", 1e-3}, {"min", 60}, {"h", 3600}, {NULL, 0}};
static const Unit FORCE[]  = {{"nN", 1e-9}, {"uN", 1e-6}, {"µN", 1e-6}, {"mN", 1e-3}, {"N", 1}, {"kN", 1e3}, {NULL, 0}};
static const Unit LENGTH[] = {{"nm", 1e-9}, {"um", 1e-6}, {"µm", 1e-6}, {"mm", 1e-3}, {"m", 1}, {NULL, 0}};
static const Unit VALUE[]  = {{"1", 1}, {"%", 1e-2}, {NULL, 0}};
static const Unit *FAMILY[4] = {TIME, FORCE, LENGTH, VALUE};
static const char *ROLES[4]  = {"time", "load", "depth", "value"};
static const char *LISTS[4]  = {"s, ms, min or h", "nN, uN, mN, N or kN", "nm, um, mm or m", "1 or % (a strain)"};

static const Unit *find_unit(const Unit *family, const char *name) {
  for (const Unit *u = family; u->name; u++)
    if (!strcmp(u->name, name)) return u;
  return NULL;
}

/* The forward scene's unit of a role (time, load, depth; value: 1), "" when it states none. */
static const char *scene_unit(const CalRun *run, int role) { return role == 3 ? "1" : run->scene_unit[role]; }

/* The forward scene's units: {time, force, length} (time: s when not stated: the UMAT's). */
static void read_scene_units(CalRun *run) {
  static const char *keys[3] = {"time", "force", "length"};
  YdDoc              fwd;
  char               msg[512];
  snprintf(run->scene_unit[0], sizeof run->scene_unit[0], "s");
  if (yd_load(run->scene, &fwd, msg, sizeof msg)) return;
  YdNode *u = yd_get(fwd.root, "units");
  for (int k = 0; u && u->kind == YD_MAPPING && k < 3; k++) {
    YdNode *v = yd_get(u, keys[k]);
    if (v && v->kind == YD_SCALAR) snprintf(run->scene_unit[k], sizeof run->scene_unit[k], "%s", v->text);
  }
  yd_free(&fwd);
}

/* A unit named in a column's name (time_min, load_mN, "depth (nm)", P[uN]): the text after its last '_', '(' or
 * '[' up to ')' or ']', if it is one of the role's units; else "". */
static const char *unit_in_name(const char *col, int role, char *buf, size_t n) {
  const char *s = col, *p;
  for (p = col; *p; p++)
    if (*p == '_' || *p == '(' || *p == '[' || *p == ' ') s = p + 1;
  snprintf(buf, n, "%s", s);
  buf[strcspn(buf, ")]")] = '\0';
  return find_unit(FAMILY[role], buf) ? buf : "";
}

const char *cal_unit_key(const CalRun *run, int role, char *buf, size_t n) {
  if (run->declared[role] == 1) snprintf(buf, n, "runs[%d].data.units.%s", run->index, ROLES[role]);
  else if (run->declared[role] == 3) snprintf(buf, n, "runs[%d].data.units", run->index);
  else snprintf(buf, n, "runs[%d].data.factors.%s", run->index, ROLES[role]);
  return buf;
}

const char *cal_unit_how(const CalRun *run, int role, char *buf, size_t n) {
  if (run->declared[role] == 1) snprintf(buf, n, "unit %s, factor %g", run->unit[role], run->factor[role]);
  else if (run->declared[role] == 2) snprintf(buf, n, "factor %g", run->factor[role]);
  else snprintf(buf, n, "the forward scene's units");
  return buf;
}

int cal_units_read(const YdDoc *doc, YdNode *data, CalRun *run, const char *path, char *err, size_t errlen) {
  const int col[4] = {run->col_time, run->col_load, run->col_depth, run->col_value};
  char      sub[256], hint[64];
  YdNode   *u = yd_get(data, "units");
  read_scene_units(run);
  run->data_line = data->line;
  snprintf(sub, sizeof sub, "%s.units", path);
  if (u && u->kind == YD_SCALAR) {
    if (strcmp(u->text, "scene"))
      FAIL("%s:%d: key '%s': expected scene (every column in the forward scene's units) or a mapping {time, load, depth, "
           "value}, got '%s'", doc->file, u->line, sub, u->text);
    for (int r = 0; r < 4; r++)
      if (!run->declared[r]) run->declared[r] = 3;
  } else if (u) {
    if (yd_expect(doc, u, YD_MAPPING, sub, err, errlen)) return 1;
    for (int r = 0; r < 4; r++) {
      YdNode     *v = yd_get(u, ROLES[r]);
      const char *name;
      if (!v) continue;
      snprintf(sub, sizeof sub, "%s.units.%s", path, ROLES[r]);
      if (yd_string(doc, v, sub, &name, err, errlen)) return 1;
      if (col[r] < 0)
        FAIL("%s:%d: key '%s': a unit for a column that is not given (%s.columns.%s is missing)", doc->file, v->line, sub,
             path, ROLES[r]);
      if (run->declared[r] == 2)
        FAIL("%s:%d: key '%s': the column '%s' has a unit and a factor (%s.factors.%s): give one of them", doc->file,
             v->line, sub, run->col_name[r], path, ROLES[r]);
      const Unit *a = find_unit(FAMILY[r], name), *b = find_unit(FAMILY[r], scene_unit(run, r));
      if (!a) FAIL("%s:%d: key '%s': expected %s, got '%s'", doc->file, v->line, sub, LISTS[r], name);
      if (!b)
        FAIL("%s:%d: key '%s': the forward scene %s states no %s unit that calibrate knows (its units.%s: '%s'): give "
             "the factor to its units instead (%s.factors.%s)", doc->file, v->line, sub, run->scene, ROLES[r],
             r == 1 ? "force" : "length", scene_unit(run, r), path, ROLES[r]);
      snprintf(run->unit[r], sizeof run->unit[r], "%s", name);
      run->factor[r]   = a->si / b->si;
      run->declared[r] = 1;
    }
    if (yd_check_unused(doc, u, sub, "time, load, depth, value", err, errlen)) return 1;
  }
  char missing[512] = "";
  int  first = -1, count = 0;
  for (int r = 0; r < 4; r++)
    if (col[r] >= 0 && !run->declared[r]) {
      size_t len = strlen(missing);
      const char *h = unit_in_name(run->col_name[r], r, hint, sizeof hint);
      snprintf(missing + len, sizeof missing - len, "%s'%s' (%s%s%s%s)", count ? ", " : "", run->col_name[r], ROLES[r],
               h[0] ? "; its name says " : "", h, h[0] ? ": say so" : "");
      if (first < 0) first = r;
      count++;
    }
  if (first < 0) return 0;
  char scene_units[160];
  snprintf(scene_units, sizeof scene_units, "time %s, load %s, depth %s", scene_unit(run, 0),
           scene_unit(run, 1)[0] ? scene_unit(run, 1) : "?", scene_unit(run, 2)[0] ? scene_unit(run, 2) : "?");
  FAIL("%s:%d: key '%s.units.%s': the unit of the data column%s %s %s not declared: a unit cannot be seen in a curve (a "
       "time in minutes read as seconds fits a viscosity 60 times off, with a standard error as small as the right "
       "one's). Declare each column's unit, %s.units: {time: s|min|h, load: nN|uN|mN|N, depth: nm|um|mm, value: 1|%%} "
       "(converted to the forward scene's: %s), or its factor (%s.factors), or units: scene if every column is in "
       "the forward scene's units", doc->file, run->data_line, path, ROLES[first], count > 1 ? "s" : "", missing,
       count > 1 ? "are" : "is", path, scene_units, path);
}

/* The forward scene's own protocol: its time (at most, when a stage ends on an event), its peak load, each stage's
 * loading rate. Indentation stages: a load ramp to a number, hold, {exp: {P0, k}} (until a load). */
typedef struct {
  double time, peak;
  int    until, have_peak, nstage;
  char   rates[512];
} ScenePlan;

static double scalar(YdNode *nd, const char *key, int *ok) {
  YdNode *v = nd && nd->kind == YD_MAPPING ? yd_get(nd, key) : NULL;
  double  x = 0;
  *ok       = v && v->kind == YD_SCALAR && sscanf(v->text, "%lf", &x) == 1;
  return x;
}

static void scene_plan(const CalRun *run, ScenePlan *sp) {
  YdDoc fwd;
  char  msg[512];
  memset(sp, 0, sizeof *sp);
  if (yd_load(run->scene, &fwd, msg, sizeof msg)) return;
  YdNode *stages = yd_get(fwd.root, run->point ? "segments" : "stages");
  double  level  = 0;
  for (size_t i = 0; stages && stages->kind == YD_SEQUENCE && i < stages->n; i++) {
    YdNode *st = stages->items[i];
    int     ok, okp, okk;
    double  dur = scalar(st, "duration", &ok), rate = NAN, rate2 = NAN;
    if (!ok) continue;
    YdNode *ind  = st->kind == YD_MAPPING ? yd_get(st, "indenter") : NULL;
    YdNode *load = ind && ind->kind == YD_MAPPING ? yd_get(ind, "load") : NULL;
    YdNode *unt  = ind && ind->kind == YD_MAPPING ? yd_get(ind, "until") : NULL;
    double  pu   = scalar(unt, "load", &ok);
    if (unt) sp->until = 1;
    if (load && load->kind == YD_SCALAR && !strcmp(load->text, "hold")) rate = 0;
    else if (load && load->kind == YD_SCALAR && sscanf(load->text, "%lf", &rate2) == 1) {
      rate = (rate2 - level) / dur, level = rate2, sp->peak = fmax(sp->peak, level), sp->have_peak = 1;
      rate2 = NAN;
    } else if (load && load->kind == YD_MAPPING && yd_get(load, "exp")) {
      YdNode *e  = yd_get(load, "exp");
      double  p0 = scalar(e, "P0", &okp), k = scalar(e, "k", &okk);
      if (okp && okk && p0 > 0 && k > 0) {
        double end = ok && pu > p0 ? fmin(pu, p0 * exp(k * dur)) : p0 * exp(k * dur);
        dur  = log(end / p0) / k;
        rate = k * p0, rate2 = k * end, level = end, sp->peak = fmax(sp->peak, end), sp->have_peak = 1;
      }
    }
    sp->time += dur, sp->nstage++;
    YdNode *nm = st->kind == YD_MAPPING ? yd_get(st, "name") : NULL;
    size_t  len = strlen(sp->rates);
    if (!isnan(rate) && len < sizeof sp->rates - 80)
      snprintf(sp->rates + len, sizeof sp->rates - len, isnan(rate2) ? "%s%s %.3g" : "%s%s %.3g to %.3g", len ? ", " : "",
               nm && nm->kind == YD_SCALAR ? nm->text : "?", rate, rate2);
  }
  yd_free(&fwd);
}

static void range_of(const CalRun *run, int col, double *lo, double *hi) {
  *lo = INFINITY, *hi = -INFINITY;
  for (int i = 0; i < run->rows; i++) *lo = fmin(*lo, run->data[i * run->ncol + col]), *hi = fmax(*hi, run->data[i * run->ncol + col]);
}

void cal_ranges_describe(const CalRun *run, char *buf, size_t n) {
  double    lo, hi;
  ScenePlan sp;
  size_t    len;
  const char *fu = run->scene_unit[1][0] ? run->scene_unit[1] : "(load)", *lu = run->scene_unit[2][0] ? run->scene_unit[2] : "(length)";
  range_of(run, run->col_time, &lo, &hi);
  snprintf(buf, n, "  data, in the forward scene's units: time %.4g to %.4g s (%.4g s)", lo, hi, hi - lo);
  if (run->col_load >= 0) {
    range_of(run, run->col_load, &lo, &hi), len = strlen(buf);
    snprintf(buf + len, n - len, ", load %.4g to %.4g %s", lo, hi, fu);
  }
  if (run->col_depth >= 0) {
    range_of(run, run->col_depth, &lo, &hi), len = strlen(buf);
    snprintf(buf + len, n - len, ", depth %.4g to %.4g %s", lo, hi, lu);
  }
  if (run->col_value >= 0) {
    range_of(run, run->col_value, &lo, &hi), len = strlen(buf);
    snprintf(buf + len, n - len, ", value %.4g to %.4g", lo, hi);
  }
  if (run->col_load >= 0 && run->nstage > 0) { /* each data stage's mean rate of load */
    len = strlen(buf);
    snprintf(buf + len, n - len, "; load rate (%s/s, each stage's mean):", fu);
    for (int j = 0; j < run->nstage; j++) {
      int    a  = j ? run->stage[j - 1].row1 : 0, b = run->stage[j].row1;
      double dt = run->data[b * run->ncol + run->col_time] - run->data[a * run->ncol + run->col_time];
      double dp = run->data[b * run->ncol + run->col_load] - run->data[a * run->ncol + run->col_load];
      len       = strlen(buf);
      snprintf(buf + len, n - len, "%s %s %.3g", j ? "," : "", run->stage[j].name, dt > 0 ? dp / dt : 0);
    }
  }
  scene_plan(run, &sp);
  len = strlen(buf);
  snprintf(buf + len, n - len, "\n  forward scene's own protocol: time %s%.4g s (%d stages)", sp.until ? "up to " : "", sp.time,
           sp.nstage);
  if (sp.have_peak) {
    len = strlen(buf);
    snprintf(buf + len, n - len, ", load to %.4g %s; load rate (%s/s): %s", sp.peak, fu, fu, sp.rates);
  }
  for (int r = 0; r < 4; r++) { /* how each column's unit was declared */
    const int col[4] = {run->col_time, run->col_load, run->col_depth, run->col_value};
    if (col[r] < 0) continue;
    len = strlen(buf);
    if (run->declared[r] == 1)
      snprintf(buf + len, n - len, "%s %s '%s' in %s (factor %g)", r ? "," : "\n  units of the data:", ROLES[r], run->col_name[r], run->unit[r],
               run->factor[r]);
    else if (run->declared[r] == 2)
      snprintf(buf + len, n - len, "%s %s '%s' times factor %g", r ? "," : "\n  units of the data:", ROLES[r], run->col_name[r], run->factor[r]);
    else snprintf(buf + len, n - len, "%s %s '%s' in the scene's units", r ? "," : "\n  units of the data:", ROLES[r], run->col_name[r]);
  }
}

int cal_check_load_scale(const CalRun *run, int accept, char *err, size_t errlen) {
  ScenePlan sp;
  double    lo, hi;
  char      key[96];
  if (!run->drive || run->col_load < 0 || (accept & CAL_ACCEPT_SCALE)) return 0;
  scene_plan(run, &sp);
  range_of(run, run->col_load, &lo, &hi);
  if (!sp.have_peak || !(hi > 0) || (hi / sp.peak <= SCALE_APART && hi / sp.peak >= 1 / SCALE_APART)) return 0;
  char how[96];
  FAIL("%s:%d: key '%s' (column '%s', %s): the data's loads reach %.4g where the forward scene's own protocol reaches "
       "%.4g (%s), %.3g times as much: a unit? The forward runs follow the data's loads, so a load in the wrong unit "
       "would show only as the depths. The %s converts the data to the forward scene's units (%s); accept: [scale] if "
       "the record is meant to be that far from the forward scene's loads (its mesh must cover the contact)", run->file,
       run->data_line, cal_unit_key(run, 1, key, sizeof key), run->col_name[1], cal_unit_how(run, 1, how, sizeof how), hi,
       sp.peak, run->scene, hi / sp.peak, run->declared[1] == 2 ? "factor" : "unit",
       run->scene_unit[1][0] ? run->scene_unit[1] : "its force unit");
}
