/* The one stage runner of every scene kind (material point, finite elements, indentation).
 *
 * A scene is a list of stages. The runner divides each stage into steps (fixed plan or adaptive with the
 * scene's error measure, step_control.h), applies instant loads as a first zero-time step, cuts a step back
 * when it fails or is too inaccurate (one policy), lands on events ('until': depth, load, p, q) and on the
 * output times, stops on a viscoplastic rate, writes the history (its own rows are the solver's columns),
 * prints progress, writes checkpoints (the runner's state and the solver's, one set, kept until the next is
 * complete) and restarts from them, and writes a replay of a UMAT call that failed for good.
 *
 * The physics is the solver's: a StepSolver solves one step from its committed state (SNES for FE scenes,
 * the semismooth Newton of the contact module for indentation, the mixed-control Newton for a point) and
 * reports what the runner needs to judge it. */
#ifndef STAGE_RUNNER_H
#define STAGE_RUNNER_H

#include <petscsys.h>
#include <stdio.h>

#include "../io/binfile.h"
#include "../io/yaml_doc.h"
#include "../material/umat_call.h"
#include "step_control.h"

/* What the runner needs of a stage. */
typedef struct {
  const char        *name;
  double             duration;
  int                instant; /* the targets jump in a first zero-time step, then are held */
  const StepControl *steps;
  StageEvent         until;
  int                must_reach; /* the until event must happen within the duration (else the run fails) */
  const char        *until_key;  /* its key in the scene, for messages (NULL: stages[s].until or segments[s].until) */
  double             event_start; /* the until quantity at the stage's start (for landing) */
  int                nout_times;  /* fields at exactly these stage times (output: {times} of a stage) */
  const double      *out_times;
  int                held;        /* the loads are constant over the stage (after an instant one's jump): only then is the
                                     time-step error of the reported quantities' change estimated (time_error_step) */
} StageView;

/* The view of stage g as it comes from the scene (the solver's stage_begin may then change it). */
void stage_view_of(const Stage *g, StageView *v);

/* The step to solve: from the committed state at total time t0 (stage time ts0) over h (0: an instant jump);
 * lambda is the fraction of the stage's ramp done at the step's end. */
typedef struct {
  int    s, first_in_stage;
  double t0, ts0, h, lambda;
  double h_prev;   /* the last accepted step's length (0: none yet) */
  UmatControl umat; /* the UMAT's own control for judging the converged state (worst_point: at the measure's tol) */
  int    want_volume_error;
  double newton_etol; /* > 0: Newton may stop once its estimated remaining error is below this fraction of the
                         step's increment (NEWTON_KAPPA x the error measure's tol); 0: the residual test only */
} StepRequest;

/* The Newton error allowed per step, as a fraction of the time-step error tolerance: small enough that the
   iteration error stays two orders below the discretisation error the measure controls (Hairer & Wanner,
   Solving ODEs II, §IV.8, stop Newton at a fraction kappa of the local error tolerance; they take 0.01-0.1). */
#define NEWTON_KAPPA 0.01

#define STEP_MAX_OUT 12
#define RUNNER_MAX_REPORT 4  /* reported quantities of a scene (StepSolver.report) */
#define RUNNER_MAX_STAGES 32 /* stages whose reported quantities are kept */
typedef struct {
  int         converged;
  const char *why;     /* when not converged */
  int         stalled; /* not converged because Newton stalled (counted apart: RunnerSummary) */
  double      pnewdt;  /* smallest PNEWDT of the UMAT calls at the converged state (large: no request) */
  int         its;     /* Newton iterations */
  double      event[EVENT_KINDS];  /* the event quantities at the step's end */
  double      progress;            /* fraction of the stage done, if the solver knows better (< 0: by time) */
  int         nout;                /* reported outputs ('output' measure), in groups */
  double      out[STEP_MAX_OUT];
  int         group[STEP_MAX_OUT];
  double      vol_err;             /* 'volume' measure: relative estimate (< 0: none) */
  int         kink;                /* the step crossed a jump of the rates the estimates rest on (an active-set
                                      change): no estimate for it, and the next starts afresh */
} StepOutcome;

#include "history_columns.h" /* RunnerRow, HistColumn: the history's shared columns and the solver's */

/* Errors of the callbacks (docs/driver.md, "Error codes"): every callback but umat_calls returns a PetscErrorCode.
 * - A PETSc failure propagates as PETSc's own code (PetscCall): the runner returns it with err empty, and main
 *   prints PETSc's message (exit status 1).
 * - A failure the user must act on (a key of the scene, a file, a contact reaching the edge of its surface) is
 *   reported by the callbacks that take err with STEP_FAIL: the project's message, naming the file, the key, the
 *   value and what was expected, goes into err and the callback returns STEP_ERR_REPORTED; the runner ends the run
 *   with that message and exit status 1, never a PETSc traceback.
 * - The callbacks that write or read the run's files and take no err (promote, save, load, save_shared,
 *   load_shared, resume) return nonzero on any failure, and the runner reports it by the file's name; save and
 *   load may also say a checkpoint file is bad by its BinFile's ok.
 * - replay runs after a step failed for good: its failure only adds a note to that message. */
#include "run_status.h" /* STEP_ERR_REPORTED, STEP_FAIL, stage_runner_status */

