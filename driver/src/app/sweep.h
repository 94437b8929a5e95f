/* The extremes sweep (scene: sweep): one material point over a matrix of time steps, viscosities,
 * strain increments, bedding angles, fractions and start states; each case is one strain-controlled
 * step, compared with the same path in many small steps. Writes a table of converged / cut back /
 * failed and the error against the fine-step reference. */
#ifndef SWEEP_H
#define SWEEP_H

#include "../io/yaml_doc.h"

int sweep_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen);

#endif
