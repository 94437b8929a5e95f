/* Adaptation by rerun (docs/adapt.md): the scene is run on its own mesh, then again from its start on meshes made
 * from the error indicator of the run before (fe/fe_estimate.h), each with about mesh.adapt.growth times the
 * cells; no state is carried between meshes. The reported quantities of the last two (or three) levels give
 * each one's estimated mesh error. Level k's files are in OUT/adapt/level<k>; the last level's history, fields
 * and mesh are copied to OUT once it is done, with summary.json. */
#ifndef FE_ADAPT_H
#define FE_ADAPT_H

#include "fe_app.h"

/* The options block: -adapt_levels, -adapt_growth (main declares it with the others, for -help). */
PetscErrorCode fe_adapt_declare(PetscInt *levels, PetscReal *growth, PetscBool *set_levels, PetscBool *set_growth);

/* -adapt_levels N (0: off) and -adapt_growth G, over the scene's mesh.adapt; adaptation with -restart or without a
   geometry is bad input (*bad = 2, err filled). */
PetscErrorCode fe_adapt_options(YdDoc *doc, FeScene *sc, PetscBool restart, char *err, size_t errlen, int *bad);

/* Run the levels. Returns the run's status (0, 1, 2 with err filled, or a PETSc code). */
int fe_adapt_run(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, char *err, size_t errlen);

#endif
