/* FE scenes: each step solved by SNES (Newton on the consistent tangent, full steps by default) from the
 * committed state, extrapolated along the last increment within a stage. */
#include "fe_stepper.h"

#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "../fe/fe_state.h"
#include "../io/options.h"

typedef struct {
  FeCommon  c;
  SNES      snes;
  Mat       J;
  Vec       U, R, U0, dU; /* iterate, residual, committed, last increment (the predictor) */
  PetscBool have_rate, predictor;
  /* the factorisation (or GAMG hierarchy) kept across Newton iterations and steps while the Krylov solver
     around it converges fast: rebuilt when a linear solve took more than refactor_its iterations on average,
     at a stage's start, and before retrying a step whose lagged solve failed (-fe_refactor_its 0: every
     iteration, as a plain direct solve); for an iterative preconditioner (GAMG) whose fresh set-up itself
     needs many iterations, when they exceed twice those of the first solve on a fresh one (fresh_its) */
  PetscInt  refactor_its;
  PetscReal fresh_its;
  PetscBool refactor;
  long      lin_its, setups;
  clock_t   cpu0; /* the process's CPU clock at the start of the run */
} FeSolver;

static PetscErrorCode stage_begin(void *ctx, int s, int resumed, StageView *v, char *err, size_t errlen) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  fe_common_stage_begin(&f->c, s, resumed, v);
  if (!resumed) f->have_rate = PETSC_FALSE; /* no extrapolation across a change of loading */
  f->refactor = PETSC_TRUE;                 /* a new load: a new tangent */
  PetscFunctionReturn(0);
}

/* One SNES solve of the step from the (extrapolated) committed state. With a lagged preconditioner it is
 * rebuilt once at the first Jacobian of this solve (lag -2) or reused (lag -1); a failed solve on a reused
 * one (a linear solve that did not converge) is retried once rebuilding it at every Newton iteration (lag 1: plain Newton with a direct solve), so
 * that lagging never costs a cutback that plain LU would not. */
static PetscErrorCode lagged_solve(FeSolver *f, const StepRequest *rq, SNESConvergedReason *reason, PetscInt *its) {
  PetscInt lag, lits;
  PetscFunctionBeginUser;
  for (int attempt = 0; attempt < 2; attempt++) {
    PetscCall(VecCopy(f->U0, f->U));
    if (f->predictor && f->have_rate && rq->h > 0 && rq->h_prev > 0) PetscCall(VecAXPY(f->U, rq->h / rq->h_prev, f->dU));
    if (f->refactor_its > 0) PetscCall(SNESSetLagPreconditioner(f->snes, attempt ? 1 : f->refactor ? -2 : -1));
    PetscCall(SNESSolve(f->snes, NULL, f->U));
    PetscCall(SNESGetConvergedReason(f->snes, reason));
    PetscCall(SNESGetIterationNumber(f->snes, its));
    PetscCall(SNESGetLinearSolveIterations(f->snes, &lits));
    f->lin_its += lits;
    if (f->refactor_its <= 0 || attempt) { /* a set-up at every Newton iteration */
      f->setups += *its + (*reason <= 0);
      f->refactor = PETSC_TRUE;
      break;
    }
    PetscCall(SNESGetLagPreconditioner(f->snes, &lag));
    if (lag == -1 && f->refactor) { /* the rebuild happened */
      f->setups++, f->refactor = PETSC_FALSE;
      f->fresh_its = (PetscReal)lits / PetscMax(*its, 1);
    }
    if (*reason > 0) {
      if (*its > 0 && lits > PetscMax(f->refactor_its, 2 * f->fresh_its) * *its) f->refactor = PETSC_TRUE;
      break;
    }
    f->refactor = PETSC_TRUE;
    /* the operator is the exact Jacobian whatever the preconditioner: only a failed linear solve is the lag's */
    if (*reason != SNES_DIVERGED_LINEAR_SOLVE) break;
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode solve(void *ctx, const StepRequest *rq, StepOutcome *o, char *err, size_t errlen) {
  FeSolver           *f = ctx;
  FeProblem          *p = f->c.p;
  SNESConvergedReason reason;
  PetscInt            its;
  PetscFunctionBeginUser;
  PetscCall(fe_common_set_loads(&f->c, rq));
  fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0)); /* Newton iterates without it */
  PetscCall(lagged_solve(f, rq, &reason, &its));
  o->converged = reason > 0, o->its = (int)its, o->why = SNESConvergedReasons[reason];
  if (!o->converged) PetscFunctionReturn(0);
  PetscReal tol = umat_control_tol(fe_problem_material(p), rq->umat);
  PetscBool same = PETSC_FALSE;
  PetscCall(fe_problem_evaluated_at(p, f->U, &same));
  if (tol > 0 || !same) { /* the converged state again, with the UMAT's PNEWDT on */
    fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_AT, tol));
    PetscCall(fe_residual(f->snes, f->U, f->R, p));
    fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0));
  }
  o->pnewdt = fe_problem_diag(p)->min_pnewdt;
  PetscCall(fe_common_observe(&f->c, rq, o));
  o->nout = 6;
  for (int k = 0; k < 6; k++) o->out[k] = f->c.stats.strain_mean[k], o->group[k] = 0;
  PetscFunctionReturn(0);
}

