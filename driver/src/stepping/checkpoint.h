/* Checkpoints of the stage runner: where the run is (RunState) and the solver's state, one file per rank,
 * as one set. A set is named by its step (checkpoint.<step>.rank<r>.bin) and becomes the one a restart
 * uses only when every rank has written its file completely: then rank 0 replaces checkpoint.latest (a
 * small text file, written to a temporary name, synced and renamed). The previous set is deleted only
 * after that, so a kill at any moment leaves a complete set to restart from. A restart reads the set that
 * checkpoint.latest names on every rank and checks it (magic, ranks, the scene's hash) on all ranks
 * before anything is written. */
#ifndef STEPPING_CHECKPOINT_H
#define STEPPING_CHECKPOINT_H

#include "stage_runner.h"

/* Where a run is (plain values only: written as one block). */
typedef struct {
  int    stage, in_stage, first_in_stage, step, its, cutbacks, cut_in_step, rejected_error;
  int    rejected_umat, rejected_stalled, rejected_unconverged; /* the cutbacks by their cause (RunnerSummary) */
  int    jumps;                                                 /* steps accepted across a jump (RunnerSummary) */
  int    pending_instant, k_planned, cut_in_plan, next_stage_time, have_prev, nout, kink;
  double t, t_stage, dt, landing, event_prev, h_prev, reject_ratio, reject_size, ratio_prev;
  double out_prev[STEP_MAX_OUT], dout_prev[STEP_MAX_OUT], out_scale[STEP_MAX_OUT];
  double out_start[STEP_MAX_OUT]; /* the outputs at the stage's start (the 'output' measure relative to the stage) */
  long   history_offset;
  double report[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT]; /* the reported quantities at the start and stage ends */
  unsigned long long mesh_hash;                            /* of the run's mesh file (0: none): a restart needs the same */
  /* the time-step error of the reported quantities (stage_runner.c, time_error_step): the last step's values and
     increment, the sum of the steps' local errors over the stage, kept at each stage's end (NAN: not a held stage) */
  int    rep_have_prev;
  double rep_prev[RUNNER_MAX_REPORT], drep_prev[RUNNER_MAX_REPORT], rep_h_prev;
  double terr_stage[RUNNER_MAX_REPORT], terr_change[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT];
} RunState;

/* Write the set for st->step; *last: the step of the previous set (deleted once the new one is in place). */
int checkpoint_write(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen);
/* Before anything of a restarted run is set up or opened (rank 0): whether the latest checkpoint is there, whole in
 * its rank-0 head and written for this scene file and this mesh file (opt->scene_file, opt->mesh_file). 0; 1 (missing
 * or damaged) or 2 (another scene, mesh or format) with checkpoint_read's message in err. */
int checkpoint_precheck(const RunnerOptions *opt, char *err, size_t errlen);
/* Read the latest set into st and the solver. Returns 0, 1 (missing or damaged) or 2 (another scene). */
int checkpoint_read(StepSolver *sv, const RunnerOptions *opt, RunState *st, int *last, char *err, size_t errlen);

#endif
