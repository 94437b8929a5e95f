/* The data's own protocol: its stages, from the data's stage column (each change of its value starts a stage)
 * or found from the load curve (loading, a hold at the peak load, unloading); and the forward scene made to
 * follow it (drive: data): the user's forward scene (mesh, material, indenter, step control) with the data's
 * stages, each driven by the data's load history as a table in the stage time (docs/calibrate.md). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/fsutil.h"
#include "../io/paths.h"
#include "calibrate_load.h"
#include "calibrate_protocol.h"

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

#define HOLD_BAND 0.01   /* a hold: the load within 1 % of the peak */
#define HOLD_CHANGE 0.05 /* a stage whose load changes by less than 5 % of the peak is a hold */
#define CYCLE_DROP 0.10  /* a loading whose load falls back by 10 % of the peak: more than one cycle */
#define NOISY 1.0e-4     /* a load noisier than this (relative to its peak: calibrate_load.c) ... */
#define SMOOTH_ROWS 10   /* ... is read through its running mean over 21 rows to find its stages */

static double T(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_time]; }
static double P(const CalRun *run, int i) { return run->data[i * run->ncol + run->col_load]; }

static int add_stage(CalRun *run, const char *name, int row0, int row1) {
  if (run->nstage == CAL_MAX_STAGES) return 1;
  CalStage *s = &run->stage[run->nstage++];
  snprintf(s->name, sizeof s->name, "%s", name);
  s->row0 = row0, s->row1 = row1;
  return 0;
}

/* The stage column's text in each data row (comment and blank lines skipped, as csv_read_columns does). */
static int from_column(const YdDoc *doc, CalRun *run, char *err, size_t errlen) {
  char  line[8192], prev[64] = "", where[PATH_MAX + 128];
  int   col = -1, row = 0, fileline = 0;
  FILE *fp  = fopen(run->data_file, "r");
  snprintf(where, sizeof where, "%s: key 'runs[%d].data.columns.stage'", doc->file, run->index);
  if (!fp) FAIL("%s: cannot open %s", where, run->data_file);
  while (fgets(line, sizeof line, fp)) {
    fileline++;
    if (line[0] == '#' || line[0] == '\n' || line[0] == '\r') continue;
    line[strcspn(line, "\r\n")] = '\0';
    char *f = line, *next;
    int   k = 0;
    for (; f; f = next, k++) { /* field k of the line */
      next = strchr(f, ',');
      if (next) *next++ = '\0';
      if (col < 0 ? !strcmp(f, run->stage_col) : k == col) break;
    }
    if (col < 0) {
      if (!f) return fclose(fp), snprintf(err, errlen, "%s: the data file %s has no column '%s'", where, run->data_file, run->stage_col), 1;
      col = k;
      continue;
    }
    if (!f || row >= run->rows) break;
    f += strspn(f, " \t\"");
    f[strcspn(f, "\"")] = '\0';
    while (*f && (f[strlen(f) - 1] == ' ' || f[strlen(f) - 1] == '\t')) f[strlen(f) - 1] = '\0';
    if (!*f) return fclose(fp), snprintf(err, errlen, "%s:%d: the stage column '%s' is empty", run->data_file, fileline, run->stage_col), 1;
    if (row == 0 || strcmp(f, prev)) {
      if (row > 0) run->stage[run->nstage - 1].row1 = row - 1;
      if (add_stage(run, f, row, row))
        return fclose(fp), snprintf(err, errlen, "%s: the data have more than %d stages (a new one at %s line %d)", where,
                                    CAL_MAX_STAGES, run->data_file, fileline), 1;
      snprintf(prev, sizeof prev, "%s", f);
    }
    run->row_stage[row++] = run->nstage - 1;
  }
  fclose(fp);
  if (row != run->rows) FAIL("%s: %d rows have a stage, %d rows were read", where, row, run->rows);
  run->stage[run->nstage - 1].row1 = row - 1;
  run->stages_from_column = 1;
  return 0;
}

/* Without a stage column: loading up to the hold, the hold (the rows about the peak whose load stays within 1 %
 * of it, when there are 3 or more), unloading after it. One cycle: a load that falls back within the loading, or
 * rises within the unloading, by 10 % of the peak is an error. */
