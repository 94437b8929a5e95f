/* scene: calibrate: fit named PROPS of the material to measured curves (indentation P-h, creep over a hold,
 * unloading; strain-time records of point or FE scenes) by least squares on TAO (POUNDERS by default),
 * each forward run a separate driver process (docs/calibrate.md). */
#ifndef CALIBRATE_H
#define CALIBRATE_H

#include <stddef.h>

#include "../io/yaml_doc.h"

/* -calibrate_load_draws: forward runs at the fit that measure a fitted load history's share of the standard errors
 * (docs/calibrate.md, "A noisy load"); its default, and its largest value. */
#define CAL_LOAD_DRAWS 6
#define CAL_LOAD_DRAWS_MAX 64

/* Run the calibrate scene doc; outputs under outdir (or the scene's output.directory). */
int calibrate_run(YdDoc *doc, const char *outdir, char *err, size_t errlen);

#endif
