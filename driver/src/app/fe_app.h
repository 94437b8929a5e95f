/* Finite-element scenes (scene: fe), with or without an indenter: set-up and run. */
#ifndef FE_APP_H
#define FE_APP_H

#include <petscsys.h>

#include "../io/yaml_doc.h"
#include "../stepping/stage_runner.h"

/* Returns 0 on success, 1 (err filled) on a failed run, 2 on bad input. */
int fe_app_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen);
/* The runner's command-line options (-checkpoint_every, -restart, -max_steps, -progress_every). */
PetscErrorCode app_runner_options(RunnerOptions *o);

#endif