static int from_curve(const YdDoc *doc, CalRun *run, char *err, size_t errlen) {
  int     n = run->rows, imax = 0, ha, hb;
  double  pmax = 0, *p = calloc((size_t)n, sizeof(double)), *raw = calloc((size_t)n, sizeof(double));
  for (int i = 0; i < n; i++) raw[i] = P(run, i), pmax = fmax(pmax, raw[i]);
  /* a noisy load (calibrate_load.c's measure) is read through its running mean over 2 SMOOTH_ROWS + 1 rows */
  int w = cal_noise(raw, n) > NOISY * pmax ? SMOOTH_ROWS : 0;
  for (int i = 0; i < n; i++) {
    double s = 0;
    int    k = 0;
    for (int j = i - w; j <= i + w; j++)
      if (j >= 0 && j < n) s += raw[j], k++;
    p[i] = s / k;
  }
  free(raw);
  for (int i = 1; i < n; i++)
    if (p[i] > p[imax]) imax = i;
  pmax = p[imax];
  for (ha = imax; ha > 0 && p[ha - 1] >= (1 - HOLD_BAND) * pmax;) ha--;
  for (hb = imax; hb < n - 1 && p[hb + 1] >= (1 - HOLD_BAND) * pmax;) hb++;
  int hold = hb - ha >= 2;
  if (!hold) ha = imax + 1, hb = imax;
  if (ha == 1) ha = 0; /* a first stage of one row spans no time */
  double top = -INFINITY, low = INFINITY;
  for (int i = 0; i < n; i++) {
    int rising = i < ha;
    if (rising ? p[i] < top - CYCLE_DROP * pmax : i > hb && p[i] > low + CYCLE_DROP * pmax) {
      free(p);
      FAIL("%s:%d: key 'runs[%d].data': the load %s from %g to %g at time %g within the %s: more than one loading cycle? "
           "Give the data's stages as a column (runs[%d].data.columns.stage)", doc->file, run->line, run->index, rising ? "falls" : "rises",
           rising ? top : low, p[i], T(run, i), rising ? "loading" : "unloading", run->index);
    }
    if (rising) top = fmax(top, p[i]);
    if (i > hb) low = fmin(low, p[i]);
  }
  free(p);
  if (ha > 0) add_stage(run, "loading", 0, ha - 1);
  if (hold) add_stage(run, "hold", ha, hb);
  if (hb < n - 1) add_stage(run, "unloading", hb + 1, n - 1);
  for (int j = 0; j < run->nstage; j++)
    for (int i = run->stage[j].row0; i <= run->stage[j].row1; i++) run->row_stage[i] = j;
  return 0;
}

/* Each stage's kind by its load's change over its rows (over the step into it, for a stage of one row); a stage
 * numbered in the data, or found from the curve, is named after its kind (loading, hold, hold_2, ...). */
static void name_stages(CalRun *run) {
  static const char *kinds[] = {"loading", "hold", "unloading"};
  double             pmax    = 0;
  int                count[3] = {0, 0, 0};
  for (int i = 0; i < run->rows; i++) pmax = fmax(pmax, P(run, i));
  for (int j = 0; j < run->nstage; j++) {
    CalStage *s  = &run->stage[j];
    double    dp = P(run, s->row1) - P(run, s->row1 > s->row0 || !j ? s->row0 : run->stage[j - 1].row1);
    s->kind      = fabs(dp) < HOLD_CHANGE * pmax ? CAL_HOLD : dp > 0 ? CAL_LOADING : CAL_UNLOADING;
    char *end;
    strtod(s->name, &end);
    if (run->stages_from_column && *end) continue; /* a named stage keeps its name */
    if (count[s->kind]++) snprintf(s->name, sizeof s->name, "%s_%d", kinds[s->kind], count[s->kind]);
    else snprintf(s->name, sizeof s->name, "%s", kinds[s->kind]);
  }
}

int cal_protocol_find(const YdDoc *doc, CalRun *run, char *err, size_t errlen) {
  run->row_stage = calloc((size_t)run->rows, sizeof(int));
  run->nstage    = 0;
  if (run->stage_col[0] ? from_column(doc, run, err, errlen) : from_curve(doc, run, err, errlen)) return 1;
  name_stages(run);
  for (int j = 0; run->drive && j < run->nstage; j++) {
    const CalStage *s = &run->stage[j];
    double          t0 = T(run, j ? run->stage[j - 1].row1 : 0);
    if (!(T(run, s->row1) > t0))
      FAIL("%s:%d: key 'runs[%d].data': the data's stage '%s' spans no time (row %d alone, at %g): drive: data makes each "
           "data stage a forward stage", doc->file, run->line, run->index, s->name, s->row0 + 1, t0);
  }
  if (run->drive) { /* the forward run starts at the data's first row: its time 0 */
    run->time_shift = -T(run, 0), run->time_shifted = 1;
    for (int i = run->rows - 1; i >= 0; i--) run->data[i * run->ncol + run->col_time] += run->time_shift;
  }
  return 0;
}

