/* Finite-element scenes (scene: fe), with or without an indenter: the scene's run from its document. */
#ifndef FE_RUN_H
#define FE_RUN_H

#include <stddef.h>

#include "../io/yaml_doc.h"

/* Returns 0 on success, 1 (err filled) on a failed run, 2 on bad input. */
int fe_app_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen);

#endif
