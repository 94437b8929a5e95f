#include "fe_stepper.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#include <petscviewerhdf5.h>

#include "../fe/fe_state.h"
#include "../point/point_solve.h"

const char *const fe_common_xyz[3] = {"x", "y", "z"};

/* The memory high-water mark of the run's ranks [MB]: mb[0] the largest rank's, mb[1] the sum over the ranks. */
PetscErrorCode fe_common_max_rss(MPI_Comm comm, double mb[2]) {
  struct rusage ru;
  PetscFunctionBeginUser;
  getrusage(RUSAGE_SELF, &ru);
  mb[0] = mb[1] = ru.ru_maxrss / 1024.0; /* kB on Linux */
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[0], 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &mb[1], 1, MPI_DOUBLE, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

HistValue fe_common_umat_calls(const void *ctx, const RunnerRow *row, int k) {
  return (HistValue){.i = (long)fe_problem_diag(((const FeCommon *)ctx)->p)->umat_calls};
}
HistValue fe_common_wall(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = row->wall}; }
HistValue fe_common_reaction(const void *ctx, const RunnerRow *row, int k) {
  return (HistValue){.r = fe_problem_diag(((const FeCommon *)ctx)->p)->reaction[k]};
}
const char *fe_common_stage_name(void *ctx, int s) { return ((FeCommon *)ctx)->sc->stage[s].name; }