void cal_protocol_describe(const CalRun *run, char *buf, size_t n) {
  buf[0] = '\0';
  for (int j = 0; j < run->nstage; j++) {
    const CalStage *s   = &run->stage[j];
    int             a   = j ? run->stage[j - 1].row1 : 0;
    size_t          len = strlen(buf);
    snprintf(buf + len, n - len, "%s    %-10s %-9s t %9.4g to %9.4g s  %5d rows  load %9.4g to %9.4g", j ? "\n" : "", s->name,
             cal_kind_name(s->kind), T(run, a) - run->time_shift, T(run, s->row1) - run->time_shift, s->row1 - s->row0 + 1,
             P(run, a), P(run, s->row1));
  }
}

/* A YAML scalar, double-quoted. */
static void quoted(FILE *fp, const char *s) {
  fputc('"', fp);
  for (; *s; s++) {
    if (*s == '"' || *s == '\\') fputc('\\', fp);
    fputc(*s, fp);
  }
  fputc('"', fp);
}

/* A node in flow style; the input paths (keys geometry and file) absolute, against the scene file 'base'. */
static void emit(FILE *fp, const YdNode *nd, const char *key, const char *base) {
  char abs[PATH_MAX];
  if (nd->kind == YD_SCALAR) {
    int is_path = key && (!strcmp(key, "geometry") || !strcmp(key, "file"));
    quoted(fp, is_path && !path_resolve(base, nd->text, abs, sizeof abs) ? abs : nd->text);
    return;
  }
  fputc(nd->kind == YD_MAPPING ? '{' : '[', fp);
  for (size_t i = 0; i < nd->n; i++) {
    if (i) fputs(", ", fp);
    if (nd->kind == YD_MAPPING) fprintf(fp, "%s: ", nd->keys[i]);
    emit(fp, nd->items[i], nd->kind == YD_MAPPING ? nd->keys[i] : key, base);
  }
  fputc(nd->kind == YD_MAPPING ? '}' : ']', fp);
}

/* The kind of each stage of the forward scene by its indenter key (a load above the last: loading, ...). */
static void forward_kinds(const YdNode *stages, CalKind *kind) {
  double level = 0, depth = 0, x;
  for (size_t i = 0; i < stages->n && i < CAL_MAX_STAGES; i++) {
    YdNode *st = stages->items[i], *in = st->kind == YD_MAPPING ? yd_get(st, "indenter") : NULL;
    YdNode *ld = in && in->kind == YD_MAPPING ? yd_get(in, "load") : NULL, *dp = in && in->kind == YD_MAPPING ? yd_get(in, "depth") : NULL;
    kind[i] = CAL_HOLD;
    if (ld && ld->kind == YD_SCALAR && sscanf(ld->text, "%lf", &x) == 1)
      kind[i] = x > level ? CAL_LOADING : x < level ? CAL_UNLOADING : CAL_HOLD, level = x;
    else if (ld && ld->kind == YD_MAPPING) kind[i] = CAL_LOADING, level = INFINITY;
    else if (dp && dp->kind == YD_SCALAR && sscanf(dp->text, "%lf", &x) == 1)
      kind[i] = x > depth ? CAL_LOADING : CAL_UNLOADING, depth = x;
  }
}

/* One data stage's load history as a table in its stage time (the row before it is its start). */
static int write_table(const CalRun *run, int j, const char *file) {
  FILE *fp = fopen(file, "w");
  if (!fp) return 1;
  fprintf(fp, "# the %s over stage '%s' (%s, rows %d to %d), from the stage's start%s\ntime,load\n",
          run->load_fitted ? "fitted load history" : "data's load", run->stage[j].name, run->data_file, run->stage[j].row0 + 1,
          run->stage[j].row1 + 1, run->load_fitted ? ": linear between these knots (docs/calibrate.md, 'A noisy load')" : "");
  int    a = j ? run->stage[j - 1].row1 : 0;
  double ta = T(run, a), tb = T(run, run->stage[j].row1), tol = 1e-12 * fmax(fabs(tb), 1);
  if (run->load_fitted) { /* the fitted history: its knots over the stage (calibrate_load.c) */
    for (int q = 0; q < run->nknot; q++)
      if (run->knot_t[q] >= ta - tol && run->knot_t[q] <= tb + tol)
        fprintf(fp, "%.17g,%.17g\n", fmax(run->knot_t[q] - ta, 0), fmax(run->knot_p[q], 0));
    return fclose(fp);
  }
  for (int i = a; i <= run->stage[j].row1; i++) fprintf(fp, "%.17g,%.17g\n", T(run, i) - T(run, a), fmax(P(run, i), 0));
  return fclose(fp);
}

