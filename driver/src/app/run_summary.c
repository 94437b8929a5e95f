/* summary.json (run_summary.h). */
#include "run_summary.h"

#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "../io/json_write.h"

/* {"name": value, ...} of the reported quantities, from a row of values. */
static void quantities(FILE *fp, const RunnerSummary *s, const double *v) {
  fputc('{', fp);
  for (int k = 0; k < s->nreport; k++) {
    fprintf(fp, "%s\"%s\": ", k ? ", " : "", s->report_names[k]);
    json_num(fp, v[k]);
  }
  fputc('}', fp);
}

static void stage_entry(FILE *fp, const char *name, const RunnerSummary *s, const MeshError *me, int k) {
  double change[RUNNER_MAX_REPORT];
  for (int q = 0; q < s->nreport; q++) change[q] = k ? s->report[k][q] - s->report[k - 1][q] : 0;
  fputs("    {\"name\": ", fp);
  json_str(fp, name);
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

int run_summary_due(int rc, const RunnerSummary *s) { return s->ran && rc != 2; }

void run_summary_error(int rc, const char *err, char *buf, size_t n) {
  const char *text = NULL;
  if (err && err[0]) snprintf(buf, n, "%s", err);
  else if (rc > 2 && !PetscErrorMessage(rc, &text, NULL) && text) snprintf(buf, n, "a PETSc error (code %d): %s", rc, text);
  else snprintf(buf, n, "a PETSc error (code %d): the run's log says more", rc);
}

/* Whether the run completed: every stage ran, not stopped by -max_steps, no failure after the stages. */
static int completed(const RunnerSummary *s, const RunEnd *end) { return !s->failed && !s->stopped && !(end && end->error); }

/* "failure": null, or where the run failed: the stage it was in (index s->nstages_done, the stages before it done;
   null past the last), the time reached, with adaptation the level, and the run's message. */
static void failure_entry(FILE *fp, const char *const *name, int nname, const RunnerSummary *s, const RunEnd *end) {
  fputs(",\n  \"failure\": ", fp);
  if (!end || !end->error) {
    fputs("null", fp);
    return;
  }
  fputs("{\"stage\": ", fp);
  if (s->nstages_done < nname) json_str(fp, name[s->nstages_done]);
  else fputs("null", fp);
  fprintf(fp, ", \"stage_index\": %d, \"time\": ", s->nstages_done);
  json_num(fp, s->t);
  if (end->level >= 0) fprintf(fp, ", \"level\": %d", end->level);
  fputs(", \"error\": ", fp);
  json_str(fp, end->error);
  fputc('}', fp);
}

/* What the stage runner's kinds (fe, indentation, point) share: the reported quantities at the start and each
   stage's end (stage k - 1 named name[k - 1], of nname), the counters, and the failure. */
static void stages_and_counters(FILE *fp, const char *const *name, int nname, const RunnerSummary *s, const MeshError *me, const RunEnd *end) {
  fputs(",\n  \"stages\": [\n", fp);
  for (int k = 0; k <= s->nstages_done; k++) stage_entry(fp, k ? name[k - 1] : "start", s, me, k);
  fprintf(fp, "  ],\n  \"counters\": {\"steps\": %d, \"cutbacks\": %d, \"rejected_by_error\": %d, \"rejected_by_umat\": %d, "
              "\"rejected_stalled\": %d, \"rejected_not_converged\": %d, \"jumps\": %d, \"newton_its\": %d, \"umat_calls\": %ld}",
          s->steps, s->cutbacks, s->rejected_error, s->rejected_umat, s->rejected_stalled, s->rejected_unconverged, s->jumps, s->its, s->umat_calls);
  failure_entry(fp, name, nname, s, end);
}

static void level_entry(FILE *fp, const RunInfo *r, int last) {
  fputs("    {\"dir\": ", fp);
  json_str(fp, r->dir);
  fprintf(fp, ", \"cells\": %ld, \"unknowns\": %ld, \"error_indicator\": ", r->cells, r->unknowns);
  json_num(fp, r->eta);
  fprintf(fp, ", \"cpu_s\": %.3f, \"wall_s\": %.3f, \"steps\": %d, \"cutbacks\": %d, \"newton_its\": %d, \"umat_calls\": %ld, \"kept\": %s}%s\n",
          r->cpu, r->sum.wall, r->sum.steps, r->sum.cutbacks, r->sum.its, r->sum.umat_calls, r->kept ? "true" : "false", last ? "" : ",");
}

int run_summary_write(const FeScene *sc, const char *dir, const RunInfo *levels, int nlevels, const MeshError *me, const RunEnd *end,
                      char *err, size_t errlen) {
  char                 part[1200];
  const RunInfo       *a = &levels[nlevels - 1];
  const RunnerSummary *s = &a->sum;
  const char          *names[RUNNER_MAX_STAGES];
  double               cpu = 0;
  FILE                *fp  = json_file_open(dir, "summary.json", part, sizeof part, err, errlen);
  if (!fp) return 1;
  for (int l = 0; l < nlevels; l++) cpu += levels[l].cpu;
  int                  nname = sc->nstage < RUNNER_MAX_STAGES ? sc->nstage : RUNNER_MAX_STAGES;
  for (int k = 0; k < nname; k++) names[k] = sc->stage[k].name;
  json_summary_head(fp, sc->name, sc->indenter ? "indentation" : "fe", completed(s, end));
  fputs(",\n  \"mesh\": {\"dir\": ", fp);
  json_str(fp, a->dir);
  fprintf(fp, ", \"cells\": %ld, \"unknowns\": %ld, \"order\": %d, \"error_indicator\": ", a->cells, a->unknowns, sc->order);
  json_num(fp, a->eta);
  fputs("},\n  \"mesh_error\": ", fp);
  if (me && me->have) fprintf(fp, "{\"how\": \"%s\", \"ratio\": %.4g}", me->how, me->ratio);
  else fputs("null", fp);
  stages_and_counters(fp, names, nname, s, me, end);
  fprintf(fp, ",\n  \"cost\": {\"cpu_s\": %.3f, \"cpu_s_answer\": %.3f, \"wall_s\": %.3f},\n  \"levels\": [\n", cpu, a->cpu, s->wall);
  for (int l = 0; l < nlevels; l++) level_entry(fp, &levels[l], l == nlevels - 1);
  fputs("  ]", fp);
  return json_file_close(fp, part, !end || end->final, err, errlen);
}

void run_summary_failed(const FeScene *sc, const char *dir, const RunInfo *levels, int nlevels, int level, int final, int rc, const char *err) {
  char   msg[4096], e2[1400];
  RunEnd end = {msg, level, final};
  if (!run_summary_due(rc, &levels[nlevels - 1].sum)) return;
  run_summary_error(rc, err, msg, sizeof msg);
  if (run_summary_write(sc, dir, levels, nlevels, NULL, &end, e2, sizeof e2)) printf("summary of the failed run: %s\n", e2);
}

int run_summary_point(const PointScene *sc, const PointSummary *ps, const RunnerSummary *s, double cpu, const RunEnd *end, char *err,
                      size_t errlen) {
  char        part[1200];
  const char *names[RUNNER_MAX_STAGES];
  FILE       *fp = json_file_open(sc->outdir, "summary.json", part, sizeof part, err, errlen);
  if (!fp) return 1;
  int         nname = sc->nseg < RUNNER_MAX_STAGES ? sc->nseg : RUNNER_MAX_STAGES;
  for (int k = 0; k < nname; k++) names[k] = sc->seg[k].stage.name;
  json_summary_head(fp, sc->name, "point", completed(s, end));
  stages_and_counters(fp, names, nname, s, NULL, end);
  fprintf(fp, ",\n  \"cost\": {\"cpu_s\": %.3f, \"wall_s\": %.3f},\n  \"point\": {\"final_stress\": [", cpu, s->wall);
  for (int i = 0; i < 6; i++) {
    if (i) fputs(", ", fp);
    json_num(fp, ps->final_stress[i]);
  }
  fprintf(fp, "], \"finite\": %s, \"worst_control_error\": ", ps->finite ? "true" : "false");
  json_num(fp, ps->worst_control_error);
  fputs(", \"worst_tangent_error\": ", fp);
  json_num(fp, sc->check_tangent ? ps->worst_tangent_error : NAN);
  fputc('}', fp);
  return json_file_close(fp, part, !end || end->final, err, errlen);
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
  else printf("mesh error: %s; the errors predicted to fall %.3g-fold from the level before\n", me->how, me->ratio);
}
