/* FE scenes: each step solved by SNES (Newton on the consistent tangent, full steps by default) from the
 * committed state, extrapolated along the last increment within a stage. */
#include "fe_stepper.h"

#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>

#include "../fe/fe_state.h"

typedef struct {
  FeCommon  c;
  SNES      snes;
  Mat       J;
  Vec       U, R, U0, dU; /* iterate, residual, committed, last increment (the predictor) */
  PetscBool have_rate, predictor;
} FeSolver;

static int stage_begin(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen) {
  FeSolver *f = ctx;
  fe_common_stage_begin(&f->c, s, resumed, v);
  if (!resumed) f->have_rate = PETSC_FALSE; /* no extrapolation across a change of loading */
  return 0;
}

static int solve(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen) {
  FeSolver           *f = ctx;
  FeProblem          *p = f->c.p;
  SNESConvergedReason reason;
  PetscInt            its;
  if (fe_common_set_loads(&f->c, rq)) return 1;
  VecCopy(f->U0, f->U);
  if (f->predictor && f->have_rate && rq->h > 0 && rq->h_prev > 0) VecAXPY(f->U, rq->h / rq->h_prev, f->dU);
  p->umat_tol = 0; /* Newton iterates without the UMAT's error control */
  PetscErrorCode ierr;
  if ((ierr = SNESSolve(f->snes, NULL, f->U)) || (ierr = SNESGetConvergedReason(f->snes, &reason)) || (ierr = SNESGetIterationNumber(f->snes, &its))) {
    err[0] = '\0'; /* main prints PETSc's message */
    return (int)ierr;
  }
  o->converged = reason > 0, o->its = (int)its, o->why = SNESConvergedReasons[reason];
  if (!o->converged) return 0;
  PetscReal tol = fe_common_umat_tol(&f->c, rq);
  PetscBool same = PETSC_FALSE;
  if (p->ddsdde_valid) VecEqual(f->U, p->ddsdde_u, &same);
  if (tol > 0 || !same) { /* the converged state again, with the UMAT's PNEWDT on */
    p->umat_tol = tol;
    if (fe_residual(f->snes, f->U, f->R, p)) return 1;
    p->umat_tol = 0;
  }
  o->pnewdt = p->min_pnewdt;
  if (fe_common_observe(&f->c, rq, o)) return 1;
  o->nout = 6;
  for (int k = 0; k < 6; k++) o->out[k] = f->c.stats.strain_mean[k], o->group[k] = 0;
  return 0;
}

static int accept(void *ctx, const StepRequest *rq, char *err, size_t errlen) {
  FeSolver *f = ctx;
  if (fe_state_commit(f->c.p, rq->h)) return 1;
  VecWAXPY(f->dU, -1.0, f->U0, f->U);
  VecCopy(f->U, f->U0);
  f->have_rate = rq->h > 0;
  fe_common_accept(&f->c, rq);
  return 0;
}

static void history_header(void *ctx, FILE *fp) {
  FeSolver *f  = ctx;
  FeScene  *sc = f->c.sc;
  fprintf(fp, "time,stage,step,dt,newton_its,cutbacks");
  for (int g = 0; g < sc->npressure; g++) fprintf(fp, ",%s_%s", strchr(sc->pressure_group[g], '.') ? "traction" : "pressure", sc->pressure_group[g]);
  fprintf(fp, ",eps_11,eps_22,eps_33,eps_12,eps_13,eps_23,sig_11,sig_22,sig_33,sig_12,sig_13,sig_23,eps_spread,evp_rate");
  const char *fr[2] = {"hard", "soft"}, *st[6] = {"mean", "min", "q1", "median", "q3", "max"};
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 6; k++) fprintf(fp, ",evp33_%s_%s", fr[i], st[k]);
  fprintf(fp, ",umat_calls,wall,reaction_x,reaction_y,reaction_z\n");
}

