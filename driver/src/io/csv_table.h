/* Numeric tables from CSV files (lab records, load histories): a header line of column names, then
 * rows of numbers; lines starting with '#' are comments. */
#ifndef CSV_TABLE_H
#define CSV_TABLE_H

#include <stddef.h>

/* Read the columns named in 'names' (ncol of them): data[row * ncol + k], malloc'ed. 'where' prefixes
 * the messages (the scene file and line that named the table). Needs two rows at least and, when
 * increasing >= 0, column 'increasing' strictly increasing. Returns 0, or 1 with err filled. */
int csv_read_columns(const char *path, const char *where, const char *const *names, int ncol, int increasing,
                     double **data, int *rows, char *err, size_t errlen);

/* 'path' as given if absolute, else relative to the directory of 'scene_file'. */
void csv_resolve_path(const char *scene_file, const char *path, char *out, size_t n);

#endif
