/* scene: calibrate: fit named PROPS of the material to measured curves (indentation P-h, creep over a hold,
 * unloading; strain-time records of point or FE scenes) by least squares on TAO (POUNDERS by default),
 * each forward run a separate driver process (docs/calibrate.md). */
#ifndef CALIBRATE_H
#define CALIBRATE_H

#include <petscsys.h>

#include "../io/yaml_doc.h"
#include "calibrate_data.h"

typedef struct {
  char   name[64];
  int    slot;           /* PROPS slot (material_slot) */
  double start, lo, hi;  /* bounds; TAO works on u in [0, 1]: linear, or in the logarithm (log: 1) */
  int    log;
  int    line;           /* its item in 'parameters', for messages */
} CalParam;

typedef struct {
  const YdDoc *doc;
  char         name[64], outdir[PATH_MAX], exe[PATH_MAX];
  CalParam     p[CAL_MAX_PARAMS];
  int          np;
  CalRun       run[CAL_MAX_RUNS];
  int          nrun, m;      /* residual count */
  int          nevals, nforward, nrejected, iterations, nfull; /* nfull: full-model (reference) runs among nforward */
  double       penalty;      /* each residual of a rejected evaluation */
  double       wall0, forward_wall;
  double       best_f, best_u[CAL_MAX_PARAMS];
  FILE        *evals;        /* evaluations.csv */
  char         tao_type[64];
  int          accept;       /* the checks the scene accepts (CAL_ACCEPT_*) */
  int          refine;       /* the two-fidelity refinement: 0 no, 1 auto (when the bias exceeds the standard error), 2 yes */
  int          refine_runs;  /* at most this many full-model runs (refine_runs:, default 6) */
  int          ncache, cache_cap; /* every evaluated point: u (np), residuals and model curves (m each) */
  double      *cache;
  double       last_u[CAL_MAX_PARAMS], last_f; /* the previous TAO iterate, for the no-progress stop */
  int          stalled, no_progress;
  int          drift_held;   /* drift: fit: the drift rates held at 0 (the first of the two solves) */
} Calib;

#define CAL_REFINE_CAP 32 /* refine_runs at most */

/* The forward model's bias at the fit (a full-model run there) and the two-fidelity refinement. */
typedef struct {
  int    have, refined, converged, nfull; /* a reference was run; refined; its steps converged; full-model runs */
  double first[CAL_MAX_PARAMS];           /* the bias from the first full-model run (linearised) */
  double p[CAL_MAX_PARAMS], se[CAL_MAX_PARAMS];       /* refined values and standard errors (se_data, se_model combined) */
  double se_data[CAL_MAX_PARAMS], se_model[CAL_MAX_PARAMS]; /* the data's part (Newey-West), the model's (the last step) */
  double bias[CAL_MAX_PARAMS], bias_se[CAL_MAX_PARAMS]; /* the forward fit less the refined one */
  double steps[CAL_REFINE_CAP][CAL_MAX_PARAMS];       /* each refinement step, relative to the value */
  int    nsteps;
  double max_diff[CAL_MAX_RUNS];          /* each run's largest model difference at the fit / data range; -1: none */
  int    max_block[CAL_MAX_RUNS];         /* the block where it is */
  char   failed[1024];                    /* a reference run failed: why ("" otherwise) */
} CalBias;

/* The standard errors' estimate (calibrate_stats.c): the residuals' lag-1 coefficient (the prewhitening's), Andrews'
 * alpha (of the innovations), and the longest block's bandwidth S and lags. */
typedef struct {
  double alpha, rho, bandwidth;
  int    lags, longest;
} CalHacInfo;

/* A hold block's residual trend at the fit that the fitted parameters cannot take up (calibrate_drift.c). */
typedef struct {
  int    run, block, warn;
  double rate, se, z;   /* depth per s, the forward scene's units: the data's depth rises this much faster than the model's */
  double size;          /* the trend over the hold, relative to the hold's data range */
  double model_rate;    /* drift measured in this stage: the model's own rate there at the fit (NAN otherwise) */
} CalTrend;