static void history_row(void *ctx, FILE *fp, const RunnerRow *row) {
  FeSolver      *f = ctx;
  const FeStats *s = &f->c.stats;
  FeProblem     *p = f->c.p;
  fprintf(fp, "%.17g,%d,%d,%.17g,%d,%d", row->t, row->stage, row->step, row->dt, row->its, row->cutbacks);
  for (int k = 0; k < f->c.sc->npressure; k++) fprintf(fp, ",%.12g", f->c.now[k]);
  for (int i = 0; i < 6; i++) fprintf(fp, ",%.15g", s->strain_mean[i]);
  for (int i = 0; i < 6; i++) fprintf(fp, ",%.15g", s->stress_mean[i]);
  fprintf(fp, ",%.6g,%.6g", s->strain_spread, s->evp_rate);
  for (int i = 0; i < 2; i++)
    for (int k = 0; k < 6; k++) fprintf(fp, ",%.12g", s->frame_evp[i][k]);
  fprintf(fp, ",%ld,%.4f,%.12g,%.12g,%.12g\n", (long)p->umat_calls, row->wall, p->reaction[0], p->reaction[1], p->reaction[2]);
}

static void progress(void *ctx, char *buf, size_t n) {
  FeSolver *f = ctx;
  PetscReal rnorm = 0;
  SNESGetFunctionNorm(f->snes, &rnorm);
  snprintf(buf, n, "|R| %.2e ", (double)rnorm);
}

static int write_fields(void *ctx, double t, char *err, size_t errlen) {
  FeSolver *f = ctx;
  return fe_common_fields(&f->c, f->U0, t, err, errlen);
}

static int promote(void *ctx) { return fe_common_promote(&((FeSolver *)ctx)->c); }

static int save(void *ctx, BinFile *b) {
  FeSolver          *f = ctx;
  PetscInt           n;
  const PetscScalar *d;
  if (fe_common_save(&f->c, f->U0, b)) return 1;
  binfile_write(b, &f->have_rate, sizeof f->have_rate, 1);
  VecGetLocalSize(f->dU, &n);
  VecGetArrayRead(f->dU, &d);
  binfile_write(b, d, sizeof(PetscScalar), (size_t)n);
  VecRestoreArrayRead(f->dU, &d);
  return !b->ok;
}

static int load(void *ctx, BinFile *b) {
  FeSolver    *f = ctx;
  PetscInt     n;
  PetscScalar *d;
  if (fe_common_load(&f->c, f->U0, b)) return 1;
  binfile_read(b, &f->have_rate, sizeof f->have_rate, 1);
  VecGetLocalSize(f->dU, &n);
  VecGetArray(f->dU, &d);
  binfile_read(b, d, sizeof(PetscScalar), (size_t)n);
  VecRestoreArray(f->dU, &d);
  return !b->ok;
}

static int resume(void *ctx) {
  FeSolver *f = ctx;
  return VecCopy(f->U0, f->U) || fe_common_resume(&f->c);
}

static void replay(void *ctx, const char *dir, char *msg, size_t n) { fe_common_replay(&((FeSolver *)ctx)->c, dir, msg, n); }

static long umat_calls(void *ctx) { return (long)((FeSolver *)ctx)->c.p->umat_calls; }

/* SNES on the element loop: a direct solver by default (LU; MUMPS on more than one rank), full Newton
 * steps on the consistent tangent (cut back by the runner when they fail), as Abaqus does;
 * -snes_linesearch_type bt restores a backtracking line search. */
