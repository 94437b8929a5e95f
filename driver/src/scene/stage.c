#include "stage.h"

#include "../io/keydecl.h"

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

/* error: {measure: worst_point | volume | output, tol: t, relative_to: step | stage, floor: f} */
static int read_error(const YdDoc *doc, YdNode *x, const char *path, StepControl *sc, char *err, size_t errlen) {
  char sub[256];
  int  k = MEASURE_WORST_POINT;
  snprintf(sub, sizeof sub, "%s.error", path);
  if (yd_expect(doc, x, YD_MAPPING, sub, err, errlen)) return 1;
  if (keys_word(doc, x, "measure", NULL, &k, NULL, err, errlen)) return 1;
  sc->measure = (ErrorMeasure)k;
  YdNode *v;
  if (keys_number(doc, x, "tol", &sc->tol, &v, err, errlen)) return 1;
  if (!v && sc->measure != MEASURE_WORST_POINT)
    FAIL("%s:%d: key '%s': the %s measure needs a tol", doc->file, x->line, sub, measure_names[sc->measure]);
  int rel = 0;
  if (keys_word(doc, x, "relative_to", NULL, &rel, &v, err, errlen)) return 1;
  if (v && sc->measure != MEASURE_OUTPUT)
    FAIL("%s:%d: key '%s.relative_to': only the output measure takes it (this one is %s)", doc->file, v->line, sub,
         measure_names[sc->measure]);
  sc->per_stage = rel == 1;
  if (keys_number(doc, x, "floor", &sc->floor, &v, err, errlen)) return 1;
  if (v && sc->measure != MEASURE_OUTPUT)
    FAIL("%s:%d: key '%s.floor': only the output measure takes it (this one is %s)", doc->file, v->line, sub,
         measure_names[sc->measure]);
  return keys_check_unused(doc, x, NULL, err, errlen);
}

static int read_adaptive(const YdDoc *doc, YdNode *x, const char *path, double duration, StepControl *sc, char *err,
                         size_t errlen) {
  YdNode *v;
  sc->first = duration / 100, sc->min = 1e-12 * fmax(duration, 1), sc->max = duration;
  if (keys_number(doc, x, "first", &sc->first, NULL, err, errlen) || keys_number(doc, x, "min", &sc->min, NULL, err, errlen) ||
      keys_number(doc, x, "max", &sc->max, &v, err, errlen))
    return 1;
  if (!(sc->max >= sc->min)) /* a range that depends on another key: its value in the message */
    FAIL("%s:%d: key '%s.max': expected >= min (%g%s), got %g", doc->file, v ? v->line : x->line, path, sc->min,
         yd_get(x, "min") ? "" : ", its default 1e-12 max(duration, 1)", sc->max);
  if (keys_number(doc, x, "growth", &sc->growth, NULL, err, errlen)) return 1;
  if ((v = yd_get(x, "error")) && read_error(doc, v, path, sc, err, errlen)) return 1;
  return keys_check_unused(doc, x, "adaptive steps take first, min, max, growth, error", err, errlen);
}

int step_control_read(const YdDoc *doc, YdNode *x, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen) {
  YdNode *v;
  int     spacing = 0; /* linear */
  memset(sc, 0, sizeof *sc);
  sc->count = 1, sc->ratio = 1, sc->growth = 1.5, sc->measure = MEASURE_WORST_POINT;
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  if (keys_bool(doc, x, "adaptive", &sc->adaptive, NULL, err, errlen)) return 1;
  if (sc->adaptive) return read_adaptive(doc, x, path, duration, sc, err, errlen);
  if (keys_integer(doc, x, "count", &sc->count, NULL, err, errlen)) return 1;
  YdNode *sp, *r = yd_get(x, "ratio");
  if (keys_word(doc, x, "spacing", NULL, &spacing, &sp, err, errlen)) return 1;
  if (sp && spacing == 0 && r) FAIL("%s:%d: key '%s.ratio': linear spacing has no ratio", doc->file, r->line, path);
  if (sp ? spacing == 1 : r != NULL) { /* geometric */
    sc->ratio = 1.05;
    if (keys_number(doc, x, "ratio", &sc->ratio, NULL, err, errlen)) return 1;
  }
  if ((v = yd_get(x, "error")))
    FAIL("%s:%d: key '%s.error': an error measure needs adaptive steps (adaptive: true)", doc->file, v->line, path);
  return keys_check_unused(doc, x, "fixed steps take count, spacing, ratio", err, errlen);
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
  if (keys_number(doc, x, k, &ev->value, NULL, err, errlen)) return 1;
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
  return keys_check_unused(doc, v, NULL, err, errlen);
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
  int load = 1; /* the choices instant, linear */
  if (keys_number(doc, node, "duration", &st->duration, NULL, err, errlen) || keys_word(doc, node, "load", NULL, &load, NULL, err, errlen))
    return 1;
  st->instant = load == 0;
  if (st->duration < 0 || (st->duration == 0 && !st->instant))
    FAIL("%s:%d: key '%s.duration': expected a duration > 0 (or 0 with load: instant; a linear %s of zero duration "
         "would never apply its target), got %g", doc->file, yd_key_line(node, "duration"), path, word, st->duration);
  snprintf(sub, sizeof sub, "%s.steps", path);
  if (step_control_read(doc, yd_get(node, "steps"), sub, st->duration, &st->steps, err, errlen)) return 1;
  snprintf(sub, sizeof sub, "%s.until", path);
  if (stage_event_read(doc, yd_get(node, "until"), sub, events, &st->until, err, errlen)) return 1;
  if (keys_bool(doc, node, "creep", &st->creep, NULL, err, errlen)) return 1;
  /* fields at stage times: a kind that writes fields (FE); a point segment's 'output' is refused as not its key */
  if (keys_apply(node, "output") && (v = yd_get(node, "output")) && read_output_times(doc, v, path, st, err, errlen)) return 1;
  return 0;
}
