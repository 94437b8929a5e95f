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
} CalParam;

typedef struct {
  const YdDoc *doc;
  char         name[64], outdir[PATH_MAX], exe[PATH_MAX];
  CalParam     p[CAL_MAX_PARAMS];
  int          np;
  CalRun       run[CAL_MAX_RUNS];
  int          nrun, m;      /* residual count */
  int          nevals, nforward, nrejected, iterations;
  double       penalty;      /* each residual of a rejected evaluation */
  double       wall0, forward_wall;
  double       best_f, best_u[CAL_MAX_PARAMS];
  FILE        *evals;        /* evaluations.csv */
  char         tao_type[64];
} Calib;

/* Run the calibrate scene doc; outputs under outdir (or the scene's output.directory). */
int calibrate_run(YdDoc *doc, const char *outdir, char *err, size_t errlen);

/* Parameters from u in [0, 1]^n, and dp/du. */
double cal_param(const CalParam *p, double u);
double cal_dparam(const CalParam *p, double u);
/* One evaluation at u: every run's forward process and residuals into r (c->m). Returns 0, or 1 when an
 * evaluation failed (err says why; r untouched). tag names the evaluation's folder. */
int cal_evaluate(Calib *c, const double *u, double *r, const char *tag, char *err, size_t errlen);
/* One forward process of a run's scene (or its reference) at parameters p into dir: the exit code. */
int cal_forward(Calib *c, const CalRun *run, const char *scene, const double *p, const char *dir);

/* The report after TAO: Jacobian at u by finite differences, standard errors, correlations, the fitted
 * curves, the reference runs, fit.yaml. */
int cal_report(Calib *c, const double *u, PetscInt its, const char *reason, char *err, size_t errlen);

#endif
