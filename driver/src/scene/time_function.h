/* A stage's time function, one for every scene kind that has one: an FE stage's pressure of a group and an
 * indentation stage's indenter load or depth (fe/fe_scene.c, contact/indent_scene.c) are each one of
 *   a number    reached linearly at the stage's end from the value at its start (a ramp);
 *   hold        the value at the stage's start (the indenter's 'load: hold'; an FE pressure not given);
 *   {exp: {P0, k}}                                  P0 exp(k t) in the stage time t (Yin et al. 2021 eqs. 25, 26);
 *   {table: {file, time, value, time_factor, factor}} a CSV history in the stage time, linear between its rows,
 *               its end values beyond them.
 * Read (time_fn_read), evaluated (time_fn_value), inverted for an end event (time_fn_time_of) and shared among a
 * model's mirror copies (time_fn_share) here. */
#ifndef SCENE_TIME_FUNCTION_H
#define SCENE_TIME_FUNCTION_H

#include "../io/yaml_doc.h"

typedef enum { TF_RAMP, TF_HOLD, TF_EXP, TF_TABLE } TimeFnKind;

typedef struct {
  TimeFnKind kind;
  double     target;  /* ramp: the value at the stage's end */
  double     P0, k;   /* exp */
  double    *t, *v;   /* table: stage times (s) and values, n rows (malloc'ed) */
  int        n;
} TimeFn;

/* The forms a key allows (time_fn_read). */
enum { TF_ALLOW_NUMBER = 1, TF_ALLOW_HOLD = 2, TF_ALLOW_EXP = 4, TF_ALLOW_TABLE = 8 };

/* The function at node nd (key path 'path') in one of the forms allowed; expected: the forms as the message about
 * any other value names them ("a number, {exp: {P0, k}} or {table: {...}}"). The table's file is relative to the
 * scene's. 0, or 1 with err naming file, line, key and value. */
int time_fn_read(const YdDoc *doc, YdNode *nd, const char *path, unsigned allowed, const char *expected, TimeFn *f, char *err,
                 size_t errlen);
/* A {file, time, value, time_factor, factor} table at node x (key path 'path'): times in the stage's time (s, after
 * time_factor) and values (after factor), malloc'ed, n rows; 0, or 1 with err filled. */
int time_fn_table_read(const YdDoc *doc, YdNode *x, const char *path, double **t, double **v, int *n, char *err, size_t errlen);

/* The value at stage time ts; start: the value at the stage's start; lambda: the fraction of the stage done. */
double time_fn_value(const TimeFn *f, double start, double lambda, double ts);
/* A table's value at stage time ts: linear between its rows, its end values outside them. */
double time_fn_table_value(const double *t, const double *v, int n, double ts);
/* The stage time at which f first reaches P (exp; ramp from start; table: its first crossing, its start if it starts
 * above P), or -1 if never within the duration (hold never). */
double time_fn_time_of(const TimeFn *f, double start, double duration, double P);
/* One of copies mirror images of a model carries 1/copies of the whole load: the function's values (a ramp's target,
 * exp's P0, a table's values) divided by copies. */
void time_fn_share(TimeFn *f, double copies);

#endif
