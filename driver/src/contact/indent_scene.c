#include "indent_scene.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

static const double DEG = M_PI / 180;

static int read_stage(YdDoc *doc, YdNode *nd, int i, double copies, IndentStage *st, char *err, size_t errlen) {
  char    path[96], sub[128];
  YdNode *x;
  snprintf(path, sizeof path, "stages[%d].indenter", i);
  st->kind = IND_LOAD_HOLD; /* a stage that does not mention the indenter holds its load */
  if (!nd) return 0;
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  YdNode *load = yd_get(nd, "load"), *depth = yd_get(nd, "depth");
  if (!!load + !!depth != 1) FAIL("%s:%d: key '%s': give exactly one of load (force control) or depth (depth control)", doc->file, nd->line, path);
  if (depth) {
    st->kind = IND_DEPTH_RAMP;
    snprintf(sub, sizeof sub, "%s.depth", path);
    if (yd_double(doc, depth, sub, &st->target, err, errlen)) return 1;
  } else if (load->kind == YD_SCALAR && !strcmp(load->text, "hold")) {
    st->kind = IND_LOAD_HOLD;
  } else if (load->kind == YD_SCALAR) {
    st->kind = IND_LOAD_RAMP;
    snprintf(sub, sizeof sub, "%s.load", path);
    if (yd_double(doc, load, sub, &st->target, err, errlen)) return 1;
    if (st->target < 0) FAIL("%s:%d: key '%s': expected a load >= 0 (the indenter pushes; it cannot pull), got %g", doc->file, load->line, sub, st->target);
  } else {
    snprintf(sub, sizeof sub, "%s.load", path);
    if (load->kind != YD_MAPPING || !(x = yd_get(load, "exp")))
      FAIL("%s:%d: key '%s': expected a number, 'hold' or {exp: {P0, k}}", doc->file, load->line, sub);
    st->kind = IND_LOAD_EXP;
    char p0[160], pk[160];
    snprintf(sub, sizeof sub, "%s.load.exp", path);
    snprintf(p0, sizeof p0, "%s.P0", sub), snprintf(pk, sizeof pk, "%s.k", sub);
    if (yd_double(doc, yd_get(x, "P0"), p0, &st->P0, err, errlen) || yd_double(doc, yd_get(x, "k"), pk, &st->k, err, errlen)) return 1;
    if (!(st->P0 > 0)) FAIL("%s:%d: key '%s': expected > 0, got %g", doc->file, yd_key_line(x, "P0"), p0, st->P0);
    if (yd_check_unused(doc, x, sub, "P0, k", err, errlen) || yd_check_unused(doc, load, path, "exp", err, errlen)) return 1;
  }
  if ((x = yd_get(nd, "until"))) {
    snprintf(sub, sizeof sub, "%s.until", path);
    if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen)) return 1;
    YdNode *d = yd_get(x, "depth"), *l = yd_get(x, "load");
    if (yd_check_unused(doc, x, sub, "depth, load", err, errlen)) return 1; /* an unknown word first, by its name */
    if (!!d + !!l != 1) FAIL("%s:%d: key '%s': give one of depth or load, got %s", doc->file, x->line, sub, d ? "both" : "neither");
    if (d && yd_double(doc, d, sub, &st->until_depth, err, errlen)) return 1;
    if (l && yd_double(doc, l, sub, &st->until_load, err, errlen)) return 1;
    if (d && !(st->until_depth > 0)) FAIL("%s:%d: key '%s.depth': expected a depth > 0, got %g", doc->file, d->line, sub, st->until_depth);
    if (l && !(st->until_load > 0)) FAIL("%s:%d: key '%s.load': expected a load > 0, got %g", doc->file, l->line, sub, st->until_load);
    if (st->kind == IND_LOAD_HOLD || st->kind == IND_DEPTH_RAMP)
      FAIL("%s:%d: key '%s': an end event needs a rising load (a ramp or exp), not %s", doc->file, x->line, sub,
           st->kind == IND_LOAD_HOLD ? "load: hold" : "depth control");
  }
  if (st->kind == IND_LOAD_RAMP) st->target /= copies; /* the model carries 1/copies of the indenter's load */
  st->P0 /= copies, st->until_load /= copies;
  return yd_check_unused(doc, nd, path, "load, depth, until", err, errlen);
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
  if (yd_string(doc, yd_get(nd, "shape"), "indenter.shape", &s, err, errlen)) return 1;
  const char *shapes[] = {"berkovich", "cone", "wedge", "sphere", "flat_punch"};
  int         kind     = -1;
  for (int k = 0; k < 5; k++)
    if (!strcmp(s, shapes[k])) kind = k;
  v = yd_get(nd, "shape");
  if (kind < 0) FAIL("%s:%d: key 'indenter.shape': expected berkovich, cone, wedge, sphere or flat_punch, got '%s'", doc->file, v->line, s);
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
    if (yd_double(doc, yd_get(nd, "radius"), "indenter.radius", &sh->radius, err, errlen)) return 1;
    if (!(sh->radius > 0)) FAIL("%s:%d: key 'indenter.radius': expected > 0, got %g", doc->file, yd_key_line(nd, "radius"), sh->radius);
  }
  if ((v = yd_get(nd, "rotation"))) {
    double deg;
    if (sh->kind != SHAPE_BERKOVICH) FAIL("%s:%d: key 'indenter.rotation': only a Berkovich indenter has one", doc->file, v->line);
    if (yd_double(doc, v, "indenter.rotation", &deg, err, errlen)) return 1;
    sh->rotation = deg * DEG;
  }
  if ((v = yd_get(nd, "tip")) && yd_doubles(doc, v, "indenter.tip", sh->tip, dim, NULL, err, errlen)) return 1;
  if (yd_string(doc, yd_get(nd, "contact"), "indenter.contact", &s, err, errlen)) return 1;
  snprintf(is->contact_group, sizeof is->contact_group, "%s", s);
  if ((v = yd_get(nd, "gap"))) {
    if (yd_string(doc, v, "indenter.gap", &s, err, errlen)) return 1;
    if (strcmp(s, "normal") && strcmp(s, "vertical"))
      FAIL("%s:%d: key 'indenter.gap': expected normal (to the indenter surface, at the current position) or vertical "
           "(along the axis at the reference position: Sneddon's and Hertz's linearised contact), got '%s'", doc->file, v->line, s);
    sh->vertical = !strcmp(s, "vertical");
  }
  if ((v = yd_get(nd, "complementarity_c"))) {
    if (yd_double(doc, v, "indenter.complementarity_c", &is->c, err, errlen)) return 1;
    if (!(is->c > 0)) FAIL("%s:%d: key 'indenter.complementarity_c': expected > 0 (stress per length), got %g", doc->file, v->line, is->c);
  }
  is->copies = 1;
  if ((v = yd_get(nd, "copies"))) {
    if (yd_double(doc, v, "indenter.copies", &is->copies, err, errlen)) return 1;
    if (!(is->copies >= 1 && is->copies == floor(is->copies)))
      FAIL("%s:%d: key 'indenter.copies': expected a whole number >= 1 (how many copies of the model make the whole: 2 for a half "
           "model, 6 for a 60-degree sector), got %g", doc->file, v->line, is->copies);
    if (sc->kin != KIN_3D && is->copies != 1)
      FAIL("%s:%d: key 'indenter.copies': a %s model already carries the whole indenter's load (1), got %g", doc->file, v->line,
           sc->kin == KIN_AXISYMMETRIC ? "axisymmetric" : "plane-strain", is->copies);
  }
  if (yd_check_unused(doc, nd, "indenter", "shape, half_angle, tip_angle, radius, rotation, tip, contact, gap, complementarity_c, copies", err, errlen)) return 1;
  if (sc->kin == KIN_AXISYMMETRIC && (sh->tip[0] != 0))
    FAIL("%s:%d: key 'indenter.tip': axisymmetric: the tip must be on the axis (x = 0)", doc->file, yd_key_line(nd, "tip"));
  for (int i = 0; i < sc->nstage; i++)
    if (read_stage(doc, sc->stage[i].indenter, i, is->copies, &is->stage[i], err, errlen)) return 1;
  return 0;
}

double indent_stage_value(const IndentStage *st, double start, double lambda, double ts) {
  switch (st->kind) {
  case IND_LOAD_EXP: return st->P0 * exp(st->k * ts);  /* Yin et al. 2021 eqs. 25, 26 (alpha folded into k) */
  case IND_LOAD_HOLD: return start;
  default: return start + lambda * (st->target - start);
  }
}
