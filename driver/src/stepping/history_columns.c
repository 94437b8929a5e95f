/* history.csv's columns and its file (history_columns.h). */
#include "history_columns.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *const hist_tensor_suffix[6] = {"11", "22", "33", "12", "13", "23"};

static HistValue v_time(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = row->t}; }
static HistValue v_stage(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = row->stage}; }
static HistValue v_name(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.s = row->stage_name}; }
static HistValue v_step(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = row->step}; }
static HistValue v_dt(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = row->dt}; }
static HistValue v_its(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = row->its}; }
static HistValue v_cutbacks(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.i = row->cutbacks}; }

/* The columns every kind begins with; their values from the runner's row. */
static const HistColumn lead[] = {
  {"time", "%.17g", 1, NULL, v_time, NULL, NULL},     {"stage", "%d", 1, NULL, v_stage, NULL, NULL},
  {"stage_name", "%s", 1, NULL, v_name, NULL, NULL},  {"step", "%d", 1, NULL, v_step, NULL, NULL},
  {"dt", "%.17g", 1, NULL, v_dt, NULL, NULL},         {"newton_its", "%d", 1, NULL, v_its, NULL, NULL},
  {"cutbacks", "%d", 1, NULL, v_cutbacks, NULL, NULL},
};
#define NLEAD ((int)(sizeof lead / sizeof lead[0]))

static int count_of(const HistColumn *c, const void *ctx) { return c->count ? c->count(ctx) : c->n > 1 ? c->n : 1; }

/* One value by its conversion's type (the last letter of fmt, "ld" for a long). */
static int print_value(FILE *fp, const char *fmt, HistValue v) {
  size_t n = strlen(fmt);
  char   last = n ? fmt[n - 1] : 'g';
  if (last == 's') return fprintf(fp, fmt, v.s ? v.s : "");
  if (last == 'd' && n > 1 && fmt[n - 2] == 'l') return fprintf(fp, fmt, v.i);
  if (last == 'd') return fprintf(fp, fmt, (int)v.i);
  return fprintf(fp, fmt, v.r);
}

static int header_part(FILE *fp, const HistColumn *cols, int ncols, const void *ctx, int first) {
  for (int c = 0; c < ncols; c++) {
    const HistColumn *h = &cols[c];
    for (int k = 0, n = count_of(h, ctx); k < n; k++, first = 0) {
      char name[256];
      if (h->label) h->label(ctx, k, name, sizeof name);
      else if (h->suffix) snprintf(name, sizeof name, "%s_%s", h->name, h->suffix[k]);
      else snprintf(name, sizeof name, "%s", h->name);
      if (fprintf(fp, "%s%s", first ? "" : ",", name) < 0) return 1;
    }
  }
  return 0;
}

static int row_part(FILE *fp, const HistColumn *cols, int ncols, const void *ctx, const RunnerRow *row, int first) {
  for (int c = 0; c < ncols; c++) {
    const HistColumn *h = &cols[c];
    for (int k = 0, n = count_of(h, ctx); k < n; k++, first = 0)
      if ((!first && fputc(',', fp) == EOF) || print_value(fp, h->fmt, h->value(ctx, row, k)) < 0) return 1;
  }
  return 0;
}

int history_header_write(FILE *fp, const HistColumn *cols, int ncols, const void *ctx) {
  if (header_part(fp, lead, NLEAD, NULL, 1) || header_part(fp, cols, ncols, ctx, 0)) return 1;
  return fputc('\n', fp) == EOF;
}

int history_row_write(FILE *fp, const HistColumn *cols, int ncols, const void *ctx, const RunnerRow *row) {
  if (row_part(fp, lead, NLEAD, NULL, row, 1) || row_part(fp, cols, ncols, ctx, row, 0)) return 1;
  return fputc('\n', fp) == EOF;
}

/* Where the header of the history at path differs from the one this driver writes: 0 (the same), or 1 with the first
   differing column (1-based) and both names in err, or -1 (no header read: left to the truncation to report). */
static int header_differs(const char *path, const HistColumn *cols, int ncols, const void *ctx, char *err, size_t errlen) {
  char  *mine = NULL, *theirs = NULL;
  size_t nm = 0, nt = 0;
  FILE  *fp = fopen(path, "r"), *mem = open_memstream(&mine, &nm);
  int    rc = -1;
  if (fp && mem && getline(&theirs, &nt, fp) > 0 && !history_header_write(mem, cols, ncols, ctx) && !fflush(mem)) {
    const char *a = theirs, *b = mine;
    int         col = 1;
    for (; *a && *a == *b; a++, b++) col += *a == ',';
    rc = *a != *b;
    if (rc) {
      while (a > theirs && a[-1] != ',') a--, b--; /* the differing column's start: the same in both */
      snprintf(err, errlen, "column %d is '%.*s', this driver writes '%.*s'", col, (int)strcspn(a, ",\r\n"), a, (int)strcspn(b, ",\n"), b);
    }
  }
  if (fp) fclose(fp);
  if (mem) fclose(mem);
  free(mine), free(theirs);
  return rc;
}

int history_file_check(const char *dir, const HistColumn *cols, int ncols, const void *ctx, char *err, size_t errlen) {
  char path[1024], which[300];
  snprintf(path, sizeof path, "%s/history.csv", dir);
  if (header_differs(path, cols, ncols, ctx, which, sizeof which) != 1) return 0;
  snprintf(err, errlen, "-restart: %s has the columns of an older history layout (%s): it and its checkpoint were written by an "
           "older driver and cannot be continued: run the scene again from its start, without -restart; nothing was written", path, which);
  return 2;
}

int history_file_open(HistoryFile *h, const char *dir, int restart, long offset, const HistColumn *cols, int ncols, const void *ctx,
                      char *err, size_t errlen) {
  snprintf(h->path, sizeof h->path, "%s/history.csv%s", dir, restart ? "" : ".part");
  if (restart) {
    if (truncate(h->path, offset) || !(h->fp = fopen(h->path, "a"))) {
      snprintf(err, errlen, "%s: cannot continue the history at the checkpoint: %s", h->path, strerror(errno));
      return 1;
    }
    return 0;
  }
  if (!(h->fp = fopen(h->path, "w")) || history_header_write(h->fp, cols, ncols, ctx)) {
    snprintf(err, errlen, "%s: cannot write: %s", h->path, strerror(errno));
    return 1;
  }
  return 0;
}

int history_file_promote(HistoryFile *h, const char *dir) {
  char final[1024];
  if (!h->fp) return 0;
  fflush(h->fp);
  snprintf(final, sizeof final, "%s/history.csv", dir);
  if (rename(h->path, final)) return 1;
  snprintf(h->path, sizeof h->path, "%s", final);
  return 0;
}

int history_file_row(HistoryFile *h, const HistColumn *cols, int ncols, const void *ctx, const RunnerRow *row, char *err,
                     size_t errlen) {
  if (history_row_write(h->fp, cols, ncols, ctx, row) || fflush(h->fp)) {
    snprintf(err, errlen, "%s: cannot write: %s", h->path, strerror(errno));
    return 1;
  }
  return 0;
}
