/* A 'runs:' item of a calibrate scene read into a CalRun: the forward scene, the data file and its columns, units,
 * stages, drift, load history and residual blocks (docs/calibrate.md). */
#ifndef CALIBRATE_DATA_H
#define CALIBRATE_DATA_H

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

/* Read runs[k] from a 'runs:' item of the calibrate scene. 0, or 1 with err filled. */
int cal_run_read(const YdDoc *doc, YdNode *item, int k, CalRun *run, char *err, size_t errlen);

#endif