/* The uncertainty of the fit (calibrate_report.c): the data's part (Newey-West) and the drift rates. */
typedef struct {
  double     se[CAL_MAX_PARAMS], white[CAL_MAX_PARAMS]; /* Newey-West, and white (independent residuals) */
  double     step[CAL_MAX_PARAMS];  /* the Gauss-Newton step left at the fit (in the parameter): TAO's convergence */
  double     drift_se[CAL_MAX_RUNS];
  CalHacInfo hac;
  CalTrend   trend[CAL_MAX_RUNS * CAL_MAX_CURVES];
  int        ntrend;
} CalUncertainty;

/* Run the calibrate scene doc; outputs under outdir (or the scene's output.directory). */
int calibrate_run(YdDoc *doc, const char *outdir, char *err, size_t errlen);

/* Parameters from u in [0, 1]^n, and dp/du. */
double cal_param(const CalParam *p, double u);
double cal_dparam(const CalParam *p, double u);
/* One evaluation at u: every run's forward process and residuals into r (c->m). Returns 0, or 1 when an
 * evaluation failed (err says why; r untouched). tag names the evaluation's folder. */
int cal_evaluate(Calib *c, const double *u, double *r, const char *tag, char *err, size_t errlen);
/* Every block's model curve (c->m values) saved into models (save 1) or restored from them (0). */
void cal_models(Calib *c, double *models, int save);
/* The same at u, each run with a reference on its full model (the two-fidelity fit's residual). */
int cal_evaluate_full(Calib *c, const double *u, double *r, const char *tag, char *err, size_t errlen);
/* One forward process of a run's scene (or its reference) at parameters p into dir: the exit code. */
int cal_forward(Calib *c, const CalRun *run, const char *scene, const double *p, const char *dir);

/* The report after TAO: Jacobian at u by finite differences, standard errors, correlations, the fitted
 * curves, the reference runs, fit.yaml. Returns 0, 1 (err filled) or a PETSc error code (err empty). */
int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen);
/* Inverse of the n x n matrix a (row-major; overwritten) into b by Gauss-Jordan with partial pivoting; 1 if singular. */
int cal_invert(int n, double *a, double *b);
/* The bias of the fit at u (J, the inverse of J^T J, the standard errors se, all of the forward model) from a
 * full-model run there, and the refinement on the full model (calibrate_refine.c). 1 with err when a reference
 * run failed (b->failed says so too). */
int cal_bias(Calib *c, const double *u, const double *J, const double *inv, const double *se, CalBias *b, char *err,
             size_t errlen);
/* fit.yaml and the summary on stdout (calibrate_yaml.c). */
void cal_write_yaml(Calib *c, FILE *fp, const double *u, const CalUncertainty *un, const double *cov, double ssr, PetscInt its,
                    const char *reason, const CalBias *b);
PetscErrorCode cal_print_summary(Calib *c, const double *u, const CalUncertainty *un, const CalBias *b);
/* The value to quote, its standard error and its parts (data; model: NAN when not measured; convergence), and where it
 * comes from. */
typedef struct {
  double v, s, data, model, conv;
  char   why[256];
} CalQuote;
void cal_quote(const Calib *c, const double *u, const CalUncertainty *un, const CalBias *b, int k, CalQuote *q);

/* calibrate_stats.c: the covariance of estimates theta = G e (G: q x m, by row) from the residuals r in blocks (nblock
 * of them, their sizes), prewhitened by an AR(1) and then Newey-West; p fitted quantities; cov and white (q x q). */
void cal_hac(int q, int m, const double *G, const double *r, const int *blocks, int nblock, int p, double *cov, double *white,
             CalHacInfo *info);
void cal_blocks(const Calib *c, int *blocks, int *nblock);
/* G = -(J^T J)^-1 J^T (n x m) and inv = (J^T J)^-1 from J (n x m, by parameter); 1 if singular (NAN filled). */
int  cal_influence(int n, int m, const double *J, double *G, double *inv);

/* calibrate_drift.c: the hold blocks' trends at the fit (X: the fit's q columns), and the drift-stage check. */
int cal_hold_trends(Calib *c, const double *X, int q, const double *r, CalTrend *out, int max);
int cal_rest_warning(const CalRun *run, const CalTrend *t);

#endif
