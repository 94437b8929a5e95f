/* summary.json (run_summary.h). */
#include "run_summary.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* A number as JSON (no NaN or Inf in JSON: null). */
static void num(FILE *fp, double v) {
  if (isfinite(v)) fprintf(fp, "%.10g", v);
  else fputs("null", fp);
}

/* A JSON string: quotes, backslashes and control characters escaped. */
static void str(FILE *fp, const char *v) {
  fputc('"', fp);
  for (const unsigned char *c = (const unsigned char *)v; *c; c++) {
    if (*c == '"' || *c == '\\') fprintf(fp, "\\%c", *c);
    else if (*c < 0x20) fprintf(fp, "\\u%04x", *c);
    else fputc(*c, fp);
  }
  fputc('"', fp);
}

/* {"name": value, ...} of the reported quantities, from a row of values. */
static void quantities(FILE *fp, const RunnerSummary *s, const double *v) {
  fputc('{', fp);
  for (int k = 0; k < s->nreport; k++) {
    fprintf(fp, "%s\"%s\": ", k ? ", " : "", s->report_names[k]);
    num(fp, v[k]);
  }
  fputc('}', fp);
}

static void stage_entry(FILE *fp, const FeScene *sc, const RunnerSummary *s, const MeshError *me, int k) {
  double change[RUNNER_MAX_REPORT];
  for (int q = 0; q < s->nreport; q++) change[q] = k ? s->report[k][q] - s->report[k - 1][q] : 0;
  fputs("    {\"name\": ", fp);
  str(fp, k ? sc->stage[k - 1].name : "start");
  fputs(", \"end\": ", fp);
  quantities(fp, s, s->report[k]);
  fputs(", \"change\": ", fp);
  quantities(fp, s, change);
  if (me && me->have) {
    fputs(", \"mesh_error\": {\"end\": ", fp);
    quantities(fp, s, me->end[k]);
    fputs(", \"change\": ", fp);
    quantities(fp, s, me->change[k]);
    fputc('}', fp);
  }
  fputs(", \"time_error\": ", fp);
  if (k && isfinite(s->time_error_change[k][0])) {
    fputs("{\"change\": ", fp);
    quantities(fp, s, s->time_error_change[k]);
    fputc('}', fp);
  } else fputs("null", fp);
  fprintf(fp, "}%s\n", k < s->nstages_done ? "," : "");
}

static void level_entry(FILE *fp, const RunInfo *r, int last) {
  fputs("    {\"dir\": ", fp);
  str(fp, r->dir);
  fprintf(fp, ", \"cells\": %ld, \"unknowns\": %ld, \"error_indicator\": ", r->cells, r->unknowns);
  num(fp, r->eta);
  fprintf(fp, ", \"cpu_s\": %.3f, \"wall_s\": %.3f, \"steps\": %d, \"cutbacks\": %d, \"newton_its\": %d, \"umat_calls\": %ld}%s\n", r->cpu,
          r->sum.wall, r->sum.steps, r->sum.cutbacks, r->sum.its, r->sum.umat_calls, last ? "" : ",");
}

int run_summary_write(const FeScene *sc, const char *dir, const RunInfo *levels, int nlevels, const MeshError *me, char *err, size_t errlen) {
  char                 part[1200], path[1100];
  const RunInfo       *a = &levels[nlevels - 1];
  const RunnerSummary *s = &a->sum;
  double               cpu = 0;
  snprintf(path, sizeof path, "%s/summary.json", dir);
  snprintf(part, sizeof part, "%s.part", path);
  FILE *fp = fopen(part, "w");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot write: %s", part, strerror(errno));
    return 1;
  }
  for (int l = 0; l < nlevels; l++) cpu += levels[l].cpu;
  fputs("{\n  \"scene\": ", fp);
  str(fp, sc->name);
  fprintf(fp, ", \"kind\": \"%s\", \"completed\": %s,\n  \"mesh\": {\"dir\": ", sc->indenter ? "indentation" : "fe", s->failed || s->stopped ? "false" : "true");
  str(fp, a->dir);
  fprintf(fp, ", \"cells\": %ld, \"unknowns\": %ld, \"order\": %d, \"error_indicator\": ", a->cells, a->unknowns, sc->order);
  num(fp, a->eta);
  fputs("},\n  \"mesh_error\": ", fp);
  if (me && me->have) fprintf(fp, "{\"how\": \"%s\", \"rate\": %.4g},\n", me->how, me->rate);
  else fputs("null,\n", fp);
  fputs("  \"stages\": [\n", fp);
  for (int k = 0; k <= s->nstages_done; k++) stage_entry(fp, sc, s, me, k);
  fprintf(fp, "  ],\n  \"counters\": {\"steps\": %d, \"cutbacks\": %d, \"rejected_by_error\": %d, \"newton_its\": %d, \"umat_calls\": %ld},\n", s->steps,
          s->cutbacks, s->rejected_error, s->its, s->umat_calls);
  fprintf(fp, "  \"cost\": {\"cpu_s\": %.3f, \"cpu_s_answer\": %.3f},\n  \"levels\": [\n", cpu, a->cpu);
  for (int l = 0; l < nlevels; l++) level_entry(fp, &levels[l], l == nlevels - 1);
  fputs("  ]\n}\n", fp);
  if (fclose(fp) || rename(part, path)) {
    snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
    return 1;
  }
  return 0;
}

/* " (mesh error m, time-step error t)" of a reported value, each where it was estimated (m >= 0, t finite). */
static void errors(double mesh, double time) {
  if (mesh >= 0 && isfinite(time)) printf(" (mesh error %.2g, time-step error %.2g)", mesh, time);
  else if (mesh >= 0) printf(" (mesh error %.2g)", mesh);
  else if (isfinite(time)) printf(" (time-step error %.2g)", time);
}

void run_summary_print(const FeScene *sc, const RunInfo *last, const MeshError *me) {
  const RunnerSummary *s = &last->sum;
  for (int k = 1; k <= s->nstages_done; k++) {
    printf("reported, stage '%s':", sc->stage[k - 1].name);
    for (int q = 0; q < s->nreport; q++) {
      double end = s->report[k][q], change = end - s->report[k - 1][q];
      printf(" %s %.6g", s->report_names[q], end);
      errors(me && me->have ? me->end[k][q] : -1, NAN);
      printf(", its change %.6g", change);
      errors(me && me->have ? me->change[k][q] : -1, s->time_error_change[k][q]);
      printf(";");
    }
    printf("\n");
  }
  if (!me || !me->have) printf("mesh error: not estimated (one mesh; mesh.adapt or -adapt_levels N gives it: docs/adapt.md)\n");
}
