/* The evaluations of a calibration: the parameters from u, each forward run a separate process (posix_spawn of
 * this executable, no shell, without the MPI launcher's environment), the residuals of every run, the points
 * evaluated kept. */
#include "calibrate_forward.h"

#include <fcntl.h>
#include <math.h>
#include <petscsys.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../io/fsutil.h"
#include "calibrate_drift.h"
#include "calibrate_residual.h"

extern char **environ;

#define FAIL(...)                                                                                                   \
  do {                                                                                                              \
    snprintf(err, errlen, __VA_ARGS__);                                                                             \
    return 1;                                                                                                       \
  } while (0)

double cal_param(const CalParam *p, double u) {
  return p->log ? exp(log(p->lo) + u * (log(p->hi) - log(p->lo))) : p->lo + u * (p->hi - p->lo);
}
double cal_dparam(const CalParam *p, double u) { return p->log ? cal_param(p, u) * log(p->hi / p->lo) : p->hi - p->lo; }

/* The environment without the MPI launcher's variables: a forward run is its own singleton. */
static char **child_environment(void) {
  int n = 0;
  while (environ[n]) n++;
  char **env = malloc(sizeof(char *) * (size_t)(n + 1));
  int    k   = 0;
  for (int i = 0; i < n; i++)
    if (strncmp(environ[i], "OMPI_", 5) && strncmp(environ[i], "PMIX_", 5) && strncmp(environ[i], "PMI_", 4) &&
        strncmp(environ[i], "HYDRA_", 6))
      env[k++] = environ[i];
  env[k] = NULL;
  return env;
}

