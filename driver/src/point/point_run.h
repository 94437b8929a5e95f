/* Running a material-point scene: segments of mixed stress/strain control, solved step by step by
 * Newton on the unknown strain components with the UMAT's DDSDDE, with cutbacks, end conditions,
 * CSV history output and an optional check of DDSDDE against finite differences. */
#ifndef POINT_RUN_H
#define POINT_RUN_H

#include "point_scene.h"

typedef struct {
  int    steps, cutbacks, failed;
  double worst_tangent_error; /* with check_tangent */
  double worst_control_error; /* largest relative residual of a controlled component at convergence */
  double final_stress[6];     /* stress at the end of the run */
  int    finite;              /* every stress and state variable stayed finite */
  double wall;                /* seconds spent in the run (no start-up, no scene reading) */
} PointSummary;

/* Returns 0 when every segment completed; 1 with err filled otherwise (and, if a UMAT call failed for
 * good, a replay scene written into the output directory, named in err). */
int point_run(const PointScene *sc, PointSummary *summary, char *err, size_t errlen);

/* mkdir -p; 0 on success. */
int make_directories(const char *path);

#endif
