/* The forward runs of a calibrate scene and their measured data: which forward scene, which CSV (columns,
 * factors to the forward scene's units), whose protocol the forward runs follow (the data's own history, or
 * the forward scene's stages), which residuals (loading, hold, unloading, series), and the residual vector
 * of one forward run's history.csv against the data (docs/calibrate.md). */
#ifndef CALIBRATE_DATA_H
#define CALIBRATE_DATA_H

#include <limits.h>
#include <stddef.h>
#include <stdio.h>

#include "../io/yaml_doc.h"

#define CAL_MAX_PARAMS 8
#define CAL_MAX_RUNS 8
#define CAL_MAX_CURVES 6
#define CAL_MAX_STAGES 16 /* the data's stages (the FE scene's MAXSTAGES) */

typedef enum { CAL_LOADING, CAL_HOLD, CAL_UNLOADING, CAL_SERIES } CalKind;

/* One residual block: model y at the data's x, within one stage of the forward run. */
typedef struct {
  CalKind kind;
  char    stage_name[64];
  int     stage;          /* 0-based index in the forward scene's stages (segments) */
  char    xcol[64], ycol[64]; /* history.csv columns: the data's x (curves.csv) and the model's y */
  char    mcol[64];       /* the history column the model is interpolated in: xcol, or time (drive: data) */
  int     relative;       /* model and data y each less their mean over the block (hold: the creep depth) */
  double  weight, scale;  /* residual = weight * (model - data) / scale; scale: the data's range of y (or its noise) */
  double  range;          /* the data's range of y */
  int     n;              /* data rows in the block (fixed at the first evaluation) */
  double *x, *y, *t;      /* data, in the forward scene's units */
  double *model;          /* model y at the data x, of the last evaluation */
  int     line, index;    /* scene line and index in runs[k].residuals, for messages */
} CalCurve;

/* A stage of the data's own protocol: its rows, from the data's stage column or found from the load curve. */
typedef struct {
  char    name[64];
  CalKind kind;           /* loading, hold or unloading: by the load's change over the stage */
  int     row0, row1;     /* its data rows, inclusive */
} CalStage;

typedef struct {
  char     name[64];
  char     file[PATH_MAX];    /* the calibrate scene, and this run's index and line in it: for messages */
  int      index, line;
  char     scene[PATH_MAX];   /* forward scene, resolved */
  char     set[512];          /* held PROPS for this run: NAME=VALUE,... */
  char     options[512];      /* extra command-line options of the forward run */
  char     reference[PATH_MAX]; /* the full model, run at the fit to measure the forward model's bias ("": none) */
  int      reference_default; /* 1: the reference was found beside the forward scene (X_fast, X_mid -> X_reference) */
  int      point;             /* a point scene: 'segment' is the stage column */
  int      drive;             /* 1: the forward runs follow the data's history (drive: data) */
  char     driven[PATH_MAX], driven_reference[PATH_MAX]; /* drive: data: the scenes written for it */
  double  *data;              /* CSV columns: time, load, depth, value (those named); ncol of them */
  int      rows, ncol, col_time, col_load, col_depth, col_value;
  char     col_name[4][64];   /* the data file's column names of time, load, depth, value */
  double   factor[4];         /* their factors */
  char     stage_col[64];     /* data.columns.stage ("": none) */
  char     data_file[PATH_MAX];
  char     time_from[64];     /* data.time_from: the data's time counts from this stage's start ("": absolute) */
  int      time_stage;        /* its index, or -1 */
  double   time_shift;        /* added to the data's times (time_from: the stage's start; drive: data: -t first) */
  int      time_shifted;
  CalStage stage[CAL_MAX_STAGES]; /* the data's own stages (indentation data), nstage of them */
  int      nstage, stages_from_column;
  int     *row_stage;         /* the data stage of each row, or NULL */
  CalCurve curve[CAL_MAX_CURVES];
  int      ncurve;
  /* units (calibrate_units.c): each column's unit declared (data.units, data.factors, or units: scene) */
  char     unit[4][16];       /* data.units.ROLE as given ("": none) */
  int      declared[4];       /* 1: by a unit, 2: by a factor, 3: units: scene */
  char     scene_unit[3][16]; /* the forward scene's units of time, force (load) and length (depth) */
  int      data_line;         /* the 'data' key's line */
  /* thermal drift of the depth (calibrate_drift.c) */
  int      drift;             /* CAL_DRIFT_NONE, _MEASURED (in a data stage, removed), _FIT (a nuisance parameter) */
  int      drift_stage, drift_line, drift_rows; /* _MEASURED: the data stage and its rows used */
  double   drift_rate, drift_se;  /* depth per s, the forward scene's units: measured, or fitted at the last evaluation */
  double   drift_t0;          /* the drift counts from the data's first row */
  /* the load history the forward runs follow, drive: data (calibrate_load.c) */
  int      load_history;      /* CAL_LOAD_AUTO, _DATA, _FITTED as asked; */
  int      load_fitted;       /* 1: the forward runs follow the fitted history */
  double   load_noise, load_rms, load_peak; /* the load's noise (second differences), the data's rms about the fit */
  int      load_pieces[CAL_MAX_STAGES];     /* linear pieces of the fit in each data stage */
  int      nknot;
  double  *knot_t, *knot_p;   /* the fitted history: continuous, linear between its knots (data times) */
  /* weighting: noise (calibrate_residual.c): each block's residuals divided by its column's noise, not its range */
  int      weighting;         /* CAL_WEIGHT_RANGE, CAL_WEIGHT_NOISE */
  double   noise[4];          /* weighting: noise: the noise of the depth and value columns (NAN: too small, range kept) */
} CalRun;