int cal_forward(Calib *c, const CalRun *run, const char *scene, const double *p, const char *dir) {
  char  set[1024], opts[512], log[PATH_MAX + 16], *argv[64], *tok, *save = NULL;
  int   argc = 0, status = 0;
  pid_t pid;
  snprintf(set, sizeof set, "%s", run->set);
  for (int k = 0; k < c->np; k++) {
    size_t len = strlen(set);
    snprintf(set + len, sizeof set - len, "%s%s=%.17g", len ? "," : "", c->p[k].name, p[k]);
  }
  if (fs_make_directories(dir)) return -1;
  argv[argc++] = c->exe, argv[argc++] = "-input", argv[argc++] = (char *)scene, argv[argc++] = "-output_dir";
  argv[argc++] = (char *)dir, argv[argc++] = "-material_set", argv[argc++] = set;
  argv[argc++] = "-progress_every", argv[argc++] = "1000000";
  snprintf(opts, sizeof opts, "%s", run->options);
  for (tok = strtok_r(opts, " \t", &save); tok && argc < 62; tok = strtok_r(NULL, " \t", &save)) argv[argc++] = tok;
  argv[argc] = NULL;
  snprintf(log, sizeof log, "%s/forward.log", dir);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  char **env = child_environment();
  double t0  = MPI_Wtime();
  int    rc  = posix_spawn(&pid, c->exe, &fa, NULL, argv, env);
  posix_spawn_file_actions_destroy(&fa);
  free(env);
  if (rc) return -1;
  while (waitpid(pid, &status, 0) < 0) {}
  c->nforward++, c->forward_wall += MPI_Wtime() - t0;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

/* The evaluated points: u, the residuals (before a fitted drift is profiled out of them) and every block's model
 * curve. A point evaluated before costs no run. */
static size_t  cache_size(const Calib *c) { return (size_t)(c->np + 2 * c->m); }
static double *cache_entry(Calib *c, int i) { return c->cache + (size_t)i * cache_size(c); }
void cal_models(Calib *c, double *models, int save) {
  for (int j = 0, off = 0; j < c->nrun; j++)
    for (int k = 0; k < c->run[j].ncurve; k++) {
      CalCurve *cv = &c->run[j].curve[k];
      if (save) memcpy(models + off, cv->model, sizeof(double) * cv->n);
      else memcpy(cv->model, models + off, sizeof(double) * cv->n);
      off += cv->n;
    }
}
static int cache_find(Calib *c, const double *u, double *r) {
  for (int i = 0; i < c->ncache; i++) {
    double *e = cache_entry(c, i);
    if (memcmp(e, u, sizeof(double) * c->np)) continue;
    memcpy(r, e + c->np, sizeof(double) * c->m);
    cal_models(c, e + c->np + c->m, 0);
    return 1;
  }
  return 0;
}
void cal_cache_add(Calib *c, const double *u, const double *r) {
  if (c->ncache == c->cache_cap) {
    c->cache_cap = c->cache_cap ? 2 * c->cache_cap : 64;
    c->cache     = realloc(c->cache, sizeof(double) * (size_t)c->cache_cap * cache_size(c));
  }
  double *e = cache_entry(c, c->ncache++);
  memcpy(e, u, sizeof(double) * c->np), memcpy(e + c->np, r, sizeof(double) * c->m);
  cal_models(c, e + c->np + c->m, 1);
}

int cal_evaluate_run(Calib *c, CalRun *run, const double *p, const char *dir, int ref, double *r, char *err, size_t errlen) {
  int rc = cal_forward(c, run, cal_run_scene(run, ref), p, dir);
  c->nfull += ref;
  char as[PATH_MAX + 32] = ""; /* drive: data: the scene that followed the data */
  if (run->drive) snprintf(as, sizeof as, " (following the data: %s)", cal_run_scene(run, ref));
  if (rc)
    FAIL("%s:%d: key 'runs[%d].%s': the %s run of %s%s failed (exit code %d; its log: %s/forward.log)", run->file,
         run->line, run->index, ref ? "reference" : "scene", ref ? "full-model" : "forward", ref ? run->reference : run->scene,
         as, rc, dir);
  if (cal_run_residual(run, dir, r, err, errlen)) {
    if (ref) { /* say whose run it was */
      char msg[1024];
      snprintf(msg, sizeof msg, "%s", err);
      FAIL("%s:%d: key 'runs[%d].reference': the full-model run of %s%s does not cover the data: %s", run->file,
           run->line, run->index, run->reference, as, msg);
    }
    return 1;
  }
  return 0;
}

/* Every run at u into r; full: a run with a reference on its full model. */
static int evaluate(Calib *c, const double *u, double *r, const char *tag, int full, char *err, size_t errlen) {
  double p[CAL_MAX_PARAMS];
  for (int k = 0; k < c->np; k++) p[k] = cal_param(&c->p[k], u[k]);
  for (int j = 0, m = 0; j < c->nrun; m += cal_run_size(&c->run[j]), j++) {
    CalRun *run = &c->run[j];
    char    dir[PATH_MAX + 200];
    snprintf(dir, sizeof dir, "%s/forward/%s_%s", c->outdir, tag, run->name);
    if (cal_evaluate_run(c, run, p, dir, full && run->reference[0], r + m, err, errlen)) return 1;
  }
  return 0;
}

/* drift: fit: each such run's drift rate profiled out of its residuals (held at 0 while c->drift_held). */
static void project_drift(Calib *c, double *r) {
  for (int j = 0, off = 0; j < c->nrun; off += cal_run_size(&c->run[j]), j++)
    if (c->run[j].drift == CAL_DRIFT_FIT) {
      if (c->drift_held) c->run[j].drift_rate = 0;
      else cal_drift_project(&c->run[j], r + off);
    }
}

int cal_evaluate(Calib *c, const double *u, double *r, const char *tag, char *err, size_t errlen) {
  if (!cache_find(c, u, r)) {
    if (evaluate(c, u, r, tag, 0, err, errlen)) return 1;
    cal_cache_add(c, u, r);
  }
  project_drift(c, r);
  return 0;
}

int cal_evaluate_full(Calib *c, const double *u, double *r, const char *tag, char *err, size_t errlen) {
  if (evaluate(c, u, r, tag, 1, err, errlen)) return 1;
  project_drift(c, r);
  return 0;
}