PetscErrorCode fe_common_init(FeCommon *c, FeScene *sc, FeProblem *p, const RunnerOptions *opt) {
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(c, sizeof *c));
  c->sc = sc, c->p = p, c->fields = opt->outdir && opt->outdir[0] ? PETSC_TRUE : PETSC_FALSE;
  c->quantiles = sc->indenter ? PETSC_FALSE : PETSC_TRUE;
  for (int k = 0; k < FE_MAX_GROUPS; k++) c->now[k] = sc->pressure0[k];
  if (c->fields) PetscCall(fe_output_open(p, opt->outdir, opt->restart ? PETSC_TRUE : PETSC_FALSE, &c->out));
  PetscCall(fe_problem_stats(p, sc->axis, &c->stats, PETSC_FALSE, c->quantiles));
  PetscCall(fe_problem_reactions(p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_finish(FeCommon *c) {
  PetscFunctionBeginUser;
  if (c->fields) PetscCall(fe_output_close(c->p, &c->out));
  PetscFunctionReturn(0);
}


void fe_common_stage_begin(FeCommon *c, int s, int resumed, StageView *v) {
  Stage *g = &c->sc->stage[s];
  if (!resumed)
    for (int k = 0; k < c->sc->npressure; k++) c->start[k] = c->now[k];
  double p, q;
  point_invariants(c->stats.stress_mean, 6, &p, &q);
  stage_view_of(g, v);
  v->event_start = g->until.kind == EVENT_P_ABOVE ? p : q;
  /* held: an instant stage after its jump, or every pressure and traction kept or ramped to its value at the start */
  const StageLoads *l = &c->sc->loads[s];
  v->held = 1;
  for (int k = 0; k < c->sc->npressure && !g->instant; k++)
    if (l->fn[k].kind != TF_HOLD && (l->fn[k].kind != TF_RAMP || !(isnan(l->pressure[k]) || l->pressure[k] == c->start[k]))) v->held = 0;
}

PetscErrorCode fe_common_set_loads(FeCommon *c, const StepRequest *rq) {
  const StageLoads *g = &c->sc->loads[rq->s];
  PetscFunctionBeginUser;
  PetscReal pressure[FE_MAX_GROUPS];
  for (int k = 0; k < c->sc->npressure; k++) {
    double target = isnan(g->pressure[k]) ? c->start[k] : g->pressure[k];
    pressure[k]   = stage_pressure(g, k, c->start[k], target, rq->lambda, rq->ts0 + rq->h);
  }
  PetscCall(fe_problem_set_pressures(c->p, c->sc->npressure, pressure));
  fe_problem_set_step(c->p, rq->t0 + rq->h, rq->h);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_observe(FeCommon *c, const StepRequest *rq, StepOutcome *o) {
  double p, q;
  PetscFunctionBeginUser;
  PetscCall(fe_problem_stats(c->p, c->sc->axis, &c->stats, PETSC_TRUE, c->quantiles));
  point_invariants(c->stats.stress_mean, 6, &p, &q);
  o->event[EVENT_P_ABOVE] = p, o->event[EVENT_Q_ABOVE] = o->event[EVENT_Q_BELOW] = q;
  o->event[EVENT_EVP_RATE_BELOW] = rq->h > 0 ? c->stats.evp_rate : INFINITY;
  if (rq->want_volume_error) PetscCall(fe_state_volume_error(c->p, rq->h, rq->h_prev, &o->vol_err));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_accept(FeCommon *c, const StepRequest *rq) {
  PetscFunctionBeginUser;
  for (int k = 0; k < c->sc->npressure; k++) c->now[k] = fe_problem_pressure(c->p, k);
  PetscCall(fe_problem_reactions(c->p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_fields(FeCommon *c, Vec U, double t, int report, char *err, size_t errlen) {
  PetscFunctionBeginUser;
  if (!c->fields) PetscFunctionReturn(0);
  if (c->out.nout > 0 && c->out.times[c->out.nout - 1] == t) PetscFunctionReturn(0); /* already written at this time */
  if (fe_output_write(c->p, U, t, report ? PETSC_TRUE : PETSC_FALSE, &c->out)) STEP_FAIL(err, errlen, "%s: cannot write the fields at t = %g s", c->out.dir, t);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_promote(FeCommon *c) {
  PetscFunctionBeginUser;
  if (c->fields) PetscCall(fe_output_promote(c->p, &c->out));
  PetscFunctionReturn(0);
}

/* A write or read that fails leaves f->ok 0 (the runner names the file). */
PetscErrorCode fe_common_save(FeCommon *c, BinFile *f) {
  PetscFunctionBeginUser;
  binfile_write(f, c->start, sizeof(double), FE_MAX_GROUPS);
  binfile_write(f, c->now, sizeof(double), FE_MAX_GROUPS);
  PetscInt nout = c->fields ? c->out.nout : 0;
  binfile_write(f, &nout, sizeof nout, 1);
  if (nout) binfile_write(f, c->out.times, sizeof(PetscReal), (size_t)nout);
  PetscBool have_devp = fe_state_have_devp(c->p);
  binfile_write(f, &have_devp, sizeof have_devp, 1);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_load(FeCommon *c, BinFile *f) {
  PetscInt nout = 0;
  PetscFunctionBeginUser;
  binfile_read(f, c->start, sizeof(double), FE_MAX_GROUPS);
  binfile_read(f, c->now, sizeof(double), FE_MAX_GROUPS);
  binfile_read(f, &nout, sizeof nout, 1);
  if (!f->ok || nout < 0 || nout > 10000000) {
    f->ok = 0;
    PetscFunctionReturn(0);
  }
  PetscCall(PetscFree(c->saved_times));
  PetscCall(PetscMalloc1(nout + 1, &c->saved_times));
  c->nsaved = nout;
  binfile_read(f, c->saved_times, sizeof(PetscReal), (size_t)nout);
  PetscBool have_devp = PETSC_FALSE;
  binfile_read(f, &have_devp, sizeof have_devp, 1);
  fe_state_set_have_devp(c->p, have_devp);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_shared_open(FeCommon *c, const char *path, PetscBool write, PetscViewer *v) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5Open(PetscObjectComm((PetscObject)fe_problem_dm(c->p)), path, write ? FILE_MODE_WRITE : FILE_MODE_READ, v));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_resume(FeCommon *c) {
  PetscFunctionBeginUser;
  if (c->fields) PetscCall(fe_output_resume(&c->out, c->nsaved, c->saved_times));
  PetscCall(PetscFree(c->saved_times));
  PetscCall(fe_problem_set_pressures(c->p, FE_MAX_GROUPS, c->now));
  PetscCall(fe_problem_stats(c->p, c->sc->axis, &c->stats, PETSC_FALSE, c->quantiles));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_common_replay(FeCommon *c, const char *dir, char *msg, size_t n) {
  const MaterialFailedCall *f = fe_problem_failed_call(c->p);
  PetscMPIInt               rank;
  PetscFunctionBeginUser;
  if (!f) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)fe_problem_dm(c->p)), &rank));
  char rp[1100];
  snprintf(rp, sizeof rp, "%s/failed_call.rank%d.yaml", dir, rank);
  if (!material_failed_call_write(f, rp, msg)) {
    size_t len = strlen(msg);
    snprintf(msg + len, n - len, "; the failing UMAT call (element %d, point %d) is replayed by: driver -input %s", f->in.noel,
             f->in.npt, rp);
  }
  PetscFunctionReturn(0);
}
