/* The forward runs of a calibrate scene and their measured data: which forward scene, which CSV (columns,
 * factors to the forward scene's units), which residuals (loading, hold, unloading, series), and the
 * residual vector of one forward run's history.csv against the data (docs/calibrate.md). */
#ifndef CALIBRATE_DATA_H
#define CALIBRATE_DATA_H

#include <limits.h>
#include <stddef.h>
#include <stdio.h>

#include "../io/yaml_doc.h"

#define CAL_MAX_PARAMS 8
#define CAL_MAX_RUNS 8
#define CAL_MAX_CURVES 6

typedef enum { CAL_LOADING, CAL_HOLD, CAL_UNLOADING, CAL_SERIES } CalKind;

/* One residual block: model y at the data's x, within one stage of the forward run. */
typedef struct {
  CalKind kind;
  char    stage_name[64];
  int     stage;          /* 0-based index in the forward scene's stages (segments) */
  char    xcol[64], ycol[64]; /* model columns of history.csv */
  int     relative;       /* model and data y each less their mean over the block (hold: the creep depth) */
  double  weight, scale;  /* residual = weight * (model - data) / scale; scale: the data's range of y */
  int     n;              /* data rows in the block (fixed at the first evaluation) */
  double *x, *y, *t;      /* data, in the forward scene's units */
  double *model;          /* model y at the data x, of the last evaluation */
  int     line;           /* scene line, for messages */
} CalCurve;

typedef struct {
  char     name[64];
  char     scene[PATH_MAX];   /* forward scene, resolved */
  char     set[512];          /* held PROPS for this run: NAME=VALUE,... */
  char     options[512];      /* extra command-line options of the forward run */
  char     reference[PATH_MAX]; /* the full model, run once at the fit to measure the forward model's error */
  int      point;             /* a point scene: 'segment' is the stage column */
  double  *data;              /* CSV columns: time, load, depth, value (those named); ncol of them */
  int      rows, ncol, col_time, col_load, col_depth, col_value;
  char     data_file[PATH_MAX];
  char     time_from[64];     /* data.time_from: the data's time counts from this stage's start ("": absolute) */
  int      time_stage;        /* its index, or -1 */
  double   time_shift;        /* the stage's start in the forward run, added to the data's times at setup */
  int      time_shifted;
  CalCurve curve[CAL_MAX_CURVES];
  int      ncurve;
} CalRun;

/* Read runs[k] from a 'runs:' item of the calibrate scene. 0, or 1 with err filled. */
int cal_run_read(const YdDoc *doc, YdNode *item, int k, CalRun *run, char *err, size_t errlen);
void cal_run_free(CalRun *run);

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
const char *cal_kind_name(CalKind k);

#endif
