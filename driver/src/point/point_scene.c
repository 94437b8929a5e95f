/* Reading a material-point scene from YAML; every error names the file, the line and the key. */
#include "point_scene.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "../io/paths.h"
#include "../material/material_input.h"

static const char *component_names[6] = {"11", "22", "33", "12", "13", "23"};

int point_component(const char *key) {
  for (int i = 0; i < 6; i++)
    if (!strcmp(key, component_names[i])) return i;
  return -1;
}

#define FAIL(...)                            \
  do {                                       \
    snprintf(err, errlen, __VA_ARGS__);      \
    return 1;                                \
  } while (0)

/* {stress: x} or {strain: x} (or {strain: {column: name, factor: f}} in a table segment). */
static int read_equation(YdDoc *doc, YdNode *nd, const char *path, Equation *eq, char **table_cols, int *ntable,
                         char *err, size_t errlen) {
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  YdNode *s = yd_get(nd, "stress"), *e = yd_get(nd, "strain");
  if ((s != NULL) == (e != NULL)) FAIL("%s:%d: key '%s': expected exactly one of 'stress' or 'strain'", doc->file, nd->line, path);
  eq->kind         = s ? EQ_STRESS : EQ_STRAIN;
  eq->table_column = -1;
  YdNode *v        = s ? s : e;
  char    sub[160];
  snprintf(sub, sizeof sub, "%s.%s", path, s ? "stress" : "strain");
  if (v->kind == YD_MAPPING) {
    const char *col;
    eq->table_factor = 1;
    if (yd_string(doc, yd_get(v, "column"), sub, &col, err, errlen)) return 1;
    YdNode *f = yd_get(v, "factor");
    if (f && yd_double(doc, f, sub, &eq->table_factor, err, errlen)) return 1;
    if (yd_check_unused(doc, v, sub, "column, factor", err, errlen)) return 1;
    table_cols[*ntable] = (char *)col;
    eq->table_column    = (*ntable)++;
  } else if (yd_double(doc, v, sub, &eq->target, err, errlen)) {
    return 1;
  }
  return yd_check_unused(doc, nd, path, "stress, strain", err, errlen);
}


/* The equations of a segment, rows [a | b] of a.eps + b.sigma: linearly dependent rows make the step's
 * system singular whatever the material's tangent (two constraints alike, or one repeating a control). */
static int check_equations(YdDoc *doc, YdNode *nd, const char *path, const Segment *sg, int ntens, char *err,
                           size_t errlen) {
  double m[6][12] = {{0}};
  int    pivot_of_row[6];
  for (int c = 0; c < ntens; c++) {
    const Equation *eq = &sg->eq[c];
    if (eq->kind == EQ_STRAIN) m[c][c] = 1;
    else if (eq->kind == EQ_STRESS) m[c][6 + c] = 1;
    else
      for (int k = 0; k < ntens; k++) m[c][k] = eq->a[k], m[c][6 + k] = eq->b[k];
  }
  for (int r = 0; r < ntens; r++) { /* Gram-Schmidt-like elimination against the earlier rows */
    double scale = 0;
    for (int k = 0; k < 12; k++) scale = fmax(scale, fabs(m[r][k]));
    for (int q = 0; q < r; q++) {
      int pc = pivot_of_row[q];
      double f = m[r][pc] / m[q][pc];
      for (int k = 0; k < 12; k++) m[r][k] -= f * m[q][k];
    }
    int best = 0;
    for (int k = 1; k < 12; k++)
      if (fabs(m[r][k]) > fabs(m[r][best])) best = k;
    if (!(fabs(m[r][best]) > 1e-12 * scale))
      FAIL("%s:%d: key '%s': the control is singular: the equation of component %s%s depends on the others "
           "(whatever the material), so no strain increment satisfies them", doc->file, nd->line, path,
           component_names[r], sg->eq[r].kind == EQ_LINEAR ? " (a constraint replaces it)" : "");
    pivot_of_row[r] = best;
  }
  return 0;
}

