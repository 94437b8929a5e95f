/* Reading a material-point scene from YAML; every error names the file, the line and the key. */
#include "point_scene.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "../io/paths.h"
#include "../io/keydecl.h"
#include "../material/material_input.h"
#include "../scene/scene_keys.h"

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
    if (keys_number(doc, v, "factor", &eq->table_factor, NULL, err, errlen) || keys_check_unused(doc, v, NULL, err, errlen)) return 1;
    table_cols[*ntable] = (char *)col;
    eq->table_column    = (*ntable)++;
  } else if (yd_double(doc, v, sub, &eq->target, err, errlen)) {
    return 1;
  }
  return keys_check_unused(doc, nd, NULL, err, errlen);
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
  return keys_check_unused(doc, cn, NULL, err, errlen);
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

/* A creep segment's loading axis (for the plots). */
static int read_axis(YdDoc *doc, YdNode *nd, const char *path, int ntens, Segment *sg, char *err, size_t errlen) {
  sg->axis = ntens == 6 ? 2 : 1; /* the choices 11, 22, 33: the component's index */
  return keys_word(doc, nd, "axis", NULL, &sg->axis, NULL, err, errlen);
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
  if (keys_number(doc, tab, "time_factor", &tfac, NULL, err, errlen) || keys_check_unused(doc, tab, NULL, err, errlen)) return 1;
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
  char path[64];
  snprintf(path, sizeof path, "segments[%d]", index);
  memset(sg, 0, sizeof *sg);
  char *table_cols[8];
  int   ntable = 0;
  if (stage_read(doc, nd, path, index, "segment", "evp_rate_below, q_above, q_below, p_above", &sg->stage, err, errlen) ||
      read_controls(doc, nd, path, ntens, sg, table_cols, &ntable, err, errlen) ||
      read_constraints(doc, nd, path, ntens, sg, err, errlen) || check_equations(doc, nd, path, sg, ntens, err, errlen) ||
      read_axis(doc, nd, path, ntens, sg, err, errlen) || read_segment_table(doc, nd, path, sg, table_cols, ntable, err, errlen))
    return 1;
  return keys_check_unused(doc, nd, NULL, err, errlen);
}

int point_scene_read(YdDoc *doc, PointScene *sc, char *err, size_t errlen) {
  memset(sc, 0, sizeof *sc);
  YdNode     *root = doc->root, *x;
  const char *s;
  scene_keys_attach(doc, SCENE_POINT);
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
  if (keys_integer(doc, root, "ntens", &ntens, NULL, err, errlen)) return 1;
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
    if (keys_check_unused(doc, x, NULL, err, errlen)) return 1;
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
    if (keys_integer(doc, x, "progress_every", &sc->progress_every, NULL, err, errlen) || keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  }
  if (keys_bool(doc, root, "check_tangent", &sc->check_tangent, NULL, err, errlen)) return 1;

  YdNode *segs = yd_require(doc, root, "segments", YD_SEQUENCE, "segments", err, errlen);
  if (!segs) return 1;
  if (segs->n == 0) FAIL("%s:%d: key 'segments': expected at least one segment", doc->file, segs->line);
  sc->nseg = (int)segs->n;
  sc->seg  = calloc(segs->n, sizeof *sc->seg);
  for (int i = 0; i < sc->nseg; i++)
    if (read_segment(doc, segs->items[i], i, ntens, &sc->seg[i], err, errlen)) return 1;
  return keys_check_unused(doc, root, NULL, err, errlen) || keys_check_document(doc, err, errlen);
}

void point_scene_free(PointScene *sc) {
  for (int i = 0; i < sc->nseg; i++) {
    free(sc->seg[i].table_time);
    free(sc->seg[i].table);
  }
  free(sc->seg);
  memset(sc, 0, sizeof *sc);
}
