#include "csv_table.h"

#include <errno.h>
#include <math.h>
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

/* Split a line at commas in place: every field counts, an empty one too ("15,,25" has three). */
static int split_fields(char *line, char **fields, int max) {
  int n = 0;
  line[strcspn(line, "\r\n")] = '\0';
  for (char *p = line;; p++) {
    char *comma = strchr(p, ',');
    if (n < max) fields[n] = p;
    n++;
    if (!comma) break;
    *comma = '\0';
    p      = comma;
  }
  return n;
}

/* A field as a finite number (surrounding blanks allowed). */
static int parse_number(const char *field, double *v) {
  char *end;
  errno = 0;
  *v    = strtod(field, &end);
  if (end == field) return 1;
  while (*end == ' ' || *end == '\t') end++;
  return *end != '\0' || errno == ERANGE || !isfinite(*v);
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
  ncols = split_fields(buf, cols, 64);
  if (ncols > 64) FAIL("%s: table file '%s': more than 64 columns", where, path);
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
    char *fields[64];
    int   nv = split_fields(buf, fields, 64);
    if (*rows == cap) *data = realloc(*data, sizeof(double) * (size_t)((cap *= 2) * ncol));
    if (nv != ncols) FAIL("%s:%d: the row has %d fields, the header %d", path, fileline, nv, ncols);
    for (int c = 0; c < ncol; c++) {
      const char *f = fields[idx[c]];
      if (!f[strspn(f, " \t")]) FAIL("%s:%d: column '%s' (field %d) is empty", path, fileline, names[c], idx[c] + 1);
      if (parse_number(f, &(*data)[*rows * ncol + c]))
        FAIL("%s:%d: column '%s' (field %d): expected a finite number, got '%s'", path, fileline, names[c], idx[c] + 1, f);
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