/* A segment's name, duration and load (instant or linear). */
static int read_segment_head(YdDoc *doc, YdNode *nd, const char *path, int index, Segment *sg, char *err, size_t errlen) {
  char        sub[160];
  const char *s;
  YdNode     *x;
  snprintf(sg->name, sizeof sg->name, "segment%d", index);
  if ((x = yd_get(nd, "name"))) {
    snprintf(sub, sizeof sub, "%s.name", path);
    if (yd_string(doc, x, sub, &s, err, errlen)) return 1;
    snprintf(sg->name, sizeof sg->name, "%s", s);
  }
  snprintf(sub, sizeof sub, "%s.duration", path);
  if (yd_double(doc, yd_get(nd, "duration"), sub, &sg->duration, err, errlen)) return 1;
  if ((x = yd_get(nd, "load"))) {
    snprintf(sub, sizeof sub, "%s.load", path);
    if (yd_string(doc, x, sub, &s, err, errlen)) return 1;
    if (!strcmp(s, "instant")) sg->instant = 1;
    else if (strcmp(s, "linear"))
      FAIL("%s:%d: key '%s.load': expected 'instant' or 'linear', got '%s'", doc->file, x->line, path, s);
  }
  if (sg->duration < 0 || (sg->duration == 0 && !sg->instant))
    FAIL("%s:%d: key '%s.duration': expected a duration > 0 (or 0 with load: instant; a linear segment of zero duration "
         "would never apply its targets), got %g", doc->file, yd_key_line(nd, "duration"), path, sg->duration);
  return 0;
}

/* A segment's control: the equation of each component (given, or 'others'); table columns go to table_cols. */
static int read_controls(YdDoc *doc, YdNode *nd, const char *path, int ntens, Segment *sg, char **table_cols, int *ntable,
                         char *err, size_t errlen) {
  char    sub[160];
  YdNode *ctl = yd_get(nd, "control");
  snprintf(sub, sizeof sub, "%s.control", path);
  if (yd_expect(doc, ctl, YD_MAPPING, sub, err, errlen)) return 1;
  int given[6] = {0};
  for (size_t i = 0; i < ctl->n; i++) {
    if (!strcmp(ctl->keys[i], "others")) continue;
    int c = point_component(ctl->keys[i]);
    if (c < 0 || c >= ntens)
      FAIL("%s:%d: unknown key '%s.%s': expected a component %s or 'others'", doc->file, ctl->key_lines[i], sub,
           ctl->keys[i], ntens == 6 ? "11, 22, 33, 12, 13, 23" : "11, 22, 33, 12 (NTENS = 4)");
    ctl->used[i] = 1;
    char p2[200];
    snprintf(p2, sizeof p2, "%s.%s", sub, ctl->keys[i]);
    if (read_equation(doc, ctl->items[i], p2, &sg->eq[c], table_cols, ntable, err, errlen)) return 1;
    given[c] = 1;
  }
  YdNode *others = yd_get(ctl, "others");
  for (int c = 0; c < ntens; c++) {
    if (given[c]) continue;
    if (!others)
      FAIL("%s:%d: key '%s': component %s is not controlled: give it ({stress: ...} or {strain: ...}) or 'others'",
           doc->file, ctl->line, sub, component_names[c]);
    char p2[200];
    snprintf(p2, sizeof p2, "%s.others", sub);
    if (read_equation(doc, others, p2, &sg->eq[c], table_cols, ntable, err, errlen)) return 1;
  }
  return 0;
}

