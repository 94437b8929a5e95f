/* A finite-element scene (scene: fe) from its document: read it (and its indenter), the runner's and the scene's
 * options, then the adaptation's levels (fe_adapt.c) or one run (fe_app.c) and the run's summary. */
#include "fe_run.h"

#include <petscsys.h>
#include <stdio.h>
#include <string.h>

#include "../contact/indent_scene.h"
#include "../fe/fe_scene.h"
#include "../io/keydecl.h"
#include "../io/options.h"
#include "fe_adapt.h"
#include "fe_app.h"
#include "run_summary.h"

/* The scene's PETSc options, each unless the command line already gives it; one that looks like a driver's option
   but is none is refused (io/options.h). Returns 0, 2 (err filled) or a PETSc error code (err empty). */
static int apply_scene_options(const char *file, const char *options, char *err, size_t errlen) {
  char buf[1024], *tok, *save = NULL, *keys[64], *vals[64], where[1100];
  int  n = 0;
  snprintf(buf, sizeof buf, "%s", options);
  for (tok = strtok_r(buf, " \t", &save); tok && n < 64; tok = strtok_r(NULL, " \t", &save)) {
    if (tok[0] == '-' && !(tok[1] >= '0' && tok[1] <= '9') && tok[1] != '.') keys[n] = tok, vals[n++] = NULL;
    else if (n > 0 && !vals[n - 1]) vals[n - 1] = tok;
  }
  snprintf(where, sizeof where, "%s: key 'solver.options'", file);
  PetscBool      bad;
  PetscErrorCode ierr = options_check_unknown((const char *const *)keys, n, NULL, where, err, errlen, &bad);
  if (ierr || bad) return ierr ? stage_runner_status(ierr, err) : 2;
  for (int k = 0; k < n; k++) {
    PetscBool set;
    ierr = PetscOptionsHasName(NULL, NULL, keys[k], &set);
    if (!ierr && !set) ierr = PetscOptionsSetValue(NULL, keys[k], vals[k]);
    if (ierr) return stage_runner_status(ierr, err);
  }
  return 0;
}

int fe_app_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen) {
  static FeScene     sc; /* large: kept off the stack */
  static IndentScene isc;
  RunnerOptions      opt;
  RunInfo            info;
  if (fe_scene_read(doc, &sc, err, errlen)) return 2;
  if (sc.indenter && indent_scene_read(doc, &sc, &isc, err, errlen)) return 2;
  if (keys_check_document(doc, err, errlen)) return 2; /* every key read, and read with its declaration */
  if (outdir_override && outdir_override[0]) snprintf(sc.outdir, sizeof sc.outdir, "%s", outdir_override);
  PetscErrorCode ierr = app_runner_options(&opt);
  int rank, bad = 0;
  if (!ierr) ierr = fe_adapt_options(doc, &sc, opt.restart, err, errlen, &bad);
  if (ierr) return stage_runner_status(ierr, err);
  if (bad || (bad = apply_scene_options(doc->file, sc.solver_options, err, errlen))) return bad;
  if (sc.adapt.levels > 0) return fe_adapt_run(doc, &sc, &isc, &opt, err, errlen);
  int rc = fe_app_run_once(doc, &sc, &isc, &opt, NULL, NULL, 0, 0, &info, err, errlen);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (!rc && !rank) {
    run_summary_print(&sc, &info, NULL);
    RunEnd end = {NULL, -1, info.sum.replaced};
    rc         = run_summary_write(&sc, sc.outdir, &info, 1, NULL, &end, err, errlen);
  } else if (rc && !rank) run_summary_failed(&sc, sc.outdir, &info, 1, -1, info.sum.replaced, rc, err);
  MPI_Bcast(&rc, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  return rc;
}
