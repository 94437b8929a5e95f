/* What a calibration tells its user: fit.yaml and the summary on stdout. Both say which number to quote: the
 * refined value when the fit was refined on the full model, else the forward model's fit (with its bias, when a
 * full model measured it). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "calibrate_yaml.h"

/* The values to quote, their standard errors in parts, and why: the data's part (Newey-West: the forward fit's, or
 * the full model's at the refined value), the model's (the refinement's last step; the forward model's bias,
 * measured and left in, when the fit was not refined; NAN when not measured) and TAO's convergence (the Gauss-Newton
 * step left at the forward fit; at a refined value its last step, the model part, holds it). */
void cal_quote(const Calib *c, const double *u, const CalUncertainty *un, const CalBias *b, int k, CalQuote *q) {
  int over = b->have && fabs(b->first[k]) > un->white[k]; /* as cal_bias decides */
  q->v     = b->refined ? b->p[k] : cal_param(&c->p[k], u[k]);
  q->data  = b->refined ? b->se_data[k] : un->se[k];
  q->model = b->refined ? b->se_model[k] : b->have && !b->failed[0] ? fabs(b->first[k]) : NAN;
  q->conv  = b->refined ? 0 : fabs(un->step[k]);
  q->load  = un->load[k];
  q->s     = sqrt(q->data * q->data + (isnan(q->model) ? 0 : q->model * q->model) + (isnan(q->load) ? 0 : q->load * q->load) +
                  q->conv * q->conv);
  if (b->failed[0]) snprintf(q->why, sizeof q->why, "the forward model's fit; its bias is unknown (the full-model run failed)");
  else if (b->refined)
    snprintf(q->why, sizeof q->why, "refined on the full model (%d full-model runs%s)", b->nfull, b->converged ? "" : ", NOT converged");
  else if (!b->have) snprintf(q->why, sizeof q->why, "the forward model's fit; its bias is not measured (no reference)");
  else if (over) snprintf(q->why, sizeof q->why, "the forward model's fit, biased beyond its standard error (refine: no): refine it");
  else snprintf(q->why, sizeof q->why, "the forward model's fit; its bias (one full-model run) is below the standard error");
}

/* "3.1e+07" or "not measured" */
static const char *num(double x, char *buf, size_t n) {
  if (isnan(x)) snprintf(buf, n, "null");
  else snprintf(buf, n, "%.3g", x);
  return buf;
}

/* A number written by %g without a point ("1e+08") is a string to YAML 1.1 readers (PyYAML): "1.0e+08" is a float.
 * The text of fit.yaml copied to fp with such mantissas given their ".0". */
static void yaml_floats(const char *t, FILE *fp) {
  for (const char *p = t; *p;) {
    int start = (p == t || strchr(" [{,:", p[-1])) && (isdigit((unsigned char)*p) || (*p == '-' && isdigit((unsigned char)p[1])));
    if (!start) {
      fputc(*p++, fp);
      continue;
    }
    const char *q = p + (*p == '-');
    while (isdigit((unsigned char)*q)) q++;
    if (*q == 'e' && (q[1] == '+' || q[1] == '-') && isdigit((unsigned char)q[2])) {
      fwrite(p, 1, (size_t)(q - p), fp), fputs(".0", fp);
      p = q;
    }
    while (p < q) fputc(*p++, fp);
  }
}

static void write_yaml(Calib *c, FILE *fp, const double *u, const CalUncertainty *un, const double *cov, double ssr, PetscInt its,
                       const char *reason, const CalBias *b);

void cal_write_yaml(Calib *c, FILE *fp, const double *u, const CalUncertainty *un, const double *cov, double ssr, PetscInt its,
                    const char *reason, const CalBias *b) {
  char  *text = NULL;
  size_t len  = 0;
  FILE  *mem  = open_memstream(&text, &len);
  if (!mem) return write_yaml(c, fp, u, un, cov, ssr, its, reason, b);
  write_yaml(c, mem, u, un, cov, ssr, its, reason, b);
  fclose(mem);
  yaml_floats(text, fp);
  free(text);
}

