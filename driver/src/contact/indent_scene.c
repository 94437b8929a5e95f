#include "indent_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../io/keydecl.h"

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

static const double DEG = M_PI / 180;

static const char *s_shape(ShapeKind k) { return (const char *[]){"berkovich", "cone", "wedge", "sphere", "flat_punch"}[k]; }

/* A load or depth table: a history in the stage time that covers the whole stage; a load's values >= 0. */
static int check_table(const YdDoc *doc, YdNode *nd, const char *path, double duration, IndentStage *st, char *err, size_t errlen) {
  const TimeFn *f = &st->fn;
  YdNode       *x = yd_get(nd, "table");
  double        t_end = f->t[f->n - 1];
  if (t_end < duration * (1 - 1e-9))
    FAIL("%s:%d: key '%s.table': the table's times end at %g s (the stage's time, after time_factor), before the stage's end "
         "(duration %g s): give the history over the whole stage", doc->file, x->line, path, t_end, duration);
  for (int r = 0; st->kind == IND_LOAD_TABLE && r < f->n; r++)
    if (f->v[r] < 0)
      FAIL("%s:%d: key '%s.table': the load at t = %g s (row %d) is %g: expected loads >= 0 (the indenter pushes; it cannot pull)",
           doc->file, x->line, path, f->t[r], r + 1, f->v[r]);
  return 0;
}

/* depth: a number or {table}; load: a number >= 0, hold, {exp: {P0, k}} or {table} (scene/time_function.h). */
static int read_function(const YdDoc *doc, YdNode *load, YdNode *depth, const char *path, double duration, IndentStage *st, char *err,
                         size_t errlen) {
  char sub[160];
  snprintf(sub, sizeof sub, "%s.%s", path, depth ? "depth" : "load");
  if (depth) {
    if (time_fn_read(doc, depth, sub, TF_ALLOW_NUMBER | TF_ALLOW_TABLE, "a number, {table: {file, time, value, time_factor, factor}}",
                     &st->fn, err, errlen))
      return 1;
    st->kind = st->fn.kind == TF_TABLE ? IND_DEPTH_TABLE : IND_DEPTH_RAMP;
  } else {
    if (time_fn_read(doc, load, sub, TF_ALLOW_NUMBER | TF_ALLOW_HOLD | TF_ALLOW_EXP | TF_ALLOW_TABLE,
                     "a number, 'hold', {exp: {P0, k}} or {table: {file, time, value, time_factor, factor}}", &st->fn, err, errlen))
      return 1;
    const IndentLoadKind kinds[] = {[TF_RAMP] = IND_LOAD_RAMP, [TF_HOLD] = IND_LOAD_HOLD, [TF_EXP] = IND_LOAD_EXP, [TF_TABLE] = IND_LOAD_TABLE};
    st->kind = kinds[st->fn.kind];
    if (st->kind == IND_LOAD_RAMP && st->fn.target < 0)
      FAIL("%s:%d: key '%s': expected a load >= 0 (the indenter pushes; it cannot pull), got %g", doc->file, load->line, sub, st->fn.target);
  }
  return st->fn.kind == TF_TABLE ? check_table(doc, depth ? depth : load, sub, duration, st, err, errlen) : 0;
}

