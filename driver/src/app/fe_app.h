/* Finite-element scenes (scene: fe), with or without an indenter: set-up and run. */
#ifndef FE_APP_H
#define FE_APP_H

#include <petscsys.h>

#include "../contact/indent_scene.h"
#include "../io/yaml_doc.h"
#include "../stepping/stage_runner.h"
#include "run_summary.h"

/* One run of the scene into sc->outdir (created if missing): meshed from its geometry, or from geo (a .geo that
   includes it with another size field) when given; after the stages, when sizes is given, the size field of the
   next mesh, for about growth times base cells (base 0: this mesh's cells; fe/fe_estimate.h), is written there. info: the run's mesh, counters, CPU and
   reported quantities. Returns the run's status (0, 1, 2 with err filled, or a PETSc code). */
int fe_app_run_once(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, const char *geo, const char *sizes, double growth, double base, RunInfo *info,
                    char *err, size_t errlen);
/* The runner's command-line options (-checkpoint_every, -restart, -max_steps, -progress_every). */
PetscErrorCode app_runner_options(RunnerOptions *o);

#endif
