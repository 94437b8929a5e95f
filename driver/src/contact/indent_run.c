#include "indent_run.h"

#include <math.h>
#include <petscksp.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../fe/fe_checkpoint.h"
#include "../fe/fe_output.h"
#include "contact.h"
#include "indent_solver.h"

/* Everything the Newton loop works on: the problem, the contact, the unknowns (u, u_r, lambda) with
 * their committed values and last converged increments (the predictor), residual parts and settings. */
typedef struct {
  FeProblem   *p;
  Contact      ct;
  IndentSolver sol;
  Mat          K;
  Vec          U, lam, Ru, Rlam, du, dlam;       /* iterate, residual parts, Newton direction */
  Vec          Uk, lamk;                         /* the iterate before a line search */
  Vec          U0, lam0, rateU, ratelam;         /* committed; last converged increment */
  PetscReal    ur, ur0, rateur, dt_prev;
  PetscBool    have_rate, predictor, monitor, line_search, fd_check;
  PetscReal    rtol, kshift, fref;
  PetscInt     max_it;
  /* the step being solved */
  PetscBool    depth_control;
  PetscReal    target;                           /* load or depth at the step's end */
  PetscReal    Rr, ncp, ru;                      /* residual parts at the last evaluation */
  PetscInt     nactive, changes;                 /* active nodes; changes over the step's iterations */
  PetscInt     its_total, steps_total, cycles, kshift_uses;
} Indent;

/* Force control at zero load: no contact pressure anywhere, and the indenter rests on the surface (its
 * position is not an unknown then). */
static PetscBool released(const Indent *in) { return !in->depth_control && in->target == 0 ? PETSC_TRUE : PETSC_FALSE; }

static double wall_since(const struct timespec *w0) {
  struct timespec w;
  clock_gettime(CLOCK_MONOTONIC, &w);
  return (double)(w.tv_sec - w0->tv_sec) + 1e-9 * (double)(w.tv_nsec - w0->tv_nsec);
}

/* Residual at the iterate (U, ur, lam): the element loop with the UMAT, the gaps, the contact forces;
 * returns the merit: the residual norm relative to the force scale (the active set does not enter). */
