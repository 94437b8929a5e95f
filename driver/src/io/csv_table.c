#include "csv_table.h"

#include <errno.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    if (fp) fclose(fp);                 \
    free(*data);                        \
    *data = NULL;                       \
    return 1;                           \
  } while (0)

void csv_resolve_path(const char *scene_file, const char *path, char *out, size_t n) {
  char dir[1024];
  if (path[0] == '/') {
    snprintf(out, n, "%s", path);
    return;
  }
  snprintf(dir, sizeof dir, "%s", scene_file);
  snprintf(out, n, "%s/%s", dirname(dir), path);
}

int csv_read_columns(const char *path, const char *where, const char *const *names, int ncol, int increasing,
                     double **data, int *rows, char *err, size_t errlen) {
  char  buf[8192], *cols[64];
  int   idx[64], ncols = 0, fileline = 0, cap = 64;
  FILE *fp = NULL;
  *data    = NULL;
  *rows    = 0;
  if (ncol > 64) FAIL("%s: too many columns asked of table '%s'", where, path);
  if (!(fp = fopen(path, "r"))) FAIL("%s: table file '%s': cannot open: %s", where, path, strerror(errno));
  do { /* the header is the first line that is not a comment */
    fileline++;
    if (!fgets(buf, sizeof buf, fp)) FAIL("%s: table file '%s' has no header line", where, path);
  } while (buf[0] == '#');
  for (char *tok = strtok(buf, ",\r\n"); tok && ncols < 64; tok = strtok(NULL, ",\r\n")) cols[ncols++] = tok;
  for (int c = 0; c < ncol; c++) {
    idx[c] = -1;
    for (int k = 0; k < ncols; k++)
      if (!strcmp(cols[k], names[c])) idx[c] = k;
    if (idx[c] < 0) FAIL("%s: table file '%s' has no column '%s'", where, path, names[c]);
  }
  *data = malloc(sizeof(double) * (size_t)(cap * ncol));
  while (fgets(buf, sizeof buf, fp)) {
    fileline++;
    if (buf[0] == '\n' || buf[0] == '\r' || buf[0] == '#') continue;
    double vals[64];
    int    nv = 0;
    for (char *tok = strtok(buf, ",\r\n"); tok && nv < 64; tok = strtok(NULL, ",\r\n")) {
      char *end;
      vals[nv] = strtod(tok, &end);
      if (end == tok) FAIL("%s:%d: not a number: '%s'", path, fileline, tok);
      nv++;
    }
    if (*rows == cap) *data = realloc(*data, sizeof(double) * (size_t)((cap *= 2) * ncol));
    for (int c = 0; c < ncol; c++) {
      if (idx[c] >= nv) FAIL("%s:%d: the row has %d values, column '%s' is number %d", path, fileline, nv, names[c], idx[c] + 1);
      (*data)[*rows * ncol + c] = vals[idx[c]];
    }
    if (increasing >= 0 && *rows > 0 && !((*data)[*rows * ncol + increasing] > (*data)[(*rows - 1) * ncol + increasing]))
      FAIL("%s:%d: column '%s' must increase", path, fileline, names[increasing]);
    (*rows)++;
  }
  fclose(fp);
  fp = NULL;
  if (*rows < 2) FAIL("%s: table file '%s' needs at least two rows", where, path);
  return 0;
}