static void write_yaml(Calib *c, FILE *fp, const double *u, const CalUncertainty *un, const double *cov, double ssr, PetscInt its,
                       const char *reason, const CalBias *b) {
  int         n  = c->np;
  const double *se = un->se;
  char        b1[32], b2[32];
  fprintf(fp, "# calibrate %s: TAO %s, %d iterations (%s), %d evaluations (%d rejected), %d forward runs, wall %.1f s\n",
          c->name, c->tao_type, (int)its, reason, c->nevals, c->nrejected, c->nforward, MPI_Wtime() - c->wall0);
  fprintf(fp, "# quote: the values to quote, with their standard errors and where they come from (docs/calibrate.md).\n"
              "# std_error = sqrt(data^2 + model^2 + load^2 + convergence^2): data, the data's noise (Newey-West, residuals correlated along\n"
              "# each block, docs/calibrate.md 'Standard errors'); model, the forward model's (the refinement's last step, or the bias left in;\n"
              "# null: not measured); load, the fitted load history's (its knots' noise, from load_draws forward runs; null: the forward\n"
              "# runs follow no fitted history, docs/calibrate.md 'A noisy load'); convergence, TAO's (the Gauss-Newton step left at the forward fit)\n");
  fprintf(fp, "quote:\n");
  for (int k = 0; k < n; k++) {
    CalQuote q;
    cal_quote(c, u, un, b, k, &q);
    fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, relative_std_error: %.3g, std_error_data: %.3g, std_error_model: %s, "
                "std_error_load: %s, std_error_convergence: %.3g, from: \"%s\"}\n", c->p[k].name, q.v, q.s, q.s / fabs(q.v), q.data,
            num(q.model, b1, sizeof b1), num(q.load, b2, sizeof b2), q.conv, q.why);
  }
  fprintf(fp, "# parameters: the forward model's fit; std_error: for residuals correlated along each block (prewhitened by an AR(1),\n"
              "# Andrews & Monahan 1992; then Newey-West 1987, the bandwidth by Andrews' 1991 AR(1) rule);\n"
              "# white_std_error: s^2 (J^T J)^-1, independent residuals of one size\n"
              "parameters:\n");
  for (int k = 0; k < n; k++) {
    double v = cal_param(&c->p[k], u[k]);
    fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, relative_std_error: %.3g, white_std_error: %.3g, gauss_newton_step: %.3g, "
                "start: %.6g, min: %.6g, max: %.6g, scale: %s%s}\n", c->p[k].name, v, se[k], se[k] / fabs(v), un->white[k],
            un->step[k], c->p[k].start, c->p[k].lo, c->p[k].hi, c->p[k].log ? "log" : "linear",
            u[k] <= 1e-6 || u[k] >= 1 - 1e-6 ? ", at_bound: true" : "");
  }
  fprintf(fp, "standard_errors: {method: prewhitened_newey_west, prewhitening: ar1, residuals_lag1: %.3g, kernel: bartlett, "
              "bandwidth_rule: andrews_1991_ar1, alpha: %.4g, longest_block: %d, its_bandwidth: %.3g, its_lags: %d}\n",
          un->hac.rho, un->hac.alpha, un->hac.longest, un->hac.bandwidth, un->hac.lags);
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
    fprintf(fp, "refinement: {refined: %s, full_model_runs: %d, converged: %s, steps_relative: [", b->refined ? "true" : "false",
            b->nfull, b->converged ? "true" : "false");
    for (int s = 0; s < b->nsteps; s++) {
      fprintf(fp, "%s[", s ? ", " : "");
      for (int k = 0; k < n; k++) fprintf(fp, "%s%.3g", k ? ", " : "", b->steps[s][k]);
      fprintf(fp, "]");
    }
    fprintf(fp, "]}\n");
    if (b->refined) {
      fprintf(fp, "refined:\n");
      for (int k = 0; k < n; k++)
        fprintf(fp, "  %s: {value: %.8g, std_error: %.3g, std_error_data: %.3g, std_error_model: %.3g}\n", c->p[k].name, b->p[k],
                b->se[k], b->se_data[k], b->se_model[k]);
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
  fprintf(fp, "# forward_models: each run's; max_error_vs_reference: the largest |forward - full model| at the data at the fit,\n"
              "# relative to that block's data range (max_error_block)\nforward_models:\n");
  for (int j = 0; j < c->nrun; j++) {
    const CalRun *run = &c->run[j];
    fprintf(fp, "  - {run: %s, scene: %s, drive: %s", run->name, run->scene, run->drive ? "data" : "scene");
    if (run->drive) {
      fprintf(fp, ", stages: [");
      for (int s = 0; s < run->nstage; s++) fprintf(fp, "%s%s", s ? ", " : "", run->stage[s].name);
      fprintf(fp, "], stages_from: %s", run->stages_from_column ? "column" : "curve");
    }
    if (run->reference[0]) fprintf(fp, ", reference: %s", run->reference);
    if (b->max_diff[j] >= 0)
      fprintf(fp, ", max_error_vs_reference: %.3g, max_error_block: %s", b->max_diff[j], cal_kind_name(run->curve[b->max_block[j]].kind));
    fprintf(fp, "}\n");
  }
  fprintf(fp, "# each run's data: the units declared, the load history the forward runs followed (drive: data), the drift\nruns:\n");
  for (int j = 0; j < c->nrun; j++) {
    static const char *roles[4] = {"time", "load", "depth", "value"};
    const CalRun      *run      = &c->run[j];
    const int          col[4]   = {run->col_time, run->col_load, run->col_depth, run->col_value};
    fprintf(fp, "  %s:\n    units: {", run->name);
    for (int r = 0, first = 1; r < 4; r++, first = first && col[r - 1] < 0)
      if (col[r] >= 0)
        fprintf(fp, "%s%s: {column: \"%s\", %s%s%s factor: %.8g}", first ? "" : ", ", roles[r], run->col_name[r],
                run->declared[r] == 1 ? "unit: \"" : run->declared[r] == 3 ? "unit: scene," : "",
                run->declared[r] == 1 ? run->unit[r] : "", run->declared[r] == 1 ? "\"," : "", run->factor[r]);
    fprintf(fp, "}\n");
    if (run->weighting == CAL_WEIGHT_NOISE)
      fprintf(fp, "    weighting: {by: noise, depth_noise: %s, value_noise: %s}\n", num(run->noise[2], b1, sizeof b1),
              num(run->noise[3], b2, sizeof b2));
    else fprintf(fp, "    weighting: {by: range}\n");
    if (run->drive)
      fprintf(fp, "    load_history: {followed: %s, asked: %s, noise: %.4g, noise_relative: %.3g, knots: %d, rms_about_fit: %s, "
                  "tables: %s/protocol/%s}\n", run->load_fitted ? "fitted" : "data",
              run->load_history == CAL_LOAD_FITTED ? "fitted" : run->load_history == CAL_LOAD_DATA ? "data" : "auto",
              run->load_noise, run->load_noise / run->load_peak, run->load_fitted ? run->nknot : 0,
              run->load_fitted ? num(run->load_rms, b1, sizeof b1) : "null", c->outdir, run->name);
    if (run->drift == CAL_DRIFT_MEASURED)
      fprintf(fp, "    drift: {treatment: measured, stage: %s, rate: %.6g, std_error: %.3g, rate_data_units: %.6g, rows: %d, "
                  "removed: true}\n", run->stage[run->drift_stage].name, run->drift_rate, run->drift_se,
              run->drift_rate / run->factor[2], run->drift_rows);
    else if (run->drift == CAL_DRIFT_FIT)
      fprintf(fp, "    drift: {treatment: fit, rate: %.6g, std_error: %s, rate_data_units: %.6g}\n", run->drift_rate,
              num(run->drift_se, b2, sizeof b2), run->drift_rate / run->factor[2]);
    for (int t = 0; t < un->ntrend; t++) {
      const CalTrend *tr = &un->trend[t];
      if (tr->run != j) continue;
      fprintf(fp, "    hold_trend_%s: {rate: %.4g, std_error: %.3g, z: %.3g, over_the_hold: %.3g, rate_data_units: %.4g, warned: %s",
              run->curve[tr->block].stage_name, tr->rate, tr->se, tr->z, tr->size, tr->rate / run->factor[2], tr->warn ? "true" : "false");
      if (!isnan(tr->model_rate)) fprintf(fp, ", model_rate: %.4g", tr->model_rate);
      fprintf(fp, "}\n");
    }
  }
  fprintf(fp, "# the quoted values, to paste into a scene's material block:\nset: {");
  for (int k = 0; k < n; k++) {
    CalQuote q;
    cal_quote(c, u, un, b, k, &q);
    fprintf(fp, "%s%s: %.6g", k ? ", " : "", c->p[k].name, q.v);
  }
  fprintf(fp, "}\n");
}

