/* Each data column's unit against the forward scene's (data.units, data.factors, units: scene). */
#ifndef CALIBRATE_UNITS_H
#define CALIBRATE_UNITS_H

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

/* data.units (each column's unit converted to the forward scene's; every column's unit declared),
 * the data's and the forward scene's ranges (the dry run), and the data's loads against the forward scene's. */
int  cal_units_read(const YdDoc *doc, YdNode *data, CalRun *run, const char *path, char *err, size_t errlen);
void cal_ranges_describe(const CalRun *run, char *buf, size_t n);
int  cal_check_load_scale(const CalRun *run, int accept, char *err, size_t errlen);
/* The key that declares a role's unit ("runs[k].data.units.load" or ".factors.load") and how ("unit mN", "factor 1000"). */
const char *cal_unit_key(const CalRun *run, int role, char *buf, size_t n);
const char *cal_unit_how(const CalRun *run, int role, char *buf, size_t n);

#endif
