/* The load history the forward runs of drive: data follow, and a series' noise. */
#ifndef CALIBRATE_LOAD_H
#define CALIBRATE_LOAD_H

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

/* The load history the forward runs follow (drive: data): the data's rows, or a continuous
 * piecewise-linear least-squares fit when the load is noisy (load_history: auto | fitted | data). */
int  cal_load_read(const YdDoc *doc, YdNode *item, CalRun *run, const char *path, char *err, size_t errlen);
int  cal_load_fit(CalRun *run, char *err, size_t errlen);
/* A series' noise from its second differences (a robust estimate, the median's) over p[0..n-1]: the standard
 * deviation of independent errors on a curve smooth at the rows' spacing. */
double cal_noise(const double *p, int n);
/* The same from the second differences themselves (d[0..n-1], overwritten). */
double cal_noise_d2(double *d, int n);
void cal_load_describe(const CalRun *run, char *buf, size_t n);

#endif