enum { CAL_WEIGHT_RANGE, CAL_WEIGHT_NOISE };

enum { CAL_DRIFT_NONE, CAL_DRIFT_MEASURED, CAL_DRIFT_FIT };
enum { CAL_LOAD_AUTO, CAL_LOAD_DATA, CAL_LOAD_FITTED };

/* Read runs[k] from a 'runs:' item of the calibrate scene. 0, or 1 with err filled. */
int cal_run_read(const YdDoc *doc, YdNode *item, int k, CalRun *run, char *err, size_t errlen);
void cal_run_free(CalRun *run);
/* The scene a forward run (reference 0) or the full-model run (1) is started with. */
const char *cal_run_scene(const CalRun *run, int reference);

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
/* A forward run's history columns (time, stage, x, y of curve c) into h (4 a row). */
int cal_read_history(const CalRun *run, const char *dir, const char *const names[4], double **h, int *rows, char *err,
                     size_t errlen);
/* Time span of a stage in a history read by cal_read_history: rows i0 (the last row before it) to i1. 1 if empty. */
int cal_stage_span(const double *h, int rows, int stage, int *i0, int *i1);

/* calibrate_protocol.c: the data's own stages (from data.columns.stage, or from the load curve: loading,
 * hold at the peak, unloading), and the forward scene made to follow them (drive: data). */
int  cal_protocol_find(const YdDoc *doc, CalRun *run, char *err, size_t errlen);
/* One line per stage into buf (the log). */
void cal_protocol_describe(const CalRun *run, char *buf, size_t n);
/* Write the forward scene (and reference) driven by the data's history into dir: run->driven(_reference). */
int  cal_protocol_write(CalRun *run, const char *dir, char *err, size_t errlen);

/* calibrate_units.c: data.units (each column's unit converted to the forward scene's; every column's unit declared),
 * the data's and the forward scene's ranges (the dry run), and the data's loads against the forward scene's. */
int  cal_units_read(const YdDoc *doc, YdNode *data, CalRun *run, const char *path, char *err, size_t errlen);
void cal_ranges_describe(const CalRun *run, char *buf, size_t n);
int  cal_check_load_scale(const CalRun *run, int accept, char *err, size_t errlen);
/* The key that declares a role's unit ("runs[k].data.units.load" or ".factors.load") and how ("unit mN", "factor 1000"). */
const char *cal_unit_key(const CalRun *run, int role, char *buf, size_t n);
const char *cal_unit_how(const CalRun *run, int role, char *buf, size_t n);

/* calibrate_drift.c: drift: fit | {measured_in: STAGE} (read after the data and their stages; a measured drift is
 * removed from the data's depths there); the drift regressor of a run's residuals (each depth residual's change
 * per unit drift rate); its projection out of the residuals (drift: fit). */
int  cal_drift_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen);
void cal_drift_regressor(const CalRun *run, double *a);
void cal_drift_project(CalRun *run, double *r);

/* calibrate_load.c: the load history the forward runs follow (drive: data): the data's rows, or a continuous
 * piecewise-linear least-squares fit when the load is noisy (load_history: auto | fitted | data). */
int  cal_load_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen);
int  cal_load_fit(CalRun *run, char *err, size_t errlen);
/* A series' noise from its second differences (a robust estimate, the median's) over p[0..n-1]: the standard
 * deviation of independent errors on a curve smooth at the rows' spacing. */
double cal_noise(const double *p, int n);
/* The same from the second differences themselves (d[0..n-1], overwritten). */
double cal_noise_d2(double *d, int n);
void cal_load_describe(const CalRun *run, char *buf, size_t n);

/* calibrate_check.c: checks that catch a wrong fit at the start (accept: the names of those accepted). */
enum { CAL_ACCEPT_ROWS = 1, CAL_ACCEPT_SCALE = 2, CAL_ACCEPT_BOUND = 4 };
/* Every data row in a forward stage, every block with the rows of its kind (indentation data). */
int cal_check_rows(const CalRun *run, const char *dir, int accept, char *err, size_t errlen);
/* The data's scale against the first forward run's (a factor of 10 apart: a unit): models 0, the loads (from the
 * history, before the residuals); 1, the depths or values (the models at the data, after them). */
int cal_check_scale(const CalRun *run, const char *dir, int accept, int models, char *err, size_t errlen);

#endif
