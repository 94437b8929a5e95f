/* history.csv from one column declaration (issue 35): every scene kind writes the same leading columns (time,
 * stage, stage_name, step, dt, newton_its, cutbacks; a point scene's segment is its stage), then its own, each
 * declared once by its name and the way its value is obtained and printed, so that header and rows cannot drift
 * apart. docs/driver.md, "history.csv", lists the columns. */
#ifndef HISTORY_COLUMNS_H
#define HISTORY_COLUMNS_H

#include <stdio.h>

/* A row of the history, as the stage runner knows it: the shared leading columns and the wall time. */
typedef struct {
  double      t, dt, wall;
  int         stage, step, its, cutbacks;
  const char *stage_name;
} RunnerRow;

/* One value: r for the conversions of a double (%g, %f), i for %d and %ld, s for %s. */
typedef struct {
  double      r;
  long        i;
  const char *s;
} HistValue;

/* A column, or a group of columns of one conversion: n of them named name_suffix[k] (n 0 or 1 and suffix NULL:
 * one column named name), or, with count set, count(ctx) of them named by label(ctx, k). value gives the k-th
 * value of the row (ctx: the solver's). */
typedef struct {
  const char        *name;
  const char        *fmt; /* the printf conversion of a value: "%.17g", "%.4f", "%d", "%ld", "%s" */
  int                n;
  const char *const *suffix;
  HistValue (*value)(const void *ctx, const RunnerRow *row, int k);
  int (*count)(const void *ctx);
  void (*label)(const void *ctx, int k, char *buf, size_t len);
} HistColumn;

/* The suffixes of a symmetric tensor's six components, in the UMAT's order. */
extern const char *const hist_tensor_suffix[6];

/* The header line: the shared columns, then the kind's (cols, ncols). 0, or nonzero on a write error. */
int history_header_write(FILE *fp, const HistColumn *cols, int ncols, const void *ctx);

/* A row in the same order. */
int history_row_write(FILE *fp, const HistColumn *cols, int ncols, const void *ctx, const RunnerRow *row);

/* The history file of a run (rank 0): a fresh run writes history.csv.part, renamed once the first step is done
 * (history_file_promote), so a run that fails early leaves an earlier run's history in place; a restart continues
 * history.csv at the offset its checkpoint recorded. fp NULL: no history (another rank, no output directory). */
typedef struct {
  FILE *fp;
  char  path[1024];
} HistoryFile;

/* Before a restart reads its checkpoint (rank 0): whether dir/history.csv has the header this driver writes. 0 (the
   same, or no header to read: its continuation reports that), or 2 with err naming the first column that differs (an
   older driver's layout, which this run cannot continue). */
int history_file_check(const char *dir, const HistColumn *cols, int ncols, const void *ctx, char *err, size_t errlen);

/* Open the history in dir (fresh: with its header). 0, or nonzero with err set. */
int history_file_open(HistoryFile *h, const char *dir, int restart, long offset, const HistColumn *cols, int ncols, const void *ctx,
                      char *err, size_t errlen);
/* history.csv.part -> history.csv in dir. 0, or nonzero on a failed rename. */
int history_file_promote(HistoryFile *h, const char *dir);
/* One row, flushed. 0, or nonzero with err set. */
int history_file_row(HistoryFile *h, const HistColumn *cols, int ncols, const void *ctx, const RunnerRow *row, char *err,
                     size_t errlen);

#endif
