/* One step of a material point under mixed stress/strain control (the physics of point scenes; the
 * stepping is stepping/point_stepper's): Newton on the unknown strain components with the UMAT's DDSDDE. */
#ifndef POINT_SOLVE_H
#define POINT_SOLVE_H

#include <stdio.h>

#include "../material/material_point.h"
#include "point_scene.h"

typedef struct {
  int      newton;
  int      umat_calls;    /* the UMAT calls of the step */
  double   control_error; /* largest relative residual of a controlled component at convergence */
  double             pnewdt;
  MaterialFailedCall failed; /* the call that asked for a smaller step (failed.have) */
} PointStepResult;

/* The target of equation i at segment time t (lambda: fraction of the ramp done), from the segment's
 * start values. */
double point_target(const Segment *sg, int i, const double start[6], double lambda, double t);
/* Linear interpolation of a table column at time t (held constant outside the table). */
double point_interp(const Segment *sg, int col, double t);
/* One step of length dt from the committed call 'cur' to the targets, the UMAT under step control c: deps in
 * (predictor) and out; 0 when converged ('next' holds the converged call), 1 otherwise (res says why). */
int point_mixed_step(const UmatMaterial *mat, UmatControl c, const Segment *sg, const UmatCall *cur, const double target[6],
                     double dt, double deps[6], UmatCall *next, PointStepResult *res);
/* Worst relative difference between DDSDDE and central differences of STRESS in DSTRAN. */
double point_tangent_check(const UmatMaterial *mat, UmatControl c, const UmatCall *cur, const UmatCall *next);
/* p = -tr(sigma)/3 and q (von Mises) of a stress with n components. */
void point_invariants(const double s[6], int n, double *p, double *q);

#endif
