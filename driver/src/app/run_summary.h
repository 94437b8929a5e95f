/* summary.json: what an FE, indentation or point run reports, machine-readable (docs/adapt.md, "summary.json"): the
 * reported quantities at every stage's end and their change over it, with their estimated mesh error when the
 * run adapted its mesh; the mesh, the counters and the cost. */
#ifndef RUN_SUMMARY_H
#define RUN_SUMMARY_H

#include "../fe/fe_scene.h"
#include "../stepping/point_stepper.h"
#include "../stepping/stage_runner.h"

/* One run on one mesh. */
typedef struct {
  RunnerSummary sum;
  long          cells, unknowns;
  double        eta;       /* the error indicator's norm: sqrt(sum over cells of eta_max^2) (fe/fe_estimate.h) */
  double        cpu;       /* CPU seconds of the run, all ranks (set-up, stages, output) */
  double        predicted; /* cells the size field written after it predicts (0: none written) */
  char          dir[512];  /* where its files are */
  int           kept;      /* 1: reused from an earlier run into the same directory, not run by this one (docs/adapt.md,
                              "Kept meshes"): cpu and the counters are that run's */
} RunInfo;

/* The estimated mesh error of each reported quantity (docs/adapt.md): at the start and each stage's end (end[s + 1])
   and of its change over stage s (change[s + 1]); have 0: no estimate (one mesh). */
typedef struct {
  int    have;
  double ratio;                                             /* the last level's predicted fall of the errors (fe_adapt.c) */
  const char *how;                                          /* how it was made, for the log and the summary */
  double end[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT];
  double change[RUNNER_MAX_STAGES + 1][RUNNER_MAX_REPORT];
} MeshError;

/* How a run ended, for its summary (docs/driver.md, "summary.json"; NULL: it completed or -max_steps stopped it,
   and its files are in place). */
typedef struct {
  const char *error; /* the run's message (NULL: no failure) */
  int         level; /* with adaptation: the level that failed (-1: none) */
  int         final; /* 1: summary.json; 0: the run has no results of its own in the directory (its first step failed;
                        an adaptation that failed before its answer was published): summary.json.part, the earlier
                        run's summary.json left in place */
} RunEnd;

/* Whether a run that ended with status rc has a summary to write: it got past its set-up (RunnerSummary.ran) and was
   not refused as bad input (rc 2). */
int run_summary_due(int rc, const RunnerSummary *s);

/* The message of a run's status rc for its summary: err, or PETSc's text of the code (err empty). */
void run_summary_error(int rc, const char *err, char *buf, size_t n);

/* Write dir/summary.json (rank 0; through summary.json.part, renamed once complete). levels: the runs, the last one
   the answer (several when the mesh was adapted; after a failure the level that failed); end: how it ended. 0, or 1
   with err filled. */
int run_summary_write(const FeScene *sc, const char *dir, const RunInfo *levels, int nlevels, const MeshError *me, const RunEnd *end,
                      char *err, size_t errlen);

/* After an FE or indentation run that failed with status rc and message err (rank 0): its summary (run_summary_write,
   the failure's stage, time and message; level: the level that failed, -1: one mesh; final as RunEnd's), written
   only when the run that failed got past its set-up (RunnerSummary.ran) and was not refused as bad input (rc 2). Its
   own failure to write is printed: err stays the run's message. */
void run_summary_failed(const FeScene *sc, const char *dir, const RunInfo *levels, int nlevels, int level, int final, int rc, const char *err);

/* Write sc->outdir/summary.json of a point run (rank 0): its stages (a point reports no quantities: each stage's
   "end" and "change" are empty), the counters (sum, the runner's), the cost (cpu: its CPU seconds) and the point's
   own: the final stress, whether every value stayed finite, the worst control and tangent errors (null: not
   checked); end: how it ended (as for run_summary_write). 0, or 1 with err filled. */
int run_summary_point(const PointScene *sc, const PointSummary *ps, const RunnerSummary *s, double cpu, const RunEnd *end, char *err,
                      size_t errlen);

/* Print the reported quantities of the last level with their mesh errors (rank 0). */
void run_summary_print(const FeScene *sc, const RunInfo *last, const MeshError *me);

#endif
