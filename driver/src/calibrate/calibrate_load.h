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
/* The fitted history's knots moved by one draw of their own uncertainty into p[0..nknot-1]: knot_p + sigma L^-T z,
 * N = L L^T the fit's normal matrix, sigma the load's noise, z random signs fixed by (draw, the run's index), so that
 * the moves have the knots' least-squares covariance sigma^2 N^-1. */
void cal_load_draw(const CalRun *run, int draw, double *p);

#endif
