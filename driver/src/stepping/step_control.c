#include "step_control.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

int step_control_read(const YdDoc *doc, YdNode *x, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen) {
  YdNode     *v;
  const char *s;
  memset(sc, 0, sizeof *sc);
  sc->count = 1, sc->ratio = 1, sc->growth = 1.5;
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  if ((v = yd_get(x, "adaptive")) && yd_bool(doc, v, path, &sc->adaptive, err, errlen)) return 1;
  if (sc->adaptive) {
    sc->first = duration / 100, sc->min = 1e-12 * fmax(duration, 1), sc->max = duration;
    if ((v = yd_get(x, "first")) && yd_double(doc, v, path, &sc->first, err, errlen)) return 1;
    if ((v = yd_get(x, "min")) && yd_double(doc, v, path, &sc->min, err, errlen)) return 1;
    if ((v = yd_get(x, "max")) && yd_double(doc, v, path, &sc->max, err, errlen)) return 1;
    if ((v = yd_get(x, "growth")) && yd_double(doc, v, path, &sc->growth, err, errlen)) return 1;
    if (!(sc->first > 0 && sc->min > 0 && sc->max >= sc->min && sc->growth >= 1))
      FAIL("%s:%d: key '%s': expected first > 0, min > 0, max >= min, growth >= 1", doc->file, x->line, path);
    return yd_check_unused(doc, x, path, "adaptive, first, min, max, growth", err, errlen);
  }
  if ((v = yd_get(x, "count")) && yd_int(doc, v, path, &sc->count, err, errlen)) return 1;
  if (sc->count < 1) FAIL("%s:%d: key '%s.count': expected >= 1, got %d", doc->file, x->line, path, sc->count);
  YdNode *sp = yd_get(x, "spacing"), *r = yd_get(x, "ratio");
  int     geometric = r != NULL;
  if (sp) {
    if (yd_string(doc, sp, path, &s, err, errlen)) return 1;
    if (strcmp(s, "geometric") && strcmp(s, "linear"))
      FAIL("%s:%d: key '%s.spacing': expected 'linear' or 'geometric', got '%s'", doc->file, sp->line, path, s);
    if (!strcmp(s, "linear") && r) FAIL("%s:%d: key '%s.ratio': linear spacing has no ratio", doc->file, r->line, path);
    geometric = !strcmp(s, "geometric");
  }
  if (geometric) {
    sc->ratio = 1.05;
    if (r && yd_double(doc, r, path, &sc->ratio, err, errlen)) return 1;
    if (!(sc->ratio > 0)) FAIL("%s:%d: key '%s.ratio': expected > 0", doc->file, x->line, path);
  }
  return yd_check_unused(doc, x, path, "count, spacing, ratio (fixed steps) or adaptive, first, min, max, growth", err,
                         errlen);
}

double step_control_planned(const StepControl *sc, double duration, int k) {
  if (sc->adaptive) return sc->first;
  double first = sc->ratio == 1 ? duration / sc->count : duration * (sc->ratio - 1) / (pow(sc->ratio, sc->count) - 1);
  return first * pow(sc->ratio, k);
}

double step_control_next(const StepControl *sc, double dt, double pnewdt) {
  return fmin(fmax(dt * fmin(pnewdt, sc->growth), sc->min), sc->max);
}