/* The scene src with the data's stages into out; the tables in dir. */
static int write_scene(const CalRun *run, const char *src, const char *out, const char *dir, char *err, size_t errlen) {
  YdDoc   d;
  char    base[PATH_MAX], msg[1024], table[PATH_MAX + 96];
  CalKind fk[CAL_MAX_STAGES];
  if (!realpath(src, base) || yd_load(base, &d, msg, sizeof msg))
    FAIL("%s: key 'runs[%d].drive': cannot read the forward scene %s", run->file, run->index, src);
  YdNode *stages = yd_get(d.root, "stages");
  if (!stages || stages->kind != YD_SEQUENCE || stages->n < 1)
    return yd_free(&d), snprintf(err, errlen, "%s: key 'runs[%d].drive': the forward scene %s has no stages", run->file, run->index, src), 1;
  for (size_t i = 0; i < stages->n; i++) {
    static const char *loads[] = {"pressure", "traction", "load"};
    for (int k = 0; k < 3; k++)
      if (stages->items[i]->kind == YD_MAPPING && yd_get(stages->items[i], loads[k]))
        return yd_free(&d), snprintf(err, errlen, "%s: key 'runs[%d].drive': data: stage %zu of the forward scene %s has "
                                     "boundary loads ('%s'): a forward run driven by the data keeps only the indenter's "
                                     "load: give drive: scene", run->file, run->index, i, src, loads[k]), 1;
  }
  forward_kinds(stages, fk);
  FILE *fp = fopen(out, "w");
  if (!fp) return yd_free(&d), snprintf(err, errlen, "calibrate: cannot write %s", out), 1;
  fprintf(fp, "# Written by calibrate (drive: data): the scene %s with the stages of the data %s, each stage's\n"
              "# indenter load the data's history (a table, in the stage time), its step control from the scene's stage of\n"
              "# the same kind. Time 0 is the data's first row (time %.10g there).\n", base, run->data_file, -run->time_shift);
  for (size_t i = 0; i < d.root->n; i++)
    if (strcmp(d.root->keys[i], "stages")) {
      fprintf(fp, "%s: ", d.root->keys[i]);
      emit(fp, d.root->items[i], d.root->keys[i], base);
      fputc('\n', fp);
    }
  fprintf(fp, "stages:\n");
  for (int j = 0; j < run->nstage; j++) {
    int f = -1;
    for (size_t i = 0; i < stages->n && i < CAL_MAX_STAGES && f < 0; i++)
      if (fk[i] == run->stage[j].kind) f = (int)i;
    if (f < 0) f = j < (int)stages->n ? j : (int)stages->n - 1;
    YdNode *steps = stages->items[f]->kind == YD_MAPPING ? yd_get(stages->items[f], "steps") : NULL;
    int     a     = j ? run->stage[j - 1].row1 : 0;
    snprintf(table, sizeof table, "%s/%02d_%s.csv", dir, j, run->stage[j].name);
    if (write_table(run, j, table)) return fclose(fp), yd_free(&d), snprintf(err, errlen, "calibrate: cannot write %s", table), 1;
    fprintf(fp, "  - {name: ");
    quoted(fp, run->stage[j].name);
    fprintf(fp, ", duration: %.17g, indenter: {load: {table: {file: ", T(run, run->stage[j].row1) - T(run, a));
    quoted(fp, table);
    fprintf(fp, ", time: time, value: load}}}");
    if (steps) fprintf(fp, ", steps: "), emit(fp, steps, "steps", base);
    fprintf(fp, "}\n");
  }
  yd_free(&d);
  return fclose(fp) ? (snprintf(err, errlen, "calibrate: cannot write %s", out), 1) : 0;
}

int cal_protocol_write(CalRun *run, const char *dir, char *err, size_t errlen) {
  char sub[PATH_MAX + 96], abs[PATH_MAX];
  snprintf(sub, sizeof sub, "%s/protocol/%s", dir, run->name);
  if (fs_make_directories(sub) || !realpath(sub, abs)) FAIL("calibrate: cannot create %s", sub);
  if (snprintf(run->driven, sizeof run->driven, "%s/scene.yaml", abs) >= (int)sizeof run->driven - 5)
    FAIL("calibrate: the output path %s is too long", abs);
  if (write_scene(run, run->scene, run->driven, abs, err, errlen)) return 1;
  if (!run->reference[0]) return 0;
  if (snprintf(run->driven_reference, sizeof run->driven_reference, "%s/reference.yaml", abs) >= (int)sizeof run->driven_reference - 5)
    FAIL("calibrate: the output path %s is too long", abs);
  return write_scene(run, run->reference, run->driven_reference, abs, err, errlen);
}