static PetscErrorCode evaluate(Indent *in, PetscReal *merit) {
  PetscFunctionBeginUser;
  PetscCall(fe_residual(NULL, in->U, in->Ru, in->p));
  PetscCall(contact_update_gaps(&in->ct, in->U, in->ur));
  PetscCall(contact_residual(&in->ct, in->lam, in->ur, in->depth_control, in->target, in->Ru, &in->Rr, &in->ncp));
  PetscCall(VecNorm(in->Ru, NORM_2, &in->ru));
  if (released(in)) { /* released: the indenter rests on the surface (set after
                                                   the step), so only lambda = 0 is asked for */
    const PetscScalar *la;
    PetscReal          s = 0, all;
    PetscCall(VecGetArrayRead(in->lam, &la));
    for (PetscInt i = 0; i < in->ct.n; i++) s += PetscSqr(in->ct.w[i] * PetscRealPart(la[i]));
    PetscCall(VecRestoreArrayRead(in->lam, &la));
    PetscCall(MPIU_Allreduce(&s, &all, 1, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
    in->ncp = PetscSqrtReal(all);
  }
  PetscReal rr = in->depth_control ? in->Rr * in->kshift : in->Rr; /* depth rows in force units */
  *merit       = PetscSqrtReal(in->ru * in->ru + in->ncp * in->ncp + rr * rr) / in->fref;
  PetscFunctionReturn(0);
}

/* A signature of the active set (all ranks), to notice a set met again: cycling. */
static PetscErrorCode active_signature(Indent *in, unsigned long long *sig) {
  unsigned long long loc = 0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < in->ct.n; i++)
    if (in->ct.active[i]) {
      unsigned long long z = (unsigned long long)(in->ct.rstart + i + 1) * 0x9E3779B97F4A7C15ULL;
      z ^= z >> 31, z *= 0xBF58476D1CE4E5B9ULL, z ^= z >> 27;
      loc += z;
    }
  PetscCallMPI(MPI_Allreduce(&loc, sig, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
  PetscFunctionReturn(0);
}

enum { STEP_OK = 0, STEP_DIVERGED, STEP_CYCLING, STEP_LINEAR };
static const char *step_failure[] = {"", "Newton did not converge", "the active set cycles", "the linear solver failed"};

/* One step by the semismooth Newton method of Box 1: the active set from eq. 14 at every iterate, the
 * system of eq. 15 solved for the set, a backtracking line search on the merit, converged when the
 * residual is small and the set did not change. */
static PetscErrorCode newton_step(Indent *in, PetscReal h, int *status, PetscInt *its_out) {
  unsigned long long sig[64];
  PetscReal          merit;
  PetscInt           k, changes, damp = 0;
  PetscFunctionBeginUser;
  *status     = STEP_DIVERGED;
  in->changes = 0;
  /* the start: the last converged state, or its extrapolation along the last converged rates */
  PetscCall(VecCopy(in->U0, in->U));
  PetscCall(VecCopy(in->lam0, in->lam));
  in->ur = in->ur0;
  if (in->predictor && in->have_rate && in->dt_prev > 0) {
    PetscReal r = h / in->dt_prev;
    PetscCall(VecAXPY(in->U, r, in->rateU));
    PetscCall(VecAXPY(in->lam, r, in->ratelam));
    in->ur += r * in->rateur;
    PetscScalar *la;
    PetscCall(VecGetArray(in->lam, &la));
    for (PetscInt i = 0; i < in->ct.n; i++) la[i] = PetscMax(0, PetscRealPart(la[i]));
    PetscCall(VecRestoreArray(in->lam, &la));
  }
  PetscCall(evaluate(in, &merit));
  for (k = 0; k <= in->max_it; k++) {
    if (released(in)) { /* released: no load, no contact pressure anywhere */
      PetscInt loc = 0;
      for (PetscInt i = 0; i < in->ct.n; i++) loc += in->ct.active[i], in->ct.active[i] = PETSC_FALSE;
      PetscCall(MPIU_Allreduce(&loc, &changes, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
      in->nactive = 0;
    } else PetscCall(contact_update_active(&in->ct, in->lam, in->fref / in->ct.weight_sum, &changes, &in->nactive));
    in->changes += changes;
    PetscCall(active_signature(in, &sig[k % 64]));
    PetscBool small = in->ru <= in->rtol * in->fref && in->ncp <= in->rtol * in->fref &&
                      PetscAbsReal(in->depth_control ? in->Rr * in->kshift : in->Rr) <= in->rtol * in->fref;
    if (in->monitor)
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    newton %2d  |R_u| %.3e  |R_r| %.3e  |ncp| %.3e  active %d (%d changes)  u_r %.10g\n",
                            (int)k, (double)in->ru, (double)PetscAbsReal(in->Rr), (double)in->ncp, (int)in->nactive, (int)changes,
                            (double)in->ur));
    if (small && changes == 0) {
      *status = STEP_OK;
      break;
    }
    if (k == in->max_it) break;
    if (changes > 0) /* cycling: a set met two or more iterations ago comes back */
      for (PetscInt j = PetscMax(0, k - 63); j < k - 1; j++)
        if (sig[j % 64] == sig[k % 64]) {
          in->cycles++;
          if (++damp > 2) { /* damped twice and still cycling: let the stepper cut the step back */
            *status = STEP_CYCLING;
            *its_out = k;
            PetscFunctionReturn(0);
          }
          break;
        }
    /* eq. 15 for the current set; a stiffness shift on the indenter row when no node is in contact
       (force control: the row would be empty) */
    PetscBool shift = !in->depth_control && in->nactive == 0;
    in->kshift_uses += shift;
    PetscCall(fe_jacobian(NULL, in->U, in->K, in->K, in->p));
    PetscCall(contact_jacobian(&in->ct, in->depth_control, shift ? in->kshift : 0.0));
    PetscCall(contact_constraint_residual(&in->ct, in->lam, in->Rlam));
    if (in->fd_check) { /* the displacement block against a finite difference of the element loop */
      Vec       r0, r1, kd;
      PetscReal eps = 1e-7, nd, nk;
      PetscCall(VecDuplicate(in->U, &r0));
      PetscCall(VecDuplicate(in->U, &r1));
      PetscCall(VecDuplicate(in->U, &kd));
      PetscCall(VecSetRandom(in->du, NULL));
      PetscCall(VecCopy(in->U, in->Uk));
      PetscCall(fe_residual(NULL, in->Uk, r0, in->p));
      PetscCall(VecAXPY(in->Uk, eps, in->du));
      PetscCall(fe_residual(NULL, in->Uk, r1, in->p));
      PetscCall(VecAXPY(r1, -1.0, r0));
      PetscCall(VecScale(r1, 1 / eps));
      PetscCall(fe_residual(NULL, in->U, r0, in->p));
      PetscCall(fe_jacobian(NULL, in->U, in->K, in->K, in->p));
      PetscCall(MatMult(in->K, in->du, kd));
      PetscCall(VecNorm(kd, NORM_2, &nk));
      PetscCall(VecAXPY(kd, -1.0, r1));
      PetscCall(VecNorm(kd, NORM_2, &nd));
      PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    tangent check: |K du - FD| / |K du| = %.3e\n", (double)(nd / nk)));
      PetscCall(VecDestroy(&r0));
      PetscCall(VecDestroy(&r1));
      PetscCall(VecDestroy(&kd));
      PetscCall(evaluate(in, &merit));
    }
    PetscReal dur;
    PetscBool ok;
    PetscCall(indent_solver_solve(&in->sol, &in->ct, in->Ru, in->Rr, in->Rlam, in->du, &dur, in->dlam, &ok));
    if (!ok) {
      *status = STEP_LINEAR;
      break;
    }
    /* line search: while the active set settles the full semismooth step is taken (it identifies the
       set in finitely many steps); with the set unchanged, the step is halved while the merit does not
       fall (Armijo, at most 5 halvings); a damped step (alpha = 1/2) after a cycle */
    PetscCall(VecCopy(in->U, in->Uk));
    PetscCall(VecCopy(in->lam, in->lamk));
    PetscReal urk = in->ur, alpha = damp ? 0.5 : 1.0, trial;
    PetscBool search = in->line_search && changes == 0 && !shift;
    for (int ls = 0;; ls++) {
      PetscCall(VecWAXPY(in->U, alpha, in->du, in->Uk));
      PetscCall(VecWAXPY(in->lam, alpha, in->dlam, in->lamk));
      in->ur = urk + alpha * dur;
      PetscCall(evaluate(in, &trial));
      if (!search || trial <= (1 - 1e-4 * alpha) * merit || ls == 5 || trial < in->rtol) break;
      alpha *= 0.5;
    }
    merit = trial;
  }
  *its_out = k;
  PetscFunctionReturn(0);
}

/* After a converged step at zero load with nothing in contact, the indenter rests on the surface: move
 * it down to the first touch (the depth then read is the residual depth). */
static PetscErrorCode rest_on_surface(Indent *in) {
  PetscReal dmin = PETSC_MAX_REAL, all;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < in->ct.n; i++) {
    PetscReal nd = contact_ndotd(&in->ct, i);
    if (nd > 1e-3) dmin = PetscMin(dmin, in->ct.g[i] / nd);
  }
  PetscCall(MPIU_Allreduce(&dmin, &all, 1, MPIU_REAL, MPI_MIN, PetscObjectComm((PetscObject)in->U)));
  if (all < PETSC_MAX_REAL) { /* down onto the surface, or up out of it */
    in->ur += all;
    PetscCall(contact_update_gaps(&in->ct, in->U, in->ur));
  }
  PetscFunctionReturn(0);
}

/* The indenter's part of a checkpoint (beside fe_checkpoint's displacement, point states and progress):
 * one file per rank, written atomically, tagged with the step so that the two parts must match. */
typedef struct {
  int    magic, step;
  double ur, load, load_max, stage_start, landing;
} IndentSaved;
#define INDENT_MAGIC 0x43433949 /* "CC9I" */

static int contact_checkpoint(const FeScene *sc, Indent *in, IndentSaved *sv, PetscBool write, char *err, size_t errlen) {
  PetscMPIInt rank;
  char        path[700], tmp[710];
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  snprintf(path, sizeof path, "%s/checkpoint_indenter.rank%d.bin", sc->outdir, rank);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  PetscInt     n = in->ct.n, m = -1;
  PetscScalar *la;
  FILE        *fp = fopen(write ? tmp : path, write ? "wb" : "rb");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot %s the checkpoint", write ? tmp : path, write ? "write" : "read");
    return 1;
  }
  VecGetArray(in->lam0, &la);
  int ok = 1;
  if (write) {
    sv->magic = INDENT_MAGIC;
    ok &= fwrite(sv, sizeof *sv, 1, fp) == 1 && fwrite(&n, sizeof n, 1, fp) == 1 && fwrite(la, sizeof *la, (size_t)n, fp) == (size_t)n;
  } else {
    ok &= fread(sv, sizeof *sv, 1, fp) == 1 && sv->magic == INDENT_MAGIC && fread(&m, sizeof m, 1, fp) == 1 && m == n;
    ok &= ok && fread(la, sizeof *la, (size_t)n, fp) == (size_t)n;
  }
  VecRestoreArray(in->lam0, &la);
  ok &= fclose(fp) == 0;
  if (ok && write) ok = rename(tmp, path) == 0;
  if (!ok) snprintf(err, errlen, "%s: %s", path, write ? "cannot write the checkpoint" : "not a complete indenter checkpoint of this scene");
  return !ok;
}

static PetscErrorCode commit(Indent *in, PetscReal h, PetscBool same_stage) {
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(in->rateU, -1.0, in->U0, in->U));
  PetscCall(VecWAXPY(in->ratelam, -1.0, in->lam0, in->lam));
  in->rateur    = in->ur - in->ur0;
  in->dt_prev   = h;
  in->have_rate = same_stage;
  PetscCall(VecCopy(in->U, in->U0));
  PetscCall(VecCopy(in->lam, in->lam0));
  in->ur0 = in->ur;
  PetscCall(fe_problem_commit(in->p));
  PetscFunctionReturn(0);
}

