#include "stage.h"

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


/* output: {times: [...]} of a stage: increasing stage times in (0, duration]. */
static int read_output_times(const YdDoc *doc, YdNode *v, const char *path, Stage *st, char *err, size_t errlen) {
  char    sub[300];
  YdNode *t;
  snprintf(sub, sizeof sub, "%s.output", path);
  if (yd_expect(doc, v, YD_MAPPING, sub, err, errlen)) return 1;
  if ((t = yd_get(v, "times"))) {
    snprintf(sub, sizeof sub, "%s.output.times", path);
    if (yd_doubles(doc, t, sub, st->out_times, -STAGE_MAX_OUT_TIMES, &st->nout_times, err, errlen)) return 1;
    for (int k = 0; k < st->nout_times; k++)
      if (!(st->out_times[k] > (k ? st->out_times[k - 1] : 0) && st->out_times[k] <= st->duration))
        FAIL("%s:%d: key '%s[%d]': expected increasing stage times in (0, %g], got %g", doc->file, t->line, sub, k, st->duration,
             st->out_times[k]);
  }
  snprintf(sub, sizeof sub, "%s.output", path);
  return yd_check_unused(doc, v, sub, "times", err, errlen);
}

int stage_read(const YdDoc *doc, YdNode *node, const char *path, int index, const char *word, const char *events, Stage *st,
               char *err, size_t errlen) {
  YdNode     *v;
  const char *s;
  char        sub[300];
  memset(st, 0, sizeof *st);
  if (yd_expect(doc, node, YD_MAPPING, path, err, errlen)) return 1;
  snprintf(st->name, sizeof st->name, "%s%d", word, index);
  if ((v = yd_get(node, "name"))) {
    snprintf(sub, sizeof sub, "%s.name", path);
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    snprintf(st->name, sizeof st->name, "%s", s);
  }
  snprintf(sub, sizeof sub, "%s.duration", path);
  if (yd_double(doc, yd_get(node, "duration"), sub, &st->duration, err, errlen)) return 1;
  if ((v = yd_get(node, "load")) && v->kind == YD_SCALAR) {
    snprintf(sub, sizeof sub, "%s.load", path);
    if (yd_string(doc, v, sub, &s, err, errlen)) return 1;
    if (strcmp(s, "instant") && strcmp(s, "linear")) FAIL("%s:%d: key '%s': expected instant or linear, got '%s'", doc->file, v->line, sub, s);
    st->instant = !strcmp(s, "instant");
  }
  if (st->duration < 0 || (st->duration == 0 && !st->instant))
    FAIL("%s:%d: key '%s.duration': expected a duration > 0 (or 0 with load: instant; a linear %s of zero duration "
         "would never apply its target), got %g", doc->file, yd_key_line(node, "duration"), path, word, st->duration);
  snprintf(sub, sizeof sub, "%s.steps", path);
  if (step_control_read(doc, yd_get(node, "steps"), sub, st->duration, &st->steps, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.until", path);
  if (stage_event_read(doc, yd_get(node, "until"), sub, events, &st->until, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.creep", path);
  if ((v = yd_get(node, "creep")) && yd_bool(doc, v, sub, &st->creep, err, errlen)) return 1;
  if ((v = yd_get(node, "output")) && read_output_times(doc, v, path, st, err, errlen)) return 1;
  return 0;
}
