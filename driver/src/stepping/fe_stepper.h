/* Finite-element scenes on the stage runner: the SNES step solver (fe_stepper.c), the indentation step
 * solver around the contact module's semismooth Newton (indent_stepper.c), and what the two share
 * (fe_common.c): the boundary loads of a stage, the volume statistics that events and the error measures
 * look at, field output and the problem's part of a checkpoint. */
#ifndef FE_STEPPER_H
#define FE_STEPPER_H

#include "../contact/indent_scene.h"
#include "../fe/fe_output.h"
#include "../fe/fe_problem.h"
#include "../fe/fe_scene.h"
#include "stage_runner.h"

typedef struct {
  FeScene   *sc;
  FeProblem *p;
  FeOutput   out;
  FeStats    stats;                    /* of the last solved state (trial) or, after a commit, the committed one */
  double     start[FE_MAX_GROUPS];     /* the loads at the stage's start */
  double     now[FE_MAX_GROUPS];       /* the loads of the committed state */
  PetscBool  fields;                   /* write fields.h5 */
  PetscBool  quantiles;                /* per-frame quantiles in the statistics (the FE history has them) */
  PetscReal *saved_times;              /* a checkpoint's output times, until every rank has read its file */
  PetscInt   nsaved;
} FeCommon;

/* The FE solver's options (-fe_*), declared and read in one place (io/options.h). */
typedef struct {
  PetscInt  refactor_its, gamg_above;
  PetscBool coo, predictor;
} FeSolverOptions;
PetscErrorCode fe_solver_options(MPI_Comm comm, FeSolverOptions *o);

/* Run the stages of an FE scene (SNES) or of an indentation scene on the set-up problem p. */
int fe_stepper_run(FeScene *sc, FeProblem *p, const RunnerOptions *opt, char *err, size_t errlen);
int indent_stepper_run(FeScene *sc, IndentScene *is, FeProblem *p, const RunnerOptions *opt, char *err, size_t errlen);

/* Shared by the two. */
/* The history's cost columns of both (umat_calls, wall, reaction_x/y/z) and a stage's name: the solver's ctx
   begins with its FeCommon. */
HistValue   fe_common_umat_calls(const void *ctx, const RunnerRow *row, int k);
HistValue   fe_common_wall(const void *ctx, const RunnerRow *row, int k);
HistValue   fe_common_reaction(const void *ctx, const RunnerRow *row, int k);
const char *fe_common_stage_name(void *ctx, int s);
extern const char *const fe_common_xyz[3];
#define FE_COMMON_COST_COLUMNS \
  {"umat_calls", "%ld", 1, NULL, fe_common_umat_calls, NULL, NULL}, {"wall", "%.4f", 1, NULL, fe_common_wall, NULL, NULL}, \
    {"reaction", "%.12g", 3, fe_common_xyz, fe_common_reaction, NULL, NULL}
PetscErrorCode fe_common_init(FeCommon *c, FeScene *sc, FeProblem *p, const RunnerOptions *opt);
PetscErrorCode fe_common_finish(FeCommon *c);
PetscErrorCode fe_common_max_rss(MPI_Comm comm, double mb[2]);
void           fe_common_stage_begin(FeCommon *c, int s, int resumed, StageView *v);
PetscErrorCode fe_common_set_loads(FeCommon *c, const StepRequest *rq);
/* The UMAT's own step control (worst_point) for the converged state: the step's, or PROPS tol; 0: off. */
/* p, q and the viscoplastic rate of the solved state; the volume error if asked. */
PetscErrorCode fe_common_observe(FeCommon *c, const StepRequest *rq, StepOutcome *o);
/* After a commit: the loads now in force, the supports' reactions (all ranks). */
PetscErrorCode fe_common_accept(FeCommon *c, const StepRequest *rq);
PetscErrorCode fe_common_fields(FeCommon *c, Vec U, double t, int report, char *err, size_t errlen); /* STEP_FAIL: a file that cannot be written */
PetscErrorCode fe_common_promote(FeCommon *c);
/* A checkpoint: the loads and output times (the same on every rank: in each rank's file), and the shared
 * file (PETSc HDF5) that holds the fields and states in the serial mesh's order (fe/fe_state.h), so that a run
 * restarts on any number of ranks. */
PetscErrorCode fe_common_save(FeCommon *c, BinFile *f); /* a file that cannot be written or read: f->ok 0 */
PetscErrorCode fe_common_load(FeCommon *c, BinFile *f); /* reads only (no collective call) */
PetscErrorCode fe_common_shared_open(FeCommon *c, const char *path, PetscBool write, PetscViewer *v);
PetscErrorCode fe_common_resume(FeCommon *c);           /* collective: loads and statistics */
PetscErrorCode fe_common_replay(FeCommon *c, const char *dir, char *msg, size_t n);

#endif