int indent_run(FeScene *sc, IndentScene *is, FeProblem *p, char *err, size_t errlen) {
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscMPIInt rank;
  Indent      in;
  MPI_Comm_rank(comm, &rank);
  PetscCall(PetscMemzero(&in, sizeof in));
  in.p = p;
  {
    PetscBool has;
    PetscCall(DMHasLabel(p->dm, is->contact_group, &has));
    if (!has) {
      snprintf(err, errlen, "%s: key 'indenter.contact': '%s' is not a physical group of the mesh %s", is->file, is->contact_group, sc->msh);
      return 2;
    }
  }
  PetscCall(contact_create(p, is->contact_group, &is->shape, &in.ct));
  PetscCall(DMCreateMatrix(p->dm, &in.K));
  { /* rigid-body modes for GAMG on the displacement block */
    MatNullSpace rbm;
    PetscCall(DMPlexCreateRigidBody(p->dm, 0, &rbm));
    PetscCall(MatSetNearNullSpace(in.K, rbm));
    PetscCall(MatNullSpaceDestroy(&rbm));
  }
  PetscCall(DMCreateGlobalVector(p->dm, &in.U));
  Vec *uv[7] = {&in.Ru, &in.du, &in.Uk, &in.U0, &in.rateU, NULL};
  for (int k = 0; uv[k]; k++) PetscCall(VecDuplicate(in.U, uv[k]));
  PetscCall(VecCreateMPI(comm, in.ct.n, in.ct.N, &in.lam));
  Vec *lv[6] = {&in.Rlam, &in.dlam, &in.lamk, &in.lam0, &in.ratelam, NULL};
  for (int k = 0; lv[k]; k++) PetscCall(VecDuplicate(in.lam, lv[k]));
  Vec *all[] = {&in.U, &in.Ru, &in.du, &in.Uk, &in.U0, &in.rateU, &in.lam, &in.Rlam, &in.dlam, &in.lamk, &in.lam0, &in.ratelam};
  for (size_t k = 0; k < sizeof all / sizeof all[0]; k++) PetscCall(VecZeroEntries(*all[k]));
  PetscCall(indent_solver_create(&in.ct, in.K, &in.sol));
  in.rtol = 1e-10, in.max_it = 30, in.predictor = PETSC_TRUE, in.line_search = PETSC_TRUE;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-indent_rtol", &in.rtol, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-indent_max_it", &in.max_it, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-indent_predictor", &in.predictor, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-indent_monitor", &in.monitor, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-indent_line_search", &in.line_search, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-indent_check_tangent", &in.fd_check, NULL));
  in.max_it = PetscMin(in.max_it, 63);

  /* The initial state: the UMAT initialises its state on a zero increment; its elastic tangent sets
     the indenter row's shift (one contact node's stiffness) and the complementarity constant. */
  p->time = 0, p->dt = 0;
  PetscCall(fe_residual(NULL, in.U, in.Ru, p));
  PetscCall(fe_problem_commit(p));
  PetscCall(fe_jacobian(NULL, in.U, in.K, in.K, p));
  PetscCall(contact_node_stiffness(&in.ct, in.K, &in.kshift));
  {
    PetscReal E = 0, Eall, ell = 0, lall;
    for (PetscInt k = 0; k < p->npoint; k++) E = PetscMax(E, p->ddsdde[k * 36]);
    for (PetscInt i = 0; i < in.ct.n; i++) { /* a contact-node spacing from the weights */
      PetscReal w = in.ct.w[i], r = in.ct.X[i * in.ct.dim];
      ell = PetscMax(ell, p->dim == 3 ? PetscSqrtReal(w) : p->kin == KIN_AXISYMMETRIC ? (r > 0 ? w / (2 * PETSC_PI * r) : 0) : w / p->thickness);
    }
    PetscCall(MPIU_Allreduce(&E, &Eall, 1, MPIU_REAL, MPI_MAX, comm));
    PetscCall(MPIU_Allreduce(&ell, &lall, 1, MPIU_REAL, MPI_MAX, comm));
    in.ct.c = is->c > 0 ? is->c : Eall / lall;
  }
  PetscCall(contact_update_gaps(&in.ct, in.U, in.ur));
  PetscCall(PetscPrintf(comm, "indenter: %s, %d potential contact nodes (group '%s', weights sum %.6g), solver %s, "
                              "complementarity c = %.4g, indenter-row shift %.4g\n",
                        (const char *[]){"berkovich", "cone", "wedge", "sphere", "flat_punch"}[is->shape.kind], (int)in.ct.N,
                        is->contact_group, (double)in.ct.weight_sum, in.sol.fieldsplit ? "fieldsplit" : "direct", (double)in.ct.c,
                        (double)in.kshift));

  /* -checkpoint_every N writes a checkpoint every N steps; -restart continues from the last one (the
     predictor then restarts from the checkpointed state); -max_steps N stops after N steps. */
  PetscInt    checkpoint_every = 0, max_steps = -1;
  PetscBool   restart = PETSC_FALSE;
  Progress    pr;
  IndentSaved sv;
  long        history_offset = 0;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-checkpoint_every", &checkpoint_every, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-max_steps", &max_steps, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-restart", &restart, NULL));
  PetscCall(PetscMemzero(&pr, sizeof pr));
  PetscCall(PetscMemzero(&sv, sizeof sv));
  if (restart) {
    if (read_checkpoint(sc, p, in.U, &pr, &history_offset, err, errlen) || contact_checkpoint(sc, &in, &sv, PETSC_FALSE, err, errlen)) return 2;
    if (sv.step != pr.step) {
      snprintf(err, errlen, "-restart: the checkpoint files of %s are from different steps (%d, %d)", sc->outdir, pr.step, sv.step);
      return 2;
    }
    PetscCall(VecCopy(in.U, in.U0));
    PetscCall(VecCopy(in.lam0, in.lam));
    in.ur = in.ur0 = sv.ur;
    PetscCall(contact_update_gaps(&in.ct, in.U, in.ur));
    PetscCall(PetscPrintf(comm, "restart at step %d, t = %g s (stage %d)\n", pr.step, pr.t, pr.stage));
  }

  char path[800];
  snprintf(path, sizeof path, "%s/history.csv", sc->outdir);
  FILE *hist = NULL;
  if (!rank && restart) { /* continue the history: drop the rows written after the checkpoint */
    if (truncate(path, history_offset) || !(hist = fopen(path, "a"))) {
      snprintf(err, errlen, "%s: cannot continue the history at the checkpoint", path);
      return 1;
    }
  } else if (!rank) {
    hist = fopen(path, "w");
    if (!hist) {
      snprintf(err, errlen, "%s: cannot write", path);
      return 1;
    }
    fprintf(hist, "time,stage,stage_name,step,dt,newton_its,cutbacks,load,depth,active_nodes,active_changes,contact_force,"
                  "max_penetration,min_lambda,umat_calls,wall\n");
    fprintf(hist, "0,0,%s,0,0,0,0,0,0,0,0,0,0,0,%d,0\n", sc->stage[0].name, (int)p->umat_calls);
  }
  FeOutput out;
  PetscCall(fe_output_open(p, sc->outdir, restart, &out));
  if (restart) PetscCall(fe_output_resume(&out, pr.nout, pr.out_times));
  else PetscCall(fe_output_write(p, in.U, 0.0, &out));
  struct timespec w0;
  clock_gettime(CLOCK_MONOTONIC, &w0);
  double t = pr.t, load = sv.load, load_max = sv.load_max;
  int    step = pr.step, total_cutbacks = pr.total_cutbacks, rc = 0, stopped = 0;
  int    resume_in_stage = restart && pr.in_stage; /* only the first stage of a restart resumes midway */
  for (int s = pr.stage; s < sc->nstage && !rc && !stopped; s++) {
    Stage       *g  = &sc->stage[s];
    IndentStage *st = &is->stage[s];
    in.depth_control = st->kind == IND_DEPTH_RAMP;
    double start = resume_in_stage ? sv.stage_start : in.depth_control ? in.ur : load, duration = g->duration;
    if (st->until_load > 0) { /* the time the load reaches the event, known in advance */
      double te = st->kind == IND_LOAD_EXP ? log(st->until_load / st->P0) / st->k
                                           : (st->target != start ? duration * (st->until_load - start) / (st->target - start) : -1);
      if (!(te >= 0 && te <= duration)) {
        snprintf(err, errlen, "stage '%s': the load never reaches until.load = %g within the stage's duration %g s", g->name,
                 st->until_load, duration);
        rc = 2;
        break;
      }
      duration = te;
    }
    double t_stage = 0, dt = step_control_planned(&g->steps, duration, 0), landing = 0;
    if (resume_in_stage) t_stage = pr.t_stage, dt = pr.dt, landing = sv.landing;
    resume_in_stage = 0;
    int    cut = 0, landed = 0;
    double stage_wall0 = wall_since(&w0);
    while (!rc && !landed && t_stage < duration * (1 - 1e-12)) {
      double h = landing > 0 ? landing : fmin(dt, duration - t_stage);
      if (duration - t_stage - h < 1e-9 * duration) h = duration - t_stage; /* no sliver at the end */
      double ts = t_stage + h, lambda = duration > 0 ? ts / duration : 1;
      if (st->until_load > 0 && ts >= duration) ts = duration;
      in.target = indent_stage_value(st, start, lambda, ts);
      if (!in.depth_control) {
        load_max = PetscMax(load_max, in.target);
        in.fref  = PetscMax(load_max, 1e-300);
      } else in.fref = PetscMax(PetscMax(load_max, in.kshift * PetscAbsReal(in.target)), 1e-300);
      p->time = t + h, p->dt = h;
      int      status;
      PetscInt its = 0;
      p->defer_step_control = PETSC_TRUE; /* the UMAT's error control judges the converged state only */
      PetscCall(newton_step(&in, h, &status, &its));
      p->defer_step_control = PETSC_FALSE;
      in.its_total += its;
      if (status == STEP_OK && p->mat.tol_slot >= 0 && p->mat.props[p->mat.tol_slot] > 0) {
        PetscReal m;
        PetscCall(evaluate(&in, &m)); /* the same state, now with the UMAT's PNEWDT */
      }
      if (status == STEP_OK && p->min_pnewdt < 1) status = -1;
      if (status != STEP_OK) { /* cut back */
        total_cutbacks++;
        double factor = status == -1 ? fmax(fmin(p->min_pnewdt, 0.5), 0.1) : 0.25;
        if (++cut > 30 || (g->steps.adaptive && h * factor < g->steps.min)) {
          snprintf(err, errlen, "stage '%s': step failed for good at t = %.6g s (dt = %.3g s): %s", g->name, t, h,
                   status == -1 ? "the UMAT asked for a smaller step" : step_failure[status]);
          rc = 1;
          break;
        }
        if (in.monitor) PetscCall(PetscPrintf(comm, "  cut back (%s): dt %.4g -> %.4g\n", status == -1 ? "PNEWDT" : step_failure[status], h, h * factor));
        dt = h * factor, landing = 0;
        continue;
      }
      const double event_tol = 1e-5; /* relative: the depth at which a stage ends */
      double       ur_before = in.ur0;
      if (st->until_depth > 0 && in.ur > st->until_depth * (1 + event_tol)) { /* overshot the event: land on it */
        double frac = (st->until_depth - ur_before) / (in.ur - ur_before);
        landing     = h * PetscMin(PetscMax(frac, 0.01), 0.999);
        continue;
      }
      if (st->until_depth > 0 && in.ur >= st->until_depth * (1 - event_tol)) landed = 1;
      landing = 0;
      if (released(&in) && in.nactive == 0) PetscCall(rest_on_surface(&in));
      PetscInt on_rim;
      PetscCall(contact_on_rim(&in.ct, &on_rim));
      if (on_rim) { /* beyond the surface the nodes are not checked: the results would be wrong from here */
        snprintf(err, errlen, "%s: at t = %.6g s (depth %.6g) the contact reached the edge of the potential contact surface '%s' "
                              "(%d active nodes on its rim): enlarge it (the mesh's contact region), then rerun; the history "
                              "up to the last step is in %s", is->file, t + h, (double)in.ur, is->contact_group, (int)on_rim, path);
        rc = 1;
        break;
      }
      PetscReal force, pen, lmin;
      PetscCall(contact_summary(&in.ct, in.lam, &force, &pen, &lmin));
      PetscCall(commit(&in, h, PETSC_TRUE));
      load = in.depth_control ? force : in.target;
      t += h, t_stage += h, step++;
      double wall = wall_since(&w0);
      if (!rank) {
        fprintf(hist, "%.17g,%d,%s,%d,%.17g,%d,%d,%.17g,%.17g,%d,%d,%.17g,%.6g,%.6g,%d,%.4f\n", t, s, g->name, step, h, (int)its, cut,
                load, (double)in.ur, (int)in.nactive, (int)in.changes, (double)force, (double)pen, (double)lmin, (int)p->umat_calls, wall);
        fflush(hist);
        double frac = st->until_depth > 0 ? in.ur / st->until_depth : duration > 0 ? t_stage / duration : 1;
        double left = frac > 0 ? (wall - stage_wall0) * (1 - frac) / frac : 0;
        printf("step %5d  %-7s t = %-10.5g dt = %-9.3g newton %2d  load %-10.5g depth %-10.5g active %4d (%3d changes)  "
               "cutbacks %d  wall %7.2f s  stage %3.0f%%, about %.0f s left\n",
               step, g->name, t, h, (int)its, load, (double)in.ur, (int)in.nactive, (int)in.changes, total_cutbacks, wall,
               100 * PetscMin(frac, 1), PetscMax(left, 0));
        fflush(stdout);
      }
      cut = 0;
      if (sc->fields_every > 0 && step % sc->fields_every == 0) PetscCall(fe_output_write(p, in.U, t, &out));
      if (g->steps.adaptive) dt = step_control_next(&g->steps, h, p->min_pnewdt);
      else dt *= g->steps.ratio;
      if (st->until_depth > 0 && !landed && in.ur > ur_before) { /* aim the next step at the event (secant) */
        double h_event = h * (st->until_depth - in.ur) / (in.ur - ur_before);
        if (h_event < dt) landing = h_event * (1 + 0.5 * event_tol);
      }
      if (checkpoint_every > 0 && step % checkpoint_every == 0) {
        int stage_done = landed || t_stage >= duration * (1 - 1e-12);
        pr.step = step, pr.stage = stage_done ? s + 1 : s, pr.in_stage = !stage_done, pr.t = t, pr.t_stage = t_stage, pr.dt = dt;
        pr.total_cutbacks = total_cutbacks, pr.nout = out.nout, pr.out_times = out.times;
        sv.step = step, sv.ur = in.ur0, sv.load = load, sv.load_max = load_max, sv.stage_start = start, sv.landing = landing;
        if (!rank) fflush(hist);
        long off = rank ? 0 : ftell(hist);
        if (write_checkpoint(sc, p, in.U0, &pr, off, err, errlen) || contact_checkpoint(sc, &in, &sv, PETSC_TRUE, err, errlen)) {
          rc = 1;
          break;
        }
      }
      if (max_steps >= 0 && step >= max_steps) {
        PetscCall(PetscPrintf(comm, "stopped after %d steps (-max_steps)\n", step));
        stopped = 1;
        break;
      }
    }
    if (!rc && !stopped && st->until_depth > 0 && !landed) {
      snprintf(err, errlen, "stage '%s': the depth %g (until.depth) was not reached by the stage's end (t = %g s, depth %.6g, load %.6g): "
                            "lengthen its duration", g->name, st->until_depth, t, (double)in.ur, load);
      rc = 1;
    }
    in.have_rate = PETSC_FALSE; /* no extrapolation across a change of loading */
    if (!rc && !stopped && (out.nout == 0 || out.times[out.nout - 1] != t)) PetscCall(fe_output_write(p, in.U, t, &out));
  }
  PetscCall(fe_output_close(p, &out));
  if (!rank) {
    fclose(hist);
    printf("indentation %s: %d steps, %d Newton iterations (predictor %s), %d cutbacks, %d active-set cycles, %d UMAT calls, "
           "assembly %.2f s, linear solves %.2f s (%s, %d Krylov iterations), wall %.2f s -> %s\n",
           sc->name, step, (int)in.its_total, in.predictor ? "on" : "off", total_cutbacks, (int)in.cycles, (int)p->umat_calls,
           p->assembly_seconds, in.sol.seconds, in.sol.fieldsplit ? "fieldsplit" : "direct", (int)in.sol.linear_its,
           wall_since(&w0), path);
  }
  PetscCall(indent_solver_destroy(&in.sol));
  PetscCall(contact_destroy(&in.ct));
  for (size_t k = 0; k < sizeof all / sizeof all[0]; k++) PetscCall(VecDestroy(all[k]));
  PetscCall(MatDestroy(&in.K));
  return rc;
}
