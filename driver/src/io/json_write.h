/* Writing the small JSON files of a run (summary.json of every scene kind: docs/driver.md, "summary.json"):
 * numbers, strings, the members every summary begins with, and a file written as NAME.part and renamed once
 * complete, so that a reader never sees half of one. */
#ifndef JSON_WRITE_H
#define JSON_WRITE_H

#include <stddef.h>
#include <stdio.h>

/* A number (%.10g; no NaN or Inf in JSON: null). */
void json_num(FILE *fp, double v);

/* A string: quotes, backslashes and control characters escaped. */
void json_str(FILE *fp, const char *v);

/* "{\n  \"scene\": ..., \"kind\": ..., \"completed\": ..." : what every summary.json begins with; each kind goes on
   with ",\n  \"key\": value" and ends with json_file_close. */
void json_summary_head(FILE *fp, const char *scene, const char *kind, int completed);

/* dir/name, written as dir/name.part (its path into part, n bytes): the open file, or NULL with err filled. */
FILE *json_file_open(const char *dir, const char *name, char *part, size_t n, char *err, size_t errlen);

/* Close the object ("\n}\n") and the file; with final 1 rename part to its final name, with final 0 the file keeps
   its .part name (a run that has no results of its own yet leaves an earlier run's file in place: docs/driver.md,
   "summary.json"). 0, or 1 with err filled. */
int json_file_close(FILE *fp, const char *part, int final, char *err, size_t errlen);

#endif
