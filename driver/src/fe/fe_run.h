/* A finite-element scene (scene: fe): mesh, material, phi field, initial stress, boundary conditions,
 * load stages with adaptive time steps, history output. */
#ifndef FE_RUN_H
#define FE_RUN_H

#include "../io/yaml_doc.h"

/* Returns 0 on success, 1 (err filled) on a bad scene or a failed run. */
int fe_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen);

#endif
