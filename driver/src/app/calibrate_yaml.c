/* What a calibration tells its user: fit.yaml and the summary on stdout. Both say which number to quote: the
 * refined value when the fit was refined on the full model, else the forward model's fit (with its bias, when a
 * full model measured it). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "calibrate.h"

/* The values to quote and why. */
static void quote(const Calib *c, const double *u, const double *se, const CalBias *b, int k, double *v, double *s,
                  char *why, size_t n) {
  int over = b->have && fabs(b->first[k]) > se[k];
  *v = b->refined ? b->p[k] : cal_param(&c->p[k], u[k]);
  *s = b->refined ? b->se[k] : se[k];
  if (b->failed[0]) snprintf(why, n, "the forward model's fit; its bias is unknown (the full-model run failed)");
  else if (b->refined)
    snprintf(why, n, "refined on the full model (%d full-model runs%s)", b->nfull, b->converged ? "" : ", NOT converged");
  else if (!b->have) snprintf(why, n, "the forward model's fit; its bias is not measured (no reference)");
  else if (over) snprintf(why, n, "the forward model's fit, biased beyond its standard error (refine: no): refine it");
  else snprintf(why, n, "the forward model's fit; its bias (one full-model run) is below the standard error");
}

void cal_write_yaml(Calib *c, FILE *fp, const double *u, const double *se, const double *cov, double ssr, PetscInt its,
                    const char *reason, const CalBias *b) {
  int  n = c->np;
  char why[256];
  fprintf(fp, "# calibrate %s: TAO %s, %d iterations (%s), %d evaluations (%d rejected), %d forward runs, wall %.1f s\n",
          c->name, c->tao_type, (int)its, reason, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0);
  fprintf(fp, "# quote: the values to quote, with their standard errors and where they come from (docs/calibrate.md)\n");
  fprintf(fp, "quote:\n");
  for (int k = 0; k < n; k++) {
    double v, s;
    quote(c, u, se, b, k, &v, &s, why, sizeof why);
    fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, relative_std_error: %.3g, from: \"%s\"}\n", c->p[k].name, v, s,
            s / fabs(v), why);
  }
  fprintf(fp, "# parameters: the forward model's fit; standard errors s^2 (J^T J)^-1, s^2 = SSR/(m - n), J by central "
              "differences at the fit\nparameters:\n");
  for (int k = 0; k < n; k++) {
    double v = cal_param(&c->p[k], u[k]);
    fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, relative_std_error: %.3g, start: %.6g, min: %.6g, max: %.6g, "
                "scale: %s%s}\n", c->p[k].name, v, se[k], se[k] / fabs(v), c->p[k].start, c->p[k].lo, c->p[k].hi,
            c->p[k].log ? "log" : "linear", u[k] <= 1e-6 || u[k] >= 1 - 1e-6 ? ", at_bound: true" : "");
  }
  if (b->have) {
    fprintf(fp, "# bias: the forward model's fit less the full model's, in the parameter's units; first_estimate: from the\n"
                "# full-model run at the fit (linearised); value, std_error: measured by the refinement\nbias:\n");
    for (int k = 0; k < n; k++) {
      double v = cal_param(&c->p[k], u[k]);
      fprintf(fp, "  %s: {first_estimate: %.6g, relative: %.4g, standard_errors: %.3g", c->p[k].name, b->first[k],
              b->first[k] / v, fabs(b->first[k]) / se[k]);
      if (b->refined) fprintf(fp, ", value: %.8g, std_error: %.3g", b->bias[k], b->bias_se[k]);
      fprintf(fp, "}\n");
    }
    fprintf(fp, "refinement: {refined: %s, full_model_runs: %d, converged: %s}\n", b->refined ? "true" : "false", b->nfull,
            b->converged ? "true" : "false");
    if (b->refined) {
      fprintf(fp, "refined:\n");
      for (int k = 0; k < n; k++) fprintf(fp, "  %s: {value: %.8g, std_error: %.3g}\n", c->p[k].name, b->p[k], b->se[k]);
    }
  }
  fprintf(fp, "correlation:\n");
  for (int i = 0; i < n; i++) {
    fprintf(fp, "  - [");
    for (int j = 0; j < n; j++) fprintf(fp, "%s%.4f", j ? ", " : "", cov[i * n + j] / sqrt(cov[i * n + i] * cov[j * n + j]));
    fprintf(fp, "]\n");
  }
  fprintf(fp, "misfit: {sum_of_squares: %.6e, residuals: %d, rms: %.4e}\n", ssr, c->m, sqrt(ssr / c->m));
  fprintf(fp, "cost: {iterations: %d, evaluations: %d, rejected: %d, forward_runs: %d, full_model_runs: %d, forward_wall: %.1f, "
              "wall: %.1f}\n", (int)its, c->nevals, c->nrejected, c->nforward - c->nfull, c->nfull, c->forward_wall,
          MPI_Wtime() - c->wall0);
  fprintf(fp, "forward_models:\n");
  for (int j = 0; j < c->nrun; j++) {
    const CalRun *run = &c->run[j];
    fprintf(fp, "  - {run: %s, scene: %s, drive: %s", run->name, run->scene, run->drive ? "data" : "scene");
    if (run->drive) {
      fprintf(fp, ", stages: [");
      for (int s = 0; s < run->nstage; s++) fprintf(fp, "%s%s", s ? ", " : "", run->stage[s].name);
      fprintf(fp, "], stages_from: %s", run->stages_from_column ? "column" : "curve");
    }
    if (run->reference[0]) fprintf(fp, ", reference: %s", run->reference);
    if (b->max_diff[j] >= 0) fprintf(fp, ", max_error_vs_reference: %.3g", b->max_diff[j]);
    fprintf(fp, "}\n");
  }
  fprintf(fp, "# the quoted values, to paste into a scene's material block:\nset: {");
  for (int k = 0; k < n; k++) {
    double v, s;
    quote(c, u, se, b, k, &v, &s, why, sizeof why);
    fprintf(fp, "%s%s: %.6g", k ? ", " : "", c->p[k].name, v);
  }
  fprintf(fp, "}\n");
}

PetscErrorCode cal_print_summary(Calib *c, const double *u, const double *se, const CalBias *b) {
  char why[256];
  PetscFunctionBeginUser;
  for (int k = 0; k < c->np; k++) {
    double p = cal_param(&c->p[k], u[k]), v, s;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s = %.6g +- %.2g (%.2g %%): the forward model's fit\n", c->p[k].name, p, se[k],
                          100 * se[k] / fabs(p)));
    if (b->have)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s   its bias (its fit less the full model's), from one full-model run: %+.4g "
                            "(%+.2g %%, %.3g standard errors)\n", "", b->first[k], 100 * b->first[k] / p, fabs(b->first[k]) / se[k]));
    if (b->refined)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s   refined on the full model: %.8g +- %.2g; the bias measured: %+.4g +- %.2g "
                            "(%+.2g %%)\n", "", b->p[k], b->se[k], b->bias[k], b->bias_se[k], 100 * b->bias[k] / p));
    quote(c, u, se, b, k, &v, &s, why, sizeof why);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "quote: %s = %.8g +- %.2g (%.2g %%): %s\n", c->p[k].name, v, s, 100 * s / fabs(v), why));
  }
  for (int j = 0; j < c->nrun; j++)
    if (b->max_diff[j] >= 0)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  run %s: forward model %s against the full model %s at the fit: largest difference %.3g "
                            "of a block's data range\n", c->run[j].name, c->run[j].scene, c->run[j].reference, b->max_diff[j]));
  PetscFunctionReturn(0);
}