static PetscErrorCode accept(void *ctx, const StepRequest *rq, char *err, size_t errlen) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_state_commit(f->c.p, rq->h));
  PetscCall(VecWAXPY(f->dU, -1.0, f->U0, f->U));
  PetscCall(VecCopy(f->U, f->U0));
  f->have_rate = rq->h > 0;
  PetscCall(fe_common_accept(&f->c, rq));
  PetscFunctionReturn(0);
}

/* The FE history's own columns (history_columns.h): the boundary loads, the volume statistics, the costs. */
static int npressure(const void *ctx) { return ((const FeSolver *)ctx)->c.sc->npressure; }
static void pressure_label(const void *ctx, int k, char *buf, size_t n) {
  const char *g = ((const FeSolver *)ctx)->c.sc->pressure_group[k];
  snprintf(buf, n, "%s_%s", strchr(g, '.') ? "traction" : "pressure", g);
}
static HistValue v_pressure(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.now[k]}; }
static HistValue v_eps(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.strain_mean[k]}; }
static HistValue v_sig(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.stress_mean[k]}; }
static HistValue v_spread(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.strain_spread}; }
static HistValue v_rate(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.evp_rate}; }
static HistValue v_hard(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.frame_evp[0][k]}; }
static HistValue v_soft(const void *ctx, const RunnerRow *row, int k) { return (HistValue){.r = ((const FeSolver *)ctx)->c.stats.frame_evp[1][k]}; }

static const char *const quantile[6] = {"mean", "min", "q1", "median", "q3", "max"};
static const HistColumn columns[] = {
  {"pressure", "%.12g", 0, NULL, v_pressure, npressure, pressure_label},
  {"eps", "%.15g", 6, hist_tensor_suffix, v_eps, NULL, NULL},
  {"sig", "%.15g", 6, hist_tensor_suffix, v_sig, NULL, NULL},
  {"eps_spread", "%.6g", 1, NULL, v_spread, NULL, NULL},
  {"evp_rate", "%.6g", 1, NULL, v_rate, NULL, NULL},
  {"evp33_hard", "%.12g", 6, quantile, v_hard, NULL, NULL},
  {"evp33_soft", "%.12g", 6, quantile, v_soft, NULL, NULL},
  FE_COMMON_COST_COLUMNS,
};

static PetscErrorCode progress(void *ctx, char *buf, size_t n) {
  FeSolver *f = ctx;
  PetscReal rnorm = 0;
  PetscFunctionBeginUser;
  PetscCall(SNESGetFunctionNorm(f->snes, &rnorm));
  snprintf(buf, n, "|R| %.2e ", (double)rnorm);
  PetscFunctionReturn(0);
}

static PetscErrorCode write_fields(void *ctx, double t, int report, char *err, size_t errlen) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_common_fields(&f->c, f->U0, t, report, err, errlen));
  PetscFunctionReturn(0);
}

static PetscErrorCode promote(void *ctx) {
  PetscFunctionBeginUser;
  PetscCall(fe_common_promote(&((FeSolver *)ctx)->c));
  PetscFunctionReturn(0);
}

static PetscErrorCode save(void *ctx, BinFile *b) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  f->refactor = PETSC_TRUE; /* the next solve factors afresh, as a run restarted from here does */
  PetscCall(fe_common_save(&f->c, b));
  binfile_write(b, &f->have_rate, sizeof f->have_rate, 1);
  PetscFunctionReturn(0);
}

