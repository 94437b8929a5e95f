#include "step_control.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

static const char *measure_names[] = {"worst_point", "volume", "output"};

const char *step_control_measure_name(ErrorMeasure m) { return measure_names[m]; }

/* error: {measure: worst_point | volume | output, tol: t} */
static int read_error(const YdDoc *doc, YdNode *x, const char *path, StepControl *sc, char *err, size_t errlen) {
  char        sub[256];
  const char *s;
  YdNode     *v;
  snprintf(sub, sizeof sub, "%s.error", path);
  if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen)) return 1;
  if ((v = yd_get(x, "measure"))) {
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    int k = 0;
    while (k < 3 && strcmp(s, measure_names[k])) k++;
    if (k == 3) FAIL("%s:%d: key '%s.measure': expected worst_point, volume or output, got '%s'", doc->file, v->line, sub, s);
    sc->measure = (ErrorMeasure)k;
  }
  if ((v = yd_get(x, "tol"))) {
    if (yd_double(doc, v, sub, &sc->tol, err, errlen)) return 1;
    if (!(sc->tol > 0 && sc->tol < 1))
      FAIL("%s:%d: key '%s.tol': expected 0 < tol < 1, got %g", doc->file, v->line, sub, sc->tol);
  } else if (sc->measure != MEASURE_WORST_POINT)
    FAIL("%s:%d: key '%s': the %s measure needs a tol", doc->file, x->line, sub, measure_names[sc->measure]);
  return yd_check_unused(doc, x, sub, "measure, tol", err, errlen);
}

static int read_adaptive(const YdDoc *doc, YdNode *x, const char *path, double duration, StepControl *sc, char *err,
                         size_t errlen) {
  YdNode *v;
  sc->first = duration / 100, sc->min = 1e-12 * fmax(duration, 1), sc->max = duration;
  const char *keys[] = {"first", "min", "max", "growth"};
  double     *dst[]  = {&sc->first, &sc->min, &sc->max, &sc->growth};
  for (int k = 0; k < 4; k++)
    if ((v = yd_get(x, keys[k])) && yd_double(doc, v, path, dst[k], err, errlen)) return 1;
  for (int k = 0; k < 4; k++) {
    int ok = k == 3 ? *dst[k] >= 1 : k == 2 ? *dst[k] >= sc->min : *dst[k] > 0;
    if (!ok)
      FAIL("%s:%d: key '%s.%s': expected %s, got %g", doc->file, yd_key_line(x, keys[k]), path, keys[k],
           k == 3 ? ">= 1" : k == 2 ? ">= min" : "> 0", *dst[k]);
  }
  if ((v = yd_get(x, "error")) && read_error(doc, v, path, sc, err, errlen)) return 1;
  return yd_check_unused(doc, x, path, "adaptive, first, min, max, growth, error", err, errlen);
}

int step_control_read(const YdDoc *doc, YdNode *x, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen) {
  YdNode     *v;
  const char *s;
  memset(sc, 0, sizeof *sc);
  sc->count = 1, sc->ratio = 1, sc->growth = 1.5, sc->measure = MEASURE_WORST_POINT;
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  if ((v = yd_get(x, "adaptive")) && yd_bool(doc, v, path, &sc->adaptive, err, errlen)) return 1;
  if (sc->adaptive) return read_adaptive(doc, x, path, duration, sc, err, errlen);
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
    if (!(sc->ratio > 0)) FAIL("%s:%d: key '%s.ratio': expected > 0, got %g", doc->file, x->line, path, sc->ratio);
  }
  if ((v = yd_get(x, "error")))
    FAIL("%s:%d: key '%s.error': an error measure needs adaptive steps (adaptive: true)", doc->file, v->line, path);
  return yd_check_unused(doc, x, path, "count, spacing, ratio (fixed steps) or adaptive, first, min, max, growth, error",
                         err, errlen);
}

double step_control_planned(const StepControl *sc, double duration, int k) {
  if (sc->adaptive) return sc->first;
  double first = sc->ratio == 1 ? duration / sc->count : duration * (sc->ratio - 1) / (pow(sc->ratio, sc->count) - 1);
  return first * pow(sc->ratio, k);
}

/* A relative measure is first order in dt (the estimate is O(dt^2), the increment O(dt)): the elementary
 * controller scales dt with 1/ratio. With the previous step's ratio too, the PI controller of Gustafsson
 * (ACM TOMS 17, 1991, 533-554; Soderlind, Numer. Algorithms 31, 2002, 281-310), with the exponents 0.7/k and
 * 0.4/k for k = 1: dt' = dt S ratio^-0.7 ratio_prev^0.4. It damps the cycle the elementary controller falls into
 * when the estimate lags the step (grow, grow, reject). worst_point follows the UMAT's PNEWDT, which already holds
 * its own safety factor. */
double step_control_next(const StepControl *sc, double dt, double pnewdt, double ratio, double ratio_prev) {
  double f = sc->growth;
  if (sc->measure == MEASURE_WORST_POINT || ratio < 0) f = fmin(f, pnewdt);
  else {
    double r = fmax(ratio, 1e-300), c = ratio_prev > 0 ? STEP_SAFETY * pow(r, -STEP_PI_I) * pow(ratio_prev, STEP_PI_P) : STEP_SAFETY / r;
    f = fmin(fmin(f, pnewdt), fmax(c, 0.2));
  }
  return fmin(fmax(dt * f, sc->min), sc->max);
}

double step_control_cut_factor(int diverged, double pnewdt, double ratio) {
  if (diverged) return STEP_CUT_DIVERGED;
  if (pnewdt < 1) return fmax(fmin(pnewdt, 0.5), 0.1);
  return fmax(fmin(STEP_SAFETY / ratio, 0.5), 0.1);
}

/* ---- until events ---- */

static const char *event_names[EVENT_KINDS] = {"", "evp_rate_below", "q_above", "q_below", "p_above", "depth", "load"};

const char *stage_event_name(EventKind k) { return event_names[k]; }

int stage_event_read(const YdDoc *doc, YdNode *x, const char *path, const char *allowed, StageEvent *ev, char *err,
                     size_t errlen) {
  ev->kind = EVENT_NONE, ev->value = 0;
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  if (x->n != 1) {
    snprintf(err, errlen, "%s:%d: key '%s': give exactly one of %s", doc->file, x->line, path, allowed);
    return 1;
  }
  const char *k = x->keys[0];
  int         kind = 1;
  while (kind < EVENT_KINDS && strcmp(k, event_names[kind])) kind++;
  /* the allowed list is comma separated: match a whole name */
  const char *hit = kind < EVENT_KINDS ? strstr(allowed, k) : NULL;
  size_t      len = strlen(k);
  if (!hit || (hit != allowed && hit[-1] != ' ') || (hit[len] && hit[len] != ',')) {
    snprintf(err, errlen, "%s:%d: unknown key '%s.%s': expected one of %s", doc->file, x->key_lines[0], path, k, allowed);
    return 1;
  }
  char sub[256];
  snprintf(sub, sizeof sub, "%s.%s", path, k);
  (void)yd_get(x, k);
  if (yd_double(doc, x->items[0], sub, &ev->value, err, errlen)) return 1;
  if (!(ev->value > 0) && kind != EVENT_Q_BELOW) {
    snprintf(err, errlen, "%s:%d: key '%s': expected > 0, got %g", doc->file, x->items[0]->line, sub, ev->value);
    return 1;
  }
  ev->kind = (EventKind)kind;
  return 0;
}