/* The misfit need not be convex in the parameters: a clean record fitted without a drift option from 3x above its truth
 * stopped at +363 % with only this warning (docs/calibrate.md, "Coverage"). */
#define LOCAL_MINIMUM "Or the fit stopped at a local minimum of the misfit: rerun it from another start"

PetscErrorCode cal_print_summary(Calib *c, const double *u, const CalUncertainty *un, const CalBias *b) {
  char         part[160];
  const double *se = un->se;
  PetscFunctionBeginUser;
  for (int j = 0; j < c->nrun; j++) { /* the drift, and the hold's trends */
    const CalRun *run = &c->run[j];
    const char   *lu  = run->scene_unit[2][0] ? run->scene_unit[2] : "(depth)";
    if (run->drift == CAL_DRIFT_FIT)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  run %s: drift rate (fitted) %.4g +- %.2g %s/s (%.4g in the data's depth unit per s)\n",
                            run->name, run->drift_rate, run->drift_se, lu, run->drift_rate / run->factor[2]));
    for (int t = 0; t < un->ntrend; t++) {
      const CalTrend *tr = &un->trend[t];
      if (tr->run != j) continue;
      const CalCurve *cv = &run->curve[tr->block];
      if (tr->warn)
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "warning: run %s, residuals[%d] (hold in stage '%s'): its residuals show a trend the fit "
                              "cannot take up: the data's depth rises %.3g %s/s (%.3g in the data's depth unit per s) faster than the "
                              "model's, z = %.1f, %.2g %% of the hold's data range over the hold. Thermal drift? %s\n", run->name,
                              cv->index, cv->stage_name, tr->rate, lu, tr->rate / run->factor[2], tr->z, 100 * tr->size,
                              run->drift == CAL_DRIFT_FIT ? "The drift is fitted already: the forward model misses the hold's shape (its bias: "
                                                            "a reference); or the drift is not constant. " LOCAL_MINIMUM
                                                          : "Give runs[k].drift: fit (the rate fitted beside the parameters), or "
                                                            "{measured_in: STAGE} (a hold where the material is at rest; "
                                                            "docs/calibrate.md, 'Thermal drift'). Or the forward model's own "
                                                            "error over the hold: a full model (reference) measures it. " LOCAL_MINIMUM));
      if (cal_rest_warning(run, tr))
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "warning: run %s: the drift was measured in stage '%s', where the model's own depth "
                              "moves at %.3g %s/s at the fit, %.0f %% of the drift measured (%.3g +- %.2g): the correction took the "
                              "material's creep or recovery there for drift, a bias beyond the rate's own uncertainty; drift: fit "
                              "separates them\n", run->name, cv->stage_name, tr->model_rate, lu,
                              100 * fabs(tr->model_rate / run->drift_rate), run->drift_rate, run->drift_se));
    }
  }
  for (int k = 0; k < c->np; k++) {
    double p = cal_param(&c->p[k], u[k]);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s = %.6g +- %.2g (%.2g %%): the forward model's fit (Newey-West; white "
                          "ones would say +- %.2g)\n", c->p[k].name, p, se[k], 100 * se[k] / fabs(p), un->white[k]));
    if (b->have)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s   its bias (its fit less the full model's), from one full-model run: %+.4g "
                            "(%+.2g %%, %.3g standard errors, %.3g white ones)\n", "", b->first[k], 100 * b->first[k] / p,
                            fabs(b->first[k]) / se[k], fabs(b->first[k]) / un->white[k]));
    if (b->refined)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  %-14s   refined on the full model: %.8g +- %.2g; the bias measured: %+.4g +- %.2g "
                            "(%+.2g %%)\n", "", b->p[k], b->se[k], b->bias[k], b->bias_se[k], 100 * b->bias[k] / p));
    CalQuote q;
    cal_quote(c, u, un, b, k, &q);
    if (isnan(q.model)) snprintf(part, sizeof part, "data %.2g, model not measured", q.data);
    else snprintf(part, sizeof part, "data %.2g, model %.2g", q.data, q.model);
    size_t len = strlen(part);
    if (!isnan(q.load)) snprintf(part + len, sizeof part - len, ", load history %.2g", q.load), len = strlen(part);
    snprintf(part + len, sizeof part - len, ", convergence %.2g", q.conv);
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "quote: %s = %.8g +- %.2g (%.2g %%; %s): %s\n", c->p[k].name, q.v, q.s,
                          100 * q.s / fabs(q.v), part, q.why));
  }
  PetscCall(PetscPrintf(PETSC_COMM_SELF, "  standard errors: for residuals correlated along each block (their lag-1 %.3g, "
                        "prewhitened; Newey-West, bandwidth %.3g on the longest block of %d residuals; docs/calibrate.md, "
                        "'Standard errors')\n", un->hac.rho, un->hac.bandwidth, un->hac.longest));
  for (int j = 0; j < c->nrun; j++)
    if (b->max_diff[j] >= 0)
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  run %s: forward model %s against the full model %s at the forward fit: largest "
                            "|forward - full| %.3g of its block's data range (block %d, %s): the forward model's own error there "
                            "(docs/calibrate.md, 'The end line')\n", c->run[j].name, c->run[j].scene, c->run[j].reference,
                            b->max_diff[j], b->max_block[j], cal_kind_name(c->run[j].curve[b->max_block[j]].kind)));
  PetscFunctionReturn(0);
}