/* until: {depth: h} or {until: {load: P}}, with a rising load, and not beside the stage's own until. */
static int read_until(const YdDoc *doc, YdNode *x, const char *path, const Stage *g, IndentStage *st, char *err, size_t errlen) {
  char sub[160];
  snprintf(sub, sizeof sub, "%s.until", path);
  if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen)) return 1;
  YdNode *d, *l;
  if (keys_number(doc, x, "depth", &st->until_depth, &d, err, errlen) || keys_number(doc, x, "load", &st->until_load, &l, err, errlen)) return 1;
  if (keys_check_unused(doc, x, NULL, err, errlen)) return 1; /* an unknown word first, by its name */
  if (!!d + !!l != 1) FAIL("%s:%d: key '%s': give one of depth or load, got %s", doc->file, x->line, sub, d ? "both" : "neither");
  if (st->kind == IND_LOAD_HOLD || indent_stage_depth_control(st))
    FAIL("%s:%d: key '%s': an end event needs a rising load (a ramp, exp or table), not %s", doc->file, x->line, sub,
         st->kind == IND_LOAD_HOLD ? "load: hold" : "depth control");
  if (g->until.kind != EVENT_NONE) { /* read now, so that no earlier stage runs first */
    YdNode *stage = x->parent ? x->parent->parent : NULL;
    FAIL("%s:%d: key '%s': %s %g, and the stage's until (line %d) %s %g: give one end event, not both", doc->file, x->line, sub,
         d ? "depth" : "load", d ? st->until_depth : st->until_load, yd_key_line(stage, "until"), stage_event_name(g->until.kind),
         g->until.value);
  }
  return 0;
}

/* One of copies mirror images carries 1/copies of the whole indenter's load: its load function and load event, here
   only (the history's loads are the whole indenter's again: stepping/indent_stepper.c). */
static void share_load(IndentStage *st, double copies) {
  if (!indent_stage_depth_control(st)) time_fn_share(&st->fn, copies);
  st->until_load /= copies;
}

static int read_stage(const YdDoc *doc, YdNode *nd, int i, const Stage *g, double copies, IndentStage *st, char *err, size_t errlen) {
  char    path[96];
  YdNode *x;
  snprintf(path, sizeof path, "stages[%d].indenter", i);
  st->kind = IND_LOAD_HOLD, st->fn.kind = TF_HOLD; /* a stage that does not mention the indenter holds its load */
  if (!nd) return 0;
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  YdNode *load = yd_get(nd, "load"), *depth = yd_get(nd, "depth");
  if (!!load + !!depth != 1) FAIL("%s:%d: key '%s': give exactly one of load (force control) or depth (depth control)", doc->file, nd->line, path);
  if (read_function(doc, load, depth, path, g->duration, st, err, errlen)) return 1;
  if ((x = yd_get(nd, "until")) && read_until(doc, x, path, g, st, err, errlen)) return 1;
  share_load(st, copies);
  return keys_check_unused(doc, nd, NULL, err, errlen);
}