/* One linear constraint (path p2): replaces the equation of one component by a.eps + b.sigma = value. */
static int read_constraint(YdDoc *doc, YdNode *cn, const char *p2, int ntens, Segment *sg, char *err, size_t errlen) {
  if (yd_expect(doc, cn, YD_MAPPING, p2, err, errlen)) return 1;
  const char *rep;
  char        p3[240];
  snprintf(p3, sizeof p3, "%s.replaces", p2);
  if (yd_string(doc, yd_get(cn, "replaces"), p3, &rep, err, errlen)) return 1;
  int c = point_component(rep);
  if (c < 0 || c >= ntens) FAIL("%s:%d: key '%s': expected a component, got '%s'", doc->file, cn->line, p3, rep);
  Equation *eq = &sg->eq[c];
  memset(eq, 0, sizeof *eq);
  eq->kind         = EQ_LINEAR;
  eq->table_column = -1;
  eq->value        = NAN;
  const char *parts[2] = {"strain", "stress"};
  for (int part = 0; part < 2; part++) {
    YdNode *coef = yd_get(cn, parts[part]);
    if (!coef) continue;
    snprintf(p3, sizeof p3, "%s.%s", p2, parts[part]);
    if (yd_expect(doc, coef, YD_MAPPING, p3, err, errlen)) return 1;
    for (size_t j = 0; j < coef->n; j++) {
      int cc = point_component(coef->keys[j]);
      if (cc < 0 || cc >= ntens) FAIL("%s:%d: unknown key '%s.%s': expected a component", doc->file, coef->key_lines[j], p3, coef->keys[j]);
      coef->used[j] = 1;
      char p4[300];
      snprintf(p4, sizeof p4, "%s.%s", p3, coef->keys[j]);
      if (yd_double(doc, coef->items[j], p4, part ? &eq->b[cc] : &eq->a[cc], err, errlen)) return 1;
    }
  }
  int nonzero = 0;
  for (int k = 0; k < ntens; k++) nonzero |= eq->a[k] != 0 || eq->b[k] != 0;
  if (!nonzero)
    FAIL("%s:%d: key '%s': an empty constraint (no non-zero strain or stress coefficient): expected e.g. "
         "strain: {11: 1, 22: 1, 33: 1}", doc->file, cn->line, p2);
  YdNode *val = yd_get(cn, "value");
  snprintf(p3, sizeof p3, "%s.value", p2);
  if (val && yd_double(doc, val, p3, &eq->value, err, errlen)) return 1;
  return yd_check_unused(doc, cn, p2, "replaces, strain, stress, value (omitted: keep the value at the segment start)", err, errlen);
}

/* A segment's constraints: a sequence of linear constraints, each replacing one component's equation. */
static int read_constraints(YdDoc *doc, YdNode *nd, const char *path, int ntens, Segment *sg, char *err, size_t errlen) {
  char    sub[160];
  YdNode *x = yd_get(nd, "constraints");
  if (!x) return 0;
  snprintf(sub, sizeof sub, "%s.constraints", path);
  if (yd_expect(doc, x, YD_SEQUENCE, sub, err, errlen)) return 1;
  for (size_t k = 0; k < x->n; k++) {
    char p2[200];
    snprintf(p2, sizeof p2, "%s[%zu]", sub, k);
    if (read_constraint(doc, x->items[k], p2, ntens, sg, err, errlen)) return 1;
  }
  return 0;
}

/* A segment's end condition (until), creep flag and loading axis. */
static int read_until_axis(YdDoc *doc, YdNode *nd, const char *path, int ntens, Segment *sg, char *err, size_t errlen) {
  char        sub[160];
  const char *s;
  YdNode     *x;
  if ((x = yd_get(nd, "until"))) {
    snprintf(sub, sizeof sub, "%s.until", path);
    if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen) || x->n != 1)
      FAIL("%s:%d: key '%s': expected one of evp_rate_below, q_above, q_below, p_above", doc->file, x->line, sub);
    const char *k = x->keys[0];
    sg->until     = !strcmp(k, "evp_rate_below") ? UNTIL_EVP_RATE_BELOW
                    : !strcmp(k, "q_above")      ? UNTIL_Q_ABOVE
                    : !strcmp(k, "q_below")      ? UNTIL_Q_BELOW
                    : !strcmp(k, "p_above")      ? UNTIL_P_ABOVE
                                                 : UNTIL_NONE;
    if (sg->until == UNTIL_NONE)
      FAIL("%s:%d: unknown key '%s.%s': expected evp_rate_below, q_above, q_below or p_above", doc->file, x->key_lines[0], sub, k);
    x->used[0] = 1;
    if (yd_double(doc, x->items[0], sub, &sg->until_value, err, errlen)) return 1;
  }
  if ((x = yd_get(nd, "creep")) && yd_bool(doc, x, "creep", &sg->creep, err, errlen)) return 1;
  sg->axis = ntens == 6 ? 2 : 1;
  if ((x = yd_get(nd, "axis"))) {
    if (yd_string(doc, x, "axis", &s, err, errlen)) return 1;
    int c = point_component(s);
    if (c < 0 || c > 2) FAIL("%s:%d: key '%s.axis': expected 11, 22 or 33, got '%s'", doc->file, x->line, path, s);
    sg->axis = c;
  }
  return 0;
}