static PetscErrorCode solver_setup(FeSolver *f) {
  FeScene    *sc = f->c.sc;
  FeProblem  *p  = f->c.p;
  MPI_Comm    comm = PetscObjectComm((PetscObject)p->dm);
  KSP         ksp;
  PC          pc;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(SNESCreate(comm, &f->snes));
  PetscCall(DMCreateMatrix(p->dm, &f->J));
  PetscCall(DMCreateGlobalVector(p->dm, &f->U));
  Vec *v[] = {&f->R, &f->U0, &f->dU, NULL};
  for (int k = 0; v[k]; k++) PetscCall(VecDuplicate(f->U, v[k]));
  PetscCall(VecZeroEntries(f->U));
  PetscCall(VecZeroEntries(f->U0));
  PetscCall(VecZeroEntries(f->dU));
  { /* rigid-body modes as the near null space, for -pc_type gamg */
    MatNullSpace rbm;
    PetscCall(DMPlexCreateRigidBody(p->dm, 0, &rbm));
    PetscCall(MatSetNearNullSpace(f->J, rbm));
    PetscCall(MatNullSpaceDestroy(&rbm));
  }
  PetscCall(SNESSetFunction(f->snes, f->R, fe_residual, p));
  PetscCall(SNESSetJacobian(f->snes, f->J, f->J, fe_jacobian, p));
  PetscCall(SNESGetKSP(f->snes, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  MPI_Comm_size(comm, &size);
  if (size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscReal pmax = 1, fref = 0; /* force scale for the absolute tolerance: the largest load on all loaded faces */
  for (int i = 0; i < sc->nstage; i++)
    for (int g = 0; g < sc->npressure; g++)
      if (!isnan(sc->stage[i].pressure[g])) pmax = PetscMax(pmax, fabs(sc->stage[i].pressure[g]));
  for (int g = 0; g < sc->npressure; g++) {
    PetscReal nrm;
    PetscCall(VecNorm(p->unit_force[g], NORM_2, &nrm));
    fref += nrm;
  }
  SNESLineSearch ls;
  PetscCall(SNESGetLineSearch(f->snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCall(SNESSetTolerances(f->snes, 1e-10 * pmax * PetscMax(fref, 1e-12), 1e-12, 1e-14, 25, 1000));
  PetscCall(SNESSetFromOptions(f->snes));
  f->predictor = PETSC_TRUE;
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-fe_predictor", &f->predictor, NULL));
  PetscFunctionReturn(0);
}

int fe_stepper_run(FeScene *sc, FeProblem *p, const RunnerOptions *opt, char *err, size_t errlen) {
  FeSolver f;
  PetscMemzero(&f, sizeof f);
  PetscErrorCode ierr = fe_common_init(&f.c, sc, p, opt);
  if (ierr || (ierr = solver_setup(&f))) {
    err[0] = '\0'; /* main prints PETSc's message */
    return (int)ierr;
  }
  if (!opt->restart) { /* the initial state: the UMAT initialises its state on a zero increment */
    p->time = 0, p->dt = 0, p->umat_tol = 0;
    if (fe_residual(f.snes, f.U, f.R, p) || fe_problem_commit(p) || fe_problem_stats(p, sc->axis, &f.c.stats, PETSC_FALSE, f.c.quantiles) ||
        fe_problem_reactions(p))
      return 1;
  }
  StepSolver sv = {&f, "fe", sc->nstage, PetscObjectComm((PetscObject)p->dm), stage_begin, solve, accept, NULL,
                   history_header, history_row, progress, write_fields, promote, save, load, replay, umat_calls, resume};
  RunnerSummary sum;
  int           rc = stage_runner_run(&sv, opt, &sum, err, errlen);
  fe_common_finish(&f.c);
  PetscPrintf(sv.comm, "fe scene %s: %d steps, %d Newton iterations, %d cutbacks (%d by the error measure), %ld UMAT calls, assembly %.2f s, wall %.2f s -> %s/history.csv\n",
              sc->name, sum.steps, sum.its, sum.cutbacks, sum.rejected_error, sum.umat_calls, p->assembly_seconds, sum.wall, opt->outdir);
  VecDestroy(&f.U), VecDestroy(&f.R), VecDestroy(&f.U0), VecDestroy(&f.dU);
  MatDestroy(&f.J);
  SNESDestroy(&f.snes);
  return rc;
}