typedef struct {
  void       *ctx;
  const char *kind; /* for messages: "fe", "indentation", "point" */
  int         nstage;
  MPI_Comm    comm;
  /* Stage s begins (resumed: from a checkpoint, midway): the solver records its start values. */
  PetscErrorCode (*stage_begin)(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen);
  /* Solve the step from the committed state; o->converged says whether it did (a step that did not converge is
   * no error: the runner cuts it back). */
  PetscErrorCode (*solve)(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen);
  /* Commit the converged step. */
  PetscErrorCode (*accept)(void *ctx, const StepRequest *rq, char *err, size_t errlen);
  /* Optional: after each accepted step, a check that can stop the run (STEP_FAIL). */
  PetscErrorCode (*check)(void *ctx, double t, char *err, size_t errlen);
  /* Output: the history's own columns after the shared ones (rank 0 writes; history_columns.h), with
   * history_prepare (may be NULL) called before each row; the stage's name (for the first row, before its stage
   * begins); the solver's part of the progress line, fields. */
  const HistColumn *columns;
  int               ncolumns;
  void (*history_prepare)(void *ctx);
  const char *(*stage_name)(void *ctx, int s);
  PetscErrorCode (*progress)(void *ctx, char *buf, size_t n);
  /* the fields at time t (may be NULL); report: t is a time the run reports at (its start, a stage's output time or
     end), not one only output.fields_every asks for (fe_estimate.h: the indicator's history keeps report times) */
  PetscErrorCode (*write_fields)(void *ctx, double t, int report, char *err, size_t errlen);
  PetscErrorCode (*promote)(void *ctx);                                           /* the solver's .part files; may be NULL */
  /* Checkpoint: the solver's state (this rank's file). */
  PetscErrorCode (*save)(void *ctx, BinFile *f);
  PetscErrorCode (*load)(void *ctx, BinFile *f);
  /* After a step failed for good: write a replay of the failing UMAT call into dir; append to msg (the runner
   * keeps msg, the failure's own message, whatever this returns). */
  PetscErrorCode (*replay)(void *ctx, const char *dir, char *msg, size_t n);
  /* Totals for the last line. */
  long (*umat_calls)(void *ctx);
  /* After every rank has loaded its checkpoint file (load reads only, so a rank whose file is bad cannot
   * leave the others in a collective call): the collective work of a resumed state. May be NULL. */
  PetscErrorCode (*resume)(void *ctx);
  /* Optional, collective: the solver's distributed state in a file of its own (path), in an order that does not
   * depend on the partition, and its reading; with them a run restarts on any number of ranks (save and load then
   * hold only what every rank has alike). FE and indentation scenes: a PETSc HDF5 file. */
  PetscErrorCode (*save_shared)(void *ctx, const char *path);
  PetscErrorCode (*load_shared)(void *ctx, const char *path);
  /* Optional: what the scene reports (nreport values, named report_names: an indenter's depth and load, an FE
   * scene's mean strain), at the committed state; the runner keeps them at the start and at every stage's end
   * (RunnerSummary), the quantities whose mesh error a run states (docs/adapt.md). */
  int         nreport;
  const char *report_names[RUNNER_MAX_REPORT];
  void (*report)(void *ctx, double *v);
  /* Optional: the outputs ('output' measure, as solve reports them in StepOutcome.out) at the committed state, read
   * at the run's start: the first stage's change is counted from them (relative_to: stage, error.floor). NULL: they
   * start at 0 (an indenter's depth and load, an FE scene's mean strain). */
  void (*outputs)(void *ctx, double *out);
} StepSolver;

typedef struct {
  const char        *outdir;      /* "" or NULL: no files at all (the extremes sweep) */
  const char        *scene_file;  /* hashed into checkpoints: a restart needs the same scene */
  int                checkpoint_every, restart, max_steps, progress_every, fields_every, quiet;
  StepGains          gains;       /* the step controller's exponents (step_control.h); alpha 0: the PI default */
  const char        *part_file;   /* another new file of the run, named *.part until its first step (the mesh) */
  struct RunnerSummary_ *summary; /* if set: a copy of the run's summary */
  const char        *mesh_file;   /* the run's mesh file, hashed into checkpoints: a restart needs the same mesh (NULL: none) */
} RunnerOptions;

typedef struct RunnerSummary_ {
  int    steps, cutbacks, its, rejected_error, failed, stopped;
  /* the cutbacks by their cause besides the error measure: the UMAT asked (PNEWDT < 1 at the converged state), Newton
     stalled (contact: -indent_stall_window), Newton did not converge otherwise (its limit, a cycling active set, the
     linear solver) */
  int    rejected_umat, rejected_stalled, rejected_unconverged;
  int    jumps; /* steps accepted across a jump of the outputs: shorter ones did not lower the error estimate (a snap at a
                   limit point of the load's path; docs/driver.md, Error measures) */
  int    ran;      /* the run got past its set-up (the history's first row written, or a checkpoint read): only then is
                      there a summary to write */
  int    replaced; /* the run's files replaced an earlier run's (its first step done, or a restart continuing them) */
  long   umat_calls; /* all ranks */
  double t, wall;
  /* the scene's reported quantities (StepSolver.report) at the start (0) and at the end of stage s (s + 1), for
     the stages done (nstages_done) */
  int         nreport, nstages_done;
  const char *report_names[RUNNER_MAX_REPORT];
  double      report[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT];
  /* the time-step error of their change over stage s (index s + 1; docs/adapt.md, "The time-step error"): the
     sum of the steps' local error estimates over a held stage (StageView.held); NAN where none is made */
  double      time_error_change[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT];
} RunnerSummary;

/* Run every stage. Returns the run's status: 0; 1 (a step failed for good, an event was missed, a file could not
 * be written, a callback's STEP_FAIL) or 2 (bad input found at run time: a restart that does not match) with err
 * filled; or a PETSc error code (> 2) with err empty. */
int stage_runner_run(StepSolver *sv, const RunnerOptions *opt, RunnerSummary *sum, char *err, size_t errlen);

#endif
