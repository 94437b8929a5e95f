/* The forward runs of a calibrate scene and their measured data: which forward scene, which CSV (columns,
 * factors to the forward scene's units), whose protocol the forward runs follow (the data's own history, or
 * the forward scene's stages), which residuals (loading, hold, unloading, series) (docs/calibrate.md). The types
 * every file of calibrate/ shares and the functions on them alone; calibrate_data.c reads them from the scene. */
#ifndef CALIBRATE_RUN_H
#define CALIBRATE_RUN_H

#include <limits.h>
#include <stddef.h>

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

/* The checks a scene accepts (accept: their names; calibrate_check.c, calibrate_units.c). */
enum { CAL_ACCEPT_ROWS = 1, CAL_ACCEPT_SCALE = 2, CAL_ACCEPT_BOUND = 4 };

const char *cal_kind_name(CalKind k);
/* The scene a forward run (reference 0) or the full-model run (1) is started with. */
const char *cal_run_scene(const CalRun *run, int reference);
void        cal_run_free(CalRun *run);

#endif