static PetscErrorCode load(void *ctx, BinFile *b) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_common_load(&f->c, b));
  binfile_read(b, &f->have_rate, sizeof f->have_rate, 1);
  PetscFunctionReturn(0);
}

/* The committed displacement and the predictor's last increment, with the points' state (fe/fe_state.h). */
static const char *const shared_names[2] = {"displacement", "increment"};

static PetscErrorCode save_shared(void *ctx, const char *path) {
  FeSolver   *f = ctx;
  PetscViewer v;
  Vec         vecs[2] = {f->U0, f->dU};
  PetscFunctionBeginUser;
  PetscCall(fe_common_shared_open(&f->c, path, PETSC_TRUE, &v));
  PetscCall(fe_state_view(f->c.p, v, 2, vecs, shared_names));
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(0);
}

static PetscErrorCode load_shared(void *ctx, const char *path) {
  FeSolver   *f = ctx;
  PetscViewer v;
  Vec         vecs[2] = {f->U0, f->dU};
  PetscFunctionBeginUser;
  PetscCall(fe_common_shared_open(&f->c, path, PETSC_FALSE, &v));
  PetscCall(fe_state_read(f->c.p, v, 2, vecs, shared_names));
  PetscCall(PetscViewerDestroy(&v));
  PetscFunctionReturn(0);
}

static PetscErrorCode resume(void *ctx) {
  FeSolver *f = ctx;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(f->U0, f->U));
  PetscCall(fe_common_resume(&f->c));
  PetscFunctionReturn(0);
}

static PetscErrorCode replay(void *ctx, const char *dir, char *msg, size_t n) {
  PetscFunctionBeginUser;
  PetscCall(fe_common_replay(&((FeSolver *)ctx)->c, dir, msg, n));
  PetscFunctionReturn(0);
}

static long umat_calls(void *ctx) { return (long)fe_problem_diag(((FeSolver *)ctx)->c.p)->umat_calls; }

/* The linear solver (docs/performance.md, "FE solver: defaults by measurement"): GMRES (right
 * preconditioned: the true residual) around MUMPS' LU, kept across iterations and steps
 * (-fe_refactor_its), on any number of ranks; above -fe_gamg_above unknowns GAMG on the rigid-body near
 * null space instead. Every choice is a default: -ksp_type, -pc_type, -pc_factor_mat_solver_type,
 * -mat_mumps_icntl_* given by the user win; -fe_refactor_its 0 -ksp_type preonly is a plain direct solve
 * at every Newton iteration. The Jacobian is unsymmetric (the viscoplastic consistent tangent; its measured
 * asymmetry: docs/performance.md, "FE solver: defaults by measurement"), so LU, not Cholesky, and GMRES, not CG. */
