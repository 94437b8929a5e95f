/* The residual vector of one forward run's history.csv against the data, and the data rows' blocks. */
#ifndef CALIBRATE_RESIDUAL_H
#define CALIBRATE_RESIDUAL_H

#include <stdio.h>

#include "calibrate_run.h"

/* Assign the data rows to the residual blocks by the stage times of a first forward run (dir/history.csv),
 * check that they lie within the run's range; fixes the residual count. 0, or 1 with err filled. */
int cal_run_setup(CalRun *run, const char *dir, char *err, size_t errlen);
/* Residual count of a set-up run. */
int cal_run_size(const CalRun *run);
/* Residuals of the forward run in dir into r (cal_run_size of them). 0, or 1 with err filled (a data point
 * outside the run's range: the evaluation is rejected). */
int cal_run_residual(CalRun *run, const char *dir, double *r, char *err, size_t errlen);
/* Write data and model curves of the last evaluation: path (CSV: run,block,x,data,model). */
int cal_run_write_curves(const CalRun *run, FILE *fp);
/* A forward run's history columns (time, stage, x, y of curve c) into h (4 a row). */
int cal_read_history(const CalRun *run, const char *dir, const char *const names[4], double **h, int *rows, char *err,
                     size_t errlen);
/* Time span of a stage in a history read by cal_read_history: rows i0 (the last row before it) to i1. 1 if empty. */
int cal_stage_span(const double *h, int rows, int stage, int *i0, int *i1);

#endif
