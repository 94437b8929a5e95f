/* Checkpoints of a finite-element run: one file per rank with where the run is (stage, times, steps,
 * loads, output times, history offset), the displacement and the state of every quadrature point;
 * written atomically (a temporary name, then rename), read by -restart on the same number of ranks. */
#ifndef FE_CHECKPOINT_H
#define FE_CHECKPOINT_H

#include "fe_problem.h"
#include "fe_scene.h"

/* Where a run is: what a checkpoint saves (with U and the state of every quadrature point). */
typedef struct {
  int        step, stage, in_stage, pending_instant, total_cutbacks;
  double     t, t_stage, dt, start[FE_MAX_GROUPS], pressure_now[FE_MAX_GROUPS];
  PetscInt   nout;
  PetscReal *out_times;
} Progress;


int write_checkpoint(const FeScene *sc, FeProblem *p, Vec U, const Progress *pr, long history_offset, char *err,
                     size_t errlen);
int read_checkpoint(const FeScene *sc, FeProblem *p, Vec U, Progress *pr, long *history_offset, char *err,
                    size_t errlen);

#endif