/* A segment's table of lab data (the time column and the columns the controls read). */
static int read_segment_table(YdDoc *doc, YdNode *nd, const char *path, Segment *sg, char **table_cols, int ntable, char *err,
                              size_t errlen) {
  char    sub[160];
  YdNode *tab = yd_get(nd, "table");
  if (ntable && !tab) FAIL("%s:%d: key '%s': a component reads a table column but the segment has no 'table'", doc->file, nd->line, path);
  if (!tab) return 0;
  snprintf(sub, sizeof sub, "%s.table", path);
  if (yd_expect(doc, tab, YD_MAPPING, sub, err, errlen)) return 1;
  const char *file, *tcol;
  double      tfac = 1;
  char pf[200], pt[200];
  snprintf(pf, sizeof pf, "%s.file", sub), snprintf(pt, sizeof pt, "%s.time", sub);
  if (yd_string(doc, yd_get(tab, "file"), pf, &file, err, errlen)) return 1;
  if (yd_string(doc, yd_get(tab, "time"), pt, &tcol, err, errlen)) return 1;
  YdNode *f = yd_get(tab, "time_factor");
  if (f && yd_double(doc, f, sub, &tfac, err, errlen)) return 1;
  if (yd_check_unused(doc, tab, sub, "file (relative to the scene file), time (column), time_factor", err, errlen)) return 1;
  char resolved[1024], where[1200];
  snprintf(where, sizeof where, "%s:%d: key '%s.file'", doc->file, yd_key_line(tab, "file"), sub);
  if (path_input(doc->file, where, file, resolved, sizeof resolved, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, tab->line, sub);
  const char *want[9];
  want[0] = tcol;
  for (int c = 0; c < ntable; c++) want[c + 1] = table_cols[c];
  double *data;
  int     rows;
  if (csv_read_columns(resolved, where, want, ntable + 1, 0, &data, &rows, err, errlen)) return 1;
  sg->table_rows = rows;
  sg->table_cols = ntable;
  sg->table_time = malloc(sizeof(double) * rows);
  sg->table      = malloc(sizeof(double) * rows * (ntable ? ntable : 1));
  for (int r = 0; r < rows; r++) {
    sg->table_time[r] = data[r * (ntable + 1)] * tfac;
    for (int c = 0; c < ntable; c++) sg->table[r * ntable + c] = data[r * (ntable + 1) + c + 1];
  }
  free(data);
  return 0;
}

static int read_segment(YdDoc *doc, YdNode *nd, int index, int ntens, Segment *sg, char *err, size_t errlen) {
  char path[64], sub[160];
  snprintf(path, sizeof path, "segments[%d]", index);
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  memset(sg, 0, sizeof *sg);
  char *table_cols[8];
  int   ntable = 0;
  if (read_segment_head(doc, nd, path, index, sg, err, errlen) ||
      read_controls(doc, nd, path, ntens, sg, table_cols, &ntable, err, errlen) ||
      read_constraints(doc, nd, path, ntens, sg, err, errlen) || check_equations(doc, nd, path, sg, ntens, err, errlen))
    return 1;
  snprintf(sub, sizeof sub, "%s.steps", path);
  if (step_control_read(doc, yd_get(nd, "steps"), sub, sg->duration, &sg->steps, err, errlen)) return 1;
  if (read_until_axis(doc, nd, path, ntens, sg, err, errlen) ||
      read_segment_table(doc, nd, path, sg, table_cols, ntable, err, errlen))
    return 1;
  return yd_check_unused(doc, nd, path,
                         "name, duration, load, control, constraints, steps, until, creep, axis, table", err, errlen);
}

int point_scene_read(YdDoc *doc, PointScene *sc, char *err, size_t errlen) {
  memset(sc, 0, sizeof *sc);
  YdNode     *root = doc->root, *x;
  const char *s;
  if (yd_string(doc, yd_get(root, "scene"), "scene", &s, err, errlen)) return 1;
  snprintf(sc->name, sizeof sc->name, "point");
  if ((x = yd_get(root, "name"))) {
    if (yd_string(doc, x, "name", &s, err, errlen)) return 1;
    snprintf(sc->name, sizeof sc->name, "%s", s);
  }
  if ((x = yd_get(root, "units"))) { /* stated for the reader; the UMAT's units are MPa and s */
    if (yd_expect(doc, x, YD_MAPPING, "units", err, errlen)) return 1;
    for (size_t i = 0; i < x->n; i++) x->used[i] = 1;
  }
  int ntens = 6;
  if ((x = yd_get(root, "ntens")) && yd_int(doc, x, "ntens", &ntens, err, errlen)) return 1;
  if (ntens != 6 && ntens != 4) FAIL("%s:%d: key 'ntens': expected 6 (3D) or 4 (plane strain), got %d", doc->file, x->line, ntens);
  if (!(x = yd_require(doc, root, "material", YD_MAPPING, "material", err, errlen)) ||
      material_read(doc, x, ntens, &sc->mat, err, errlen))
    return 1;

  if ((x = yd_get(root, "initial"))) {
    if (yd_expect(doc, x, YD_MAPPING, "initial", err, errlen)) return 1;
    YdNode *v;
    if ((v = yd_get(x, "stress")) && yd_doubles(doc, v, "initial.stress", sc->stress0, ntens, NULL, err, errlen)) return 1;
    if ((v = yd_get(x, "statev"))) {
      int got;
      if (yd_doubles(doc, v, "initial.statev", sc->statev0, -sc->mat.nstatv, &got, err, errlen)) return 1;
    }
    if (yd_check_unused(doc, x, "initial", "stress (both frames), statev", err, errlen)) return 1;
  }
  snprintf(sc->outdir, sizeof sc->outdir, "out/point/%s", sc->name);
  sc->progress_every = 0;
  if ((x = yd_get(root, "output"))) {
    if (yd_expect(doc, x, YD_MAPPING, "output", err, errlen)) return 1;
    YdNode *v;
    if ((v = yd_get(x, "directory"))) {
      if (yd_string(doc, v, "output.directory", &s, err, errlen)) return 1;
      snprintf(sc->outdir, sizeof sc->outdir, "%s", s);
    }
    if ((v = yd_get(x, "progress_every")) && yd_int_range(doc, v, "output.progress_every", 0, INT_MAX, &sc->progress_every, err, errlen)) return 1;
    if (yd_check_unused(doc, x, "output", "directory, progress_every", err, errlen)) return 1;
  }
  if ((x = yd_get(root, "check_tangent")) && yd_bool(doc, x, "check_tangent", &sc->check_tangent, err, errlen)) return 1;

  YdNode *segs = yd_require(doc, root, "segments", YD_SEQUENCE, "segments", err, errlen);
  if (!segs) return 1;
  if (segs->n == 0) FAIL("%s:%d: key 'segments': expected at least one segment", doc->file, segs->line);
  sc->nseg = (int)segs->n;
  sc->seg  = calloc(segs->n, sizeof *sc->seg);
  for (int i = 0; i < sc->nseg; i++)
    if (read_segment(doc, segs->items[i], i, ntens, &sc->seg[i], err, errlen)) return 1;
  return yd_check_unused(doc, root, "", "scene, name, units, ntens, material, initial, output, check_tangent, segments",
                         err, errlen);
}

void point_scene_free(PointScene *sc) {
  for (int i = 0; i < sc->nseg; i++) {
    free(sc->seg[i].table_time);
    free(sc->seg[i].table);
  }
  free(sc->seg);
  memset(sc, 0, sizeof *sc);
}