int indent_scene_read(YdDoc *doc, const FeScene *sc, IndentScene *is, char *err, size_t errlen) {
  YdNode     *nd = sc->indenter, *v;
  const char *s;
  const int   dim = sc->kin == KIN_3D ? 3 : 2;
  memset(is, 0, sizeof *is);
  snprintf(is->file, sizeof is->file, "%s", doc->file);
  if (yd_expect(doc, nd, YD_MAPPING, "indenter", err, errlen)) return 1;
  IndenterShape *sh = &is->shape;
  sh->dim = dim;
  int kind = 0, gap = 0; /* the choices of shape (ShapeKind's order) and of gap (normal, vertical) */
  if (keys_word(doc, nd, "shape", NULL, &kind, &v, err, errlen)) return 1;
  sh->kind = (ShapeKind)kind;
  if (sh->kind == SHAPE_BERKOVICH && dim != 3)
    FAIL("%s:%d: key 'indenter.shape': berkovich needs a 3D mesh (axisymmetric: the cone of the same area, half_angle 70.3; plane strain: wedge)", doc->file, v->line);
  if (sh->kind == SHAPE_WEDGE && sc->kin != KIN_PLANE_STRAIN)
    FAIL("%s:%d: key 'indenter.shape': a wedge needs kinematics: plane_strain", doc->file, v->line);
  if (sh->kind == SHAPE_CONE && sc->kin == KIN_PLANE_STRAIN)
    FAIL("%s:%d: key 'indenter.shape': a cone in plane strain is a wedge: say shape: wedge", doc->file, v->line);
  if (sh->kind == SHAPE_BERKOVICH || sh->kind == SHAPE_CONE || sh->kind == SHAPE_WEDGE) {
    YdNode *ha = yd_get(nd, "half_angle"), *ta = yd_get(nd, "tip_angle");
    double  deg;
    if (!!ha + !!ta != 1) FAIL("%s:%d: key 'indenter': give half_angle (degrees, axis to face) or tip_angle (degrees, face to face)", doc->file, nd->line);
    if (yd_double(doc, ha ? ha : ta, ha ? "indenter.half_angle" : "indenter.tip_angle", &deg, err, errlen)) return 1;
    if (ta) deg /= 2;
    if (!(deg > 0 && deg < 90)) FAIL("%s:%d: key 'indenter.%s': expected a half-angle between 0 and 90 degrees, got %g", doc->file, (ha ? ha : ta)->line, ha ? "half_angle" : "tip_angle", ha ? deg : 2 * deg);
    sh->half_angle = deg * DEG;
  } else {
    if (keys_number(doc, nd, "radius", &sh->radius, &v, err, errlen)) return 1;
    if (!v) FAIL("%s:%d: key 'indenter.radius' is missing: expected a number (a %s has a radius)", doc->file, nd->line, s_shape(sh->kind));
  }
  double deg = 0;
  if (keys_number(doc, nd, "rotation", &deg, &v, err, errlen)) return 1;
  if (v && sh->kind != SHAPE_BERKOVICH) FAIL("%s:%d: key 'indenter.rotation': only a Berkovich indenter has one", doc->file, v->line);
  sh->rotation = deg * DEG;
  if ((v = yd_get(nd, "tip")) && yd_doubles(doc, v, "indenter.tip", sh->tip, dim, NULL, err, errlen)) return 1;
  if (yd_string(doc, yd_get(nd, "contact"), "indenter.contact", &s, err, errlen)) return 1;
  snprintf(is->contact_group, sizeof is->contact_group, "%s", s);
  if (keys_word(doc, nd, "gap", NULL, &gap, NULL, err, errlen) || keys_number(doc, nd, "complementarity_c", &is->c, NULL, err, errlen)) return 1;
  sh->vertical = gap == 1;
  is->copies = 1;
  if ((v = yd_get(nd, "copies"))) {
    if (yd_double(doc, v, "indenter.copies", &is->copies, err, errlen)) return 1;
    if (!(is->copies >= 1 && is->copies == floor(is->copies)))
      FAIL("%s:%d: key 'indenter.copies': expected a whole number >= 1 (how many copies of the model make the whole: 2 for a half "
           "model, 6 for a 60-degree sector), got %g", doc->file, v->line, is->copies);
    if (sc->kin == KIN_AXISYMMETRIC && is->copies != 1)
      FAIL("%s:%d: key 'indenter.copies': an axisymmetric model already carries the whole indenter's load (1), got %g", doc->file,
           v->line, is->copies);
    if (sc->kin == KIN_PLANE_STRAIN && is->copies > 2)
      FAIL("%s:%d: key 'indenter.copies': a plane-strain model is the whole body (1) or its half on one side of the indenter's "
           "axis (2), got %g", doc->file, v->line, is->copies);
  }
  if (keys_check_unused(doc, nd, NULL, err, errlen)) return 1;
  if (sc->kin == KIN_AXISYMMETRIC && (sh->tip[0] != 0))
    FAIL("%s:%d: key 'indenter.tip': axisymmetric: the tip must be on the axis (x = 0)", doc->file, yd_key_line(nd, "tip"));
  for (int i = 0; i < sc->nstage; i++)
    if (read_stage(doc, sc->loads[i].indenter, i, &sc->stage[i], is->copies, &is->stage[i], err, errlen)) return 1;
  return 0;
}

double indent_stage_value(const IndentStage *st, double start, double lambda, double ts) { return time_fn_value(&st->fn, start, lambda, ts); }

double indent_stage_time_of_load(const IndentStage *st, double start, double duration, double P) {
  return time_fn_time_of(&st->fn, start, duration, P);
}
