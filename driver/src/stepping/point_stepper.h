/* Running a material-point scene on the stage runner: each segment a stage, each step the mixed-control
 * Newton of point/point_solve. */
#ifndef POINT_STEPPER_H
#define POINT_STEPPER_H

#include "../point/point_scene.h"
#include "stage_runner.h"

typedef struct {
  int    steps, cutbacks, failed;
  long   umat_calls;          /* every UMAT call of the run (the steps tried, the tangent checks, the first) */
  double worst_tangent_error; /* with check_tangent */
  double worst_control_error; /* largest relative residual of a controlled component at convergence */
  double final_stress[6];     /* stress at the end of the run */
  int    finite;              /* every stress and state variable stayed finite */
  double wall;                /* seconds spent in the run (no start-up, no scene reading) */
} PointSummary;

/* opt may be NULL (no checkpoints, no restart). Returns 0 when every segment completed; 1 with err filled
 * otherwise (and, if a UMAT call failed for good, a replay scene written into the output directory, named
 * in err). */
int point_run(const PointScene *sc, const RunnerOptions *opt, PointSummary *summary, char *err, size_t errlen);

#endif
