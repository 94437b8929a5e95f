/* A calibration's state (the parameters, the runs, the counters) and its evaluations: the parameters mapped from
 * u in [0, 1] (linear or logarithmic within their bounds), each forward run a separate driver process (posix_spawn
 * of this executable, no shell), the residuals of every run, the evaluated points kept. */
#ifndef CALIBRATE_FORWARD_H
#define CALIBRATE_FORWARD_H

#include <stdio.h>

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

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
  int          load_draws;   /* -calibrate_load_draws: forward runs for a fitted load history's share of the errors */
} Calib;

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
/* One run at parameters p into dir (ref 1: its full model) and its residuals into r (cal_run_size of them, before a
 * fitted drift is profiled out): 0, or 1 with err naming the run, its scene and its log. */
int cal_evaluate_run(Calib *c, CalRun *run, const double *p, const char *dir, int ref, double *r, char *err, size_t errlen);
/* One forward process of a run's scene (or its reference) at parameters p into dir: the exit code. */
int cal_forward(Calib *c, const CalRun *run, const char *scene, const double *p, const char *dir);

/* A point evaluated (u, its residuals r and the blocks' model curves) kept: evaluating it again costs no run. */
void cal_cache_add(Calib *c, const double *u, const double *r);

#endif
