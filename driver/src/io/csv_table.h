/* Numeric tables from CSV files (lab records, load histories): a header line of column names, then
 * rows of numbers; lines starting with '#' are comments. */
#ifndef CSV_TABLE_H
#define CSV_TABLE_H

#include <stddef.h>

/* Read the columns named in 'names' (ncol of them): data[row * ncol + k], malloc'ed. 'where' prefixes
 * the messages (the scene file and line that named the table). Every field counts (an empty one is
 * an error in a column asked for, as is anything but a finite number); every row has the header's
 * number of fields. Needs two rows at least and, when
 * increasing >= 0, column 'increasing' strictly increasing. Returns 0, or 1 with err filled. */
int csv_read_columns(const char *path, const char *where, const char *const *names, int ncol, int increasing,
                     double **data, int *rows, char *err, size_t errlen);

#endif