static PetscErrorCode linear_solver_setup(FeSolver *f, KSP ksp, const FeSolverOptions *o) {
  PC        pc;
  PetscInt  n, gamg_above = o->gamg_above;
  PetscBool given;
  PetscFunctionBeginUser;
  f->refactor_its = o->refactor_its;
  PetscCall(MatGetSize(f->J, &n, NULL));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-pc_type", &given));
  if (!given && n > gamg_above) PetscCall(options_default("-pc_type", "gamg"));
  PetscCall(options_default("-ksp_type", f->refactor_its > 0 ? "gmres" : "preonly"));
  PetscCall(options_default("-ksp_pc_side", "right"));
  PetscCall(options_default("-ksp_rtol", "1e-10"));
  PetscCall(options_default("-ksp_max_it", "100"));
  /* the ordering: MUMPS' automatic choice (ICNTL(7) = 7), the one measured (docs/performance.md, "FE solver:
     defaults by measurement") */
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  f->refactor = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode fe_solver_options(MPI_Comm comm, FeSolverOptions *o) {
  PetscFunctionBeginUser;
  o->refactor_its = 20, o->gamg_above = 100000, o->coo = PETSC_TRUE, o->predictor = PETSC_TRUE;
  PetscOptionsBegin(comm, NULL, "Finite-element scenes (docs/driver.md, Solvers)", NULL);
  PetscCall(options_int(PetscOptionsObject, "-fe_refactor_its", "rebuild the kept factorisation when a solve takes more Krylov iterations "
                        "per Newton iteration (0: every iteration)", o->refactor_its, 0, PETSC_MAX_INT, &o->refactor_its, NULL));
  PetscCall(options_int(PetscOptionsObject, "-fe_gamg_above", "GAMG instead of LU above this many unknowns (measured: docs/performance.md)",
                        o->gamg_above, 0, PETSC_MAX_INT, &o->gamg_above, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-fe_coo", "assemble the Jacobian by COO (false: MatSetValues)", o->coo, &o->coo, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-fe_predictor", "start each step's Newton from the extrapolated last increment", o->predictor,
                         &o->predictor, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* SNES on the element loop: full Newton steps on the consistent tangent (cut back by the runner when they
 * fail), as Abaqus does; -snes_linesearch_type bt restores a backtracking line search. */
static PetscErrorCode solver_setup(FeSolver *f) {
  FeScene    *sc = f->c.sc;
  FeProblem  *p  = f->c.p;
  MPI_Comm    comm = PetscObjectComm((PetscObject)fe_problem_dm(p));
  KSP         ksp;
  FeSolverOptions o;
  PetscFunctionBeginUser;
  PetscCall(fe_solver_options(comm, &o));
  PetscCall(SNESCreate(comm, &f->snes));
  PetscCall(DMCreateMatrix(fe_problem_dm(p), &f->J));
  PetscCall(DMCreateGlobalVector(fe_problem_dm(p), &f->U));
  Vec *v[] = {&f->R, &f->U0, &f->dU, NULL};
  for (int k = 0; v[k]; k++) PetscCall(VecDuplicate(f->U, v[k]));
  PetscCall(VecZeroEntries(f->U));
  PetscCall(VecZeroEntries(f->U0));
  PetscCall(VecZeroEntries(f->dU));
  { /* rigid-body modes as the near null space, for -pc_type gamg */
    MatNullSpace rbm;
    PetscCall(DMPlexCreateRigidBody(fe_problem_dm(p), 0, &rbm));
    PetscCall(MatSetNearNullSpace(f->J, rbm));
    PetscCall(MatNullSpaceDestroy(&rbm));
  }
  PetscCall(SNESSetFunction(f->snes, f->R, fe_residual, p));
  PetscCall(SNESSetJacobian(f->snes, f->J, f->J, fe_jacobian, p));
  if (o.coo) PetscCall(fe_jacobian_coo_setup(p, f->J)); /* measured: docs/performance.md, "FE element loops" */
  PetscCall(SNESGetKSP(f->snes, &ksp));
  PetscCall(linear_solver_setup(f, ksp, &o));
  PetscReal pmax = 1, fref = 0; /* force scale for the absolute tolerance: the largest load on all loaded faces */
  for (int i = 0; i < sc->nstage; i++)
    for (int g = 0; g < sc->npressure; g++)
      if (!isnan(sc->loads[i].pressure[g])) pmax = PetscMax(pmax, fabs(sc->loads[i].pressure[g]));
  for (int g = 0; g < sc->npressure; g++) {
    PetscReal nrm;
    PetscCall(VecNorm(fe_problem_unit_force(p, g), NORM_2, &nrm));
    fref += nrm;
  }
  SNESLineSearch ls;
  PetscCall(SNESGetLineSearch(f->snes, &ls));
  PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
  PetscCall(SNESSetTolerances(f->snes, 1e-10 * pmax * PetscMax(fref, 1e-12), 1e-12, 1e-14, 25, 1000));
  PetscCall(SNESSetFromOptions(f->snes));
  PetscBool preonly;
  PetscCall(PetscObjectTypeCompare((PetscObject)ksp, KSPPREONLY, &preonly));
  if (preonly) f->refactor_its = 0; /* no Krylov solver to correct a kept factorisation */
  f->predictor = o.predictor;
  PetscFunctionReturn(0);
}

/* The linear solver's work and the memory high-water mark (largest and summed over the ranks). */
static PetscErrorCode solver_summary(FeSolver *f, MPI_Comm comm) {
  KSP         ksp;
  PC          pc;
  KSPType     kt;
  PCType      pt;
  MatSolverType st = NULL;
  double      mb[2], cpu = (double)(clock() - f->cpu0) / CLOCKS_PER_SEC;
  PetscFunctionBeginUser;
  PetscCall(SNESGetKSP(f->snes, &ksp));
  PetscCall(KSPGetType(ksp, &kt));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCGetType(pc, &pt));
  if (pt && !strcmp(pt, PCLU)) PetscCall(PCFactorGetMatSolverType(pc, &st));
  PetscCall(fe_common_max_rss(comm, mb));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &cpu, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscCall(PetscPrintf(comm, "fe solver: %s/%s%s%s, %ld Krylov iterations, %ld preconditioner set-ups, max RSS %.1f MB per rank, %.1f MB in all, CPU %.2f s (the slowest rank)\n",
                        kt, pt, st ? "/" : "", st ? st : "", f->lin_its, f->setups, mb[0], mb[1], cpu));
  PetscFunctionReturn(0);
}

/* The initial state: the UMAT initialises its state on a zero increment. */
static PetscErrorCode initial_state(FeSolver *f) {
  FeProblem *p = f->c.p;
  PetscFunctionBeginUser;
  fe_problem_set_step(p, 0, 0), fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0));
  PetscCall(fe_residual(f->snes, f->U, f->R, p));
  PetscCall(fe_problem_commit(p));
  PetscCall(fe_problem_stats(p, f->c.sc->axis, &f->c.stats, PETSC_FALSE, f->c.quantiles));
  PetscCall(fe_problem_reactions(p));
  PetscFunctionReturn(0);
}

/* What an FE scene reports (StepSolver.report): the volume-mean strain along the scene's axis and its trace. */
static void report(void *ctx, double *v) {
  FeSolver *f = ctx;
  v[0] = f->c.stats.strain_mean[f->c.sc->axis];
  v[1] = f->c.stats.strain_mean[0] + f->c.stats.strain_mean[1] + f->c.stats.strain_mean[2];
}

/* After the run: the output closed, the summary lines, the solver's objects freed. */
static PetscErrorCode finish(FeSolver *f, MPI_Comm comm, const RunnerSummary *sum, const RunnerOptions *opt) {
  FeProblem *p = f->c.p;
  PetscFunctionBeginUser;
  PetscCall(fe_common_finish(&f->c));
  PetscCall(solver_summary(f, comm));
  PetscCall(PetscPrintf(comm, "fe scene %s: %d steps, %d Newton iterations, %d cutbacks (%d by the error measure), %ld UMAT calls, assembly %.2f s, wall %.2f s -> %s/history.csv\n",
                        f->c.sc->name, sum->steps, sum->its, sum->cutbacks, sum->rejected_error, sum->umat_calls, fe_problem_diag(p)->assembly_seconds, sum->wall,
                        opt->outdir));
  PetscCall(VecDestroy(&f->U));
  PetscCall(VecDestroy(&f->R));
  PetscCall(VecDestroy(&f->U0));
  PetscCall(VecDestroy(&f->dU));
  PetscCall(MatDestroy(&f->J));
  fe_jacobian_coo_release(p);
  PetscCall(SNESDestroy(&f->snes));
  PetscFunctionReturn(0);
}

int fe_stepper_run(FeScene *sc, FeProblem *p, const RunnerOptions *opt, char *err, size_t errlen) {
  FeSolver f;
  PetscErrorCode ierr = PetscMemzero(&f, sizeof f);
  f.cpu0 = clock();
  if (!ierr) ierr = fe_common_init(&f.c, sc, p, opt);
  if (!ierr) ierr = solver_setup(&f);
  if (!ierr && !opt->restart) ierr = initial_state(&f);
  if (ierr) return stage_runner_status(ierr, err);
  StepSolver sv = {.ctx = &f, .kind = "fe", .nstage = sc->nstage, .comm = PetscObjectComm((PetscObject)fe_problem_dm(p)),
                   .stage_begin = stage_begin, .solve = solve, .accept = accept, .columns = columns,
                   .ncolumns = sizeof columns / sizeof columns[0], .stage_name = fe_common_stage_name, .progress = progress,
                   .write_fields = write_fields, .promote = promote,
                   .save = save, .load = load, .replay = replay, .umat_calls = umat_calls, .resume = resume,
                   .save_shared = save_shared, .load_shared = load_shared,
                   .nreport = 2, .report_names = {"strain_axial", "strain_volumetric"}, .report = report};
  RunnerSummary sum;
  int           rc = stage_runner_run(&sv, opt, &sum, err, errlen);
  ierr             = finish(&f, sv.comm, &sum, opt);
  return rc ? rc : stage_runner_status(ierr, err);
}
