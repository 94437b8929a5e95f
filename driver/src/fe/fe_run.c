#include "fe_run.h"

#include <errno.h>
#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "../contact/indent_run.h"
#include "../material/umat_call.h"
#include "../point/point_run.h"
#include "fe_checkpoint.h"
#include "fe_output.h"
#include "fe_problem.h"
#include "fe_scene.h"

/* The scene's PETSc options, each unless the command line already gives it. */
static PetscErrorCode apply_scene_options(const char *options) {
  char  buf[1024], *tok, *save = NULL, *keys[64], *vals[64];
  int   n = 0;
  PetscFunctionBeginUser;
  snprintf(buf, sizeof buf, "%s", options);
  for (tok = strtok_r(buf, " \t", &save); tok && n < 64; tok = strtok_r(NULL, " \t", &save)) {
    if (tok[0] == '-' && !(tok[1] >= '0' && tok[1] <= '9') && tok[1] != '.') keys[n] = tok, vals[n++] = NULL;
    else if (n > 0 && !vals[n - 1]) vals[n - 1] = tok;
  }
  for (int k = 0; k < n; k++) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, keys[k], &set));
    if (!set) PetscCall(PetscOptionsSetValue(NULL, keys[k], vals[k]));
  }
  PetscFunctionReturn(0);
}

int fe_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen) {
  FeScene     sc;
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscMPIInt rank;
  MPI_Comm_rank(comm, &rank);
  IndentScene isc;
  if (fe_scene_read(doc, &sc, err, errlen)) return 2;
  if (sc.indenter && indent_scene_read(doc, &sc, &isc, err, errlen)) return 2;
  if (outdir_override && outdir_override[0]) snprintf(sc.outdir, sizeof sc.outdir, "%s", outdir_override);
  if (!rank && make_directories(sc.outdir)) {
    snprintf(err, errlen, "output directory '%s': cannot create: %s", sc.outdir, strerror(errno));
    return 2;
  }
  /* Writable? (nothing already written is touched when it is not) */
  char probe[700];
  snprintf(probe, sizeof probe, "%s/.writable", sc.outdir);
  int writable = 1;
  if (!rank) {
    FILE *fp = fopen(probe, "w");
    writable = fp != NULL;
    if (fp) fclose(fp), remove(probe);
  }
  MPI_Bcast(&writable, 1, MPI_INT, 0, comm);
  if (!writable) {
    snprintf(err, errlen, "output directory '%s' is not writable", sc.outdir);
    return 2;
  }
  if (sc.geometry[0]) { /* mesh the geometry with gmsh, into the output directory */
    char cmd[4096];
    int  rc = 0;
    snprintf(sc.msh, sizeof sc.msh, "%s/mesh.msh", sc.outdir);
    snprintf(cmd, sizeof cmd, "gmsh -3 -format msh41 -v 1 %s%s -o %s", sc.geometry, sc.gmsh_params, sc.msh);
    if (!rank) rc = system(cmd);
    MPI_Bcast(&rc, 1, MPI_INT, 0, comm);
    if (rc) {
      snprintf(err, errlen, "meshing failed: %s", cmd);
      return 1;
    }
  }

  DM        dm;
  FeProblem p;
  memset(&p, 0, sizeof p);
  PetscErrorCode ierr = fe_mesh_create(comm, sc.msh, sc.kin == KIN_3D ? 3 : 2, &dm);
  if (ierr) {
    snprintf(err, errlen, "cannot read the mesh '%s'", sc.msh);
    return 1;
  }
  { /* every group the scene names must be a physical group of the mesh */
    const char *missing = NULL;
    PetscBool   has;
    for (int k = 0; k < sc.nfixed && !missing; k++) {
      PetscCall(DMHasLabel(dm, sc.fixed[k].group, &has));
      if (!has) missing = sc.fixed[k].group;
    }
    static char base[64];
    for (int k = 0; k < sc.npressure && !missing; k++) {
      snprintf(base, sizeof base, "%s", sc.pressure_group[k]);
      size_t len = strlen(base);
      if (len > 2 && base[len - 2] == '.' && strchr("xyz", base[len - 1])) base[len - 2] = '\0';
      PetscCall(DMHasLabel(dm, base, &has));
      if (!has) missing = base;
    }
    if (missing) {
      char     groups[512] = "";
      PetscInt nl;
      PetscCall(DMGetNumLabels(dm, &nl));
      for (PetscInt l = 0; l < nl; l++) {
        const char *ln;
        PetscCall(DMGetLabelName(dm, l, &ln));
        if (!strcmp(ln, "depth") || !strcmp(ln, "celltype")) continue;
        size_t len = strlen(groups);
        snprintf(groups + len, sizeof groups - len, "%s%s", len ? ", " : "", ln);
      }
      snprintf(err, errlen, "%s: key 'boundary': group '%s' is not a physical group of the mesh %s (it has: %s)",
               doc->file, missing, sc.msh, groups);
      PetscCall(DMDestroy(&dm));
      return 2;
    }
  }
  ierr = fe_problem_setup(&p, dm, sc.kin, sc.thickness, sc.order, &sc.mat, sc.fixed, sc.nfixed, (const char(*)[64])sc.pressure_group, sc.npressure);
  if (ierr) {
    snprintf(err, errlen, "setting up the problem failed (see the PETSc message above: a missing physical group?)");
    return 1;
  }
  snprintf(p.outdir, sizeof p.outdir, "%s", sc.outdir);
  {
    PetscInt ncell = p.cEnd - p.cStart, nall, ndof;
    Vec      tmp;
    PetscCall(MPIU_Allreduce(&ncell, &nall, 1, MPIU_INT, MPI_SUM, comm));
    PetscCall(DMCreateGlobalVector(dm, &tmp));
    PetscCall(VecGetSize(tmp, &ndof));
    PetscCall(VecDestroy(&tmp));
    PetscCall(PetscPrintf(comm, "fe scene %s: %d cells, P%d, %d quadrature points per cell, %d unknowns, %d UMAT state slots per point\n",
                          sc.name, (int)nall, sc.order, (int)p.nq, (int)ndof, (int)p.nsv));
  }
  PetscCall(fe_problem_set_initial_stress(&p, sc.stress0));
  PetscCall(fe_problem_set_phi(&p, sc.phi_mean, sc.phi_std, sc.phi_lo, sc.phi_hi, sc.phi_seed, sc.phi_corr));
  PetscCall(apply_scene_options(sc.solver_options));
  if (sc.indenter) { /* a rigid indenter: the contact stepper (Newton with an active set) */
    int irc = indent_run(&sc, &isc, &p, err, errlen);
    PetscCall(fe_problem_destroy(&p));
    PetscCall(DMDestroy(&dm));
    return irc;
  }

  SNES snes;
  Mat  J;
  Vec  U, R, U0;
  PetscCall(SNESCreate(comm, &snes));
  PetscCall(DMCreateMatrix(dm, &J));
  PetscCall(DMCreateGlobalVector(dm, &U));
  PetscCall(VecDuplicate(U, &R));
  PetscCall(VecDuplicate(U, &U0));
  PetscCall(VecZeroEntries(U));
  { /* rigid-body modes as the near null space, for -pc_type gamg (the default stays a direct solver) */
    MatNullSpace rbm;
    PetscCall(DMPlexCreateRigidBody(dm, 0, &rbm));
    PetscCall(MatSetNearNullSpace(J, rbm));
    PetscCall(MatNullSpaceDestroy(&rbm));
  }
  PetscCall(SNESSetFunction(snes, R, fe_residual, &p));
  PetscCall(SNESSetJacobian(snes, J, J, fe_jacobian, &p));
  {
    KSP         ksp;
    PC          pc;
    PetscMPIInt size;
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
    MPI_Comm_size(comm, &size);
    if (size > 1) PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
    /* Force scale for the absolute tolerance: the largest pressure on all loaded faces. */
    PetscReal pmax = 1, fref = 0;
    for (int i = 0; i < sc.nstage; i++)
      for (int g = 0; g < sc.npressure; g++)
        if (!isnan(sc.stage[i].pressure[g])) pmax = PetscMax(pmax, fabs(sc.stage[i].pressure[g]));
    for (int g = 0; g < sc.npressure; g++) {
      PetscReal nrm;
      PetscCall(VecNorm(p.unit_force[g], NORM_2, &nrm));
      fref += nrm;
    }
    { /* Full Newton steps on the consistent tangent (cut back by the stepper when they fail), as
         Abaqus does; -snes_linesearch_type bt restores a backtracking line search. */
      SNESLineSearch ls;
      PetscCall(SNESGetLineSearch(snes, &ls));
      PetscCall(SNESLineSearchSetType(ls, SNESLINESEARCHBASIC));
    }
    PetscCall(SNESSetTolerances(snes, 1e-10 * pmax * PetscMax(fref, 1e-12), 1e-12, 1e-14, 25, 1000));
    PetscCall(SNESSetFromOptions(snes));
  }

  /* Checkpoints (-checkpoint_every N steps; one file per rank) and -restart from the last one. */
  PetscInt  checkpoint_every = 0, max_steps = -1;
  PetscBool restart = PETSC_FALSE;
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-checkpoint_every", &checkpoint_every, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-max_steps", &max_steps, NULL));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-restart", &restart, NULL));
  Progress pr;
  memset(&pr, 0, sizeof pr);
  for (int k = 0; k < FE_MAX_GROUPS; k++) pr.pressure_now[k] = sc.pressure0[k];
  long history_offset = 0;
  if (restart) {
    if (read_checkpoint(&sc, &p, U, &pr, &history_offset, err, errlen)) return 2;
  }
  char path[800];
  snprintf(path, sizeof path, "%s/history.csv", sc.outdir);
  FILE *hist = NULL;
  if (!rank && restart) {
    /* continue the history of the checkpointed run: drop the rows written after the checkpoint */
    if (truncate(path, history_offset)) {
      snprintf(err, errlen, "%s: cannot truncate to the checkpoint: %s", path, strerror(errno));
      return 1;
    }
    hist = fopen(path, "a");
  } else if (!rank) {
    hist = fopen(path, "w");
    fprintf(hist, "time,stage,step,dt,newton_its,cutbacks");
    for (int g = 0; g < sc.npressure; g++)
      fprintf(hist, ",%s_%s", strchr(sc.pressure_group[g], '.') ? "traction" : "pressure", sc.pressure_group[g]);
    fprintf(hist, ",eps_11,eps_22,eps_33,eps_12,eps_13,eps_23,sig_11,sig_22,sig_33,sig_12,sig_13,sig_23,eps_spread,evp_rate");
    const char *fr[2] = {"hard", "soft"}, *st[6] = {"mean", "min", "q1", "median", "q3", "max"};
    for (int f = 0; f < 2; f++)
      for (int k = 0; k < 6; k++) fprintf(hist, ",evp33_%s_%s", fr[f], st[k]);
    fprintf(hist, ",umat_calls,wall\n");
  }
  FeOutput out;
  PetscCall(fe_output_open(&p, sc.outdir, restart, &out));
  if (restart) PetscCall(fe_output_resume(&out, pr.nout, pr.out_times));
  else PetscCall(fe_output_write(&p, U, 0.0, &out));
  struct timespec w0, w1;
  clock_gettime(CLOCK_MONOTONIC, &w0);
  for (int k = 0; k < FE_MAX_GROUPS; k++) p.pressure[k] = pr.pressure_now[k];
  PetscCall(fe_problem_update_loads(&p));
  int     rc = 0, stopped = 0;
  FeStats stats;
  double  t = pr.t;
  int     step = pr.step, total_cutbacks = pr.total_cutbacks;
  double *pressure_now = pr.pressure_now;
  if (!restart) { /* row 0: the initial state (the UMAT initialises its state on a zero increment) */
    p.time = 0, p.dt = 0;
    PetscCall(fe_residual(snes, U, R, &p));
    PetscCall(fe_problem_commit(&p));
  }
  int resume_in_stage = restart && pr.in_stage; /* only the first stage of a restart resumes midway */
  for (int s = pr.stage; s < sc.nstage && !rc && !stopped; s++) {
    Stage *g = &sc.stage[s];
    double target[FE_MAX_GROUPS];
    double dt_plan = step_control_planned(&g->steps, g->duration, 0);
    if (!resume_in_stage) { /* a new stage (a resumed one keeps its saved progress) */
      for (int k = 0; k < sc.npressure; k++) pr.start[k] = pressure_now[k];
      pr.t_stage = 0, pr.dt = dt_plan, pr.pending_instant = g->instant;
    }
    resume_in_stage = 0;
    double stage_wall0;
    {
      struct timespec ws;
      clock_gettime(CLOCK_MONOTONIC, &ws);
      stage_wall0 = (double)(ws.tv_sec - w0.tv_sec) + 1e-9 * (double)(ws.tv_nsec - w0.tv_nsec);
    }
    double *start = pr.start, t_stage = pr.t_stage, dt = pr.dt;
    int     pending_instant = pr.pending_instant, cut = 0;
    for (int k = 0; k < sc.npressure; k++) target[k] = isnan(g->pressure[k]) ? start[k] : g->pressure[k];
    while (!rc) {
      double h = pending_instant ? 0 : fmin(dt, g->duration - t_stage);
      if (!pending_instant && (t_stage >= g->duration * (1 - 1e-12))) break;
      double lambda = g->instant || g->duration == 0 ? 1 : (t_stage + h) / g->duration;
      for (int k = 0; k < sc.npressure; k++) p.pressure[k] = stage_pressure(g, k, start[k], target[k], lambda, t_stage + h);
      PetscCall(fe_problem_update_loads(&p));
      p.time = t + h, p.dt = h;
      PetscCall(VecCopy(U, U0));
      SNESConvergedReason reason;
      PetscInt            its;
      p.defer_step_control = PETSC_TRUE; /* the UMAT's error control judges the converged state only */
      PetscCall(SNESSolve(snes, NULL, U));
      p.defer_step_control = PETSC_FALSE;
      PetscCall(SNESGetConvergedReason(snes, &reason));
      PetscCall(SNESGetIterationNumber(snes, &its));
      if (reason > 0) PetscCall(fe_residual(snes, U, R, &p)); /* trial state at the solution, error control on */
      if (reason <= 0 || p.min_pnewdt < 1) {
        PetscCall(VecCopy(U0, U));
        total_cutbacks++;
        double factor = reason > 0 ? fmax(fmin(p.min_pnewdt, 0.5), 0.1) : 0.25;
        if (h == 0 || ++cut > 30 || (g->steps.adaptive && h * factor < g->steps.min)) {
          snprintf(err, errlen, "stage '%s': step failed for good at t = %.6g s (dt = %.3g s): %s", g->name, t, h,
                   reason <= 0 ? SNESConvergedReasons[reason] : "the UMAT asked for a smaller step");
          if (p.have_failed_call) { /* replay the failing call at one point: driver -input failed_call.yaml */
            char rp[700];
            snprintf(rp, sizeof rp, "%s/failed_call.rank%d.yaml", sc.outdir, rank);
            if (!umat_write_replay(rp, &p.failed_mat, &p.failed_in, &p.failed_out, err)) {
              size_t len = strlen(err);
              snprintf(err + len, errlen - len, "; the failing UMAT call (element %d, point %d) is replayed by: driver -input %s",
                       p.failed_in.noel, p.failed_in.npt, rp);
            }
          }
          rc = 1;
          break;
        }
        dt = h * factor;
        continue;
      }
      PetscCall(fe_problem_stats(&p, sc.axis, &stats, PETSC_TRUE));
      PetscCall(fe_problem_commit(&p));
      for (int k = 0; k < sc.npressure; k++) pressure_now[k] = p.pressure[k];
      t += h, t_stage += h, step++;
      clock_gettime(CLOCK_MONOTONIC, &w1);
      double wall = (double)(w1.tv_sec - w0.tv_sec) + 1e-9 * (double)(w1.tv_nsec - w0.tv_nsec);
      PetscReal rnorm;
      PetscCall(SNESGetFunctionNorm(snes, &rnorm));
      if (!rank) {
        fprintf(hist, "%.17g,%d,%d,%.17g,%d,%d", t, s, step, h, (int)its, cut);
        for (int k = 0; k < sc.npressure; k++) fprintf(hist, ",%.12g", p.pressure[k]);
        for (int vI = 0; vI < 6; vI++) fprintf(hist, ",%.15g", stats.strain_mean[vI]);
        for (int vI = 0; vI < 6; vI++) fprintf(hist, ",%.15g", stats.stress_mean[vI]);
        fprintf(hist, ",%.6g,%.6g", stats.strain_spread, stats.evp_rate);
        for (int f = 0; f < 2; f++)
          for (int k = 0; k < 6; k++) fprintf(hist, ",%.12g", stats.frame_evp[f][k]);
        fprintf(hist, ",%d,%.4f\n", (int)p.umat_calls, wall);
        fflush(hist);
        /* time left in this stage, from the wall time spent in it so far and the stage time done */
        double frac = g->duration > 0 ? t_stage / g->duration : 1, left = frac > 0 ? (wall - stage_wall0) * (1 - frac) / frac : 0;
        printf("step %5d  %-8s t = %-11.5g dt = %-10.4g newton %2d  |R| %.2e  cutbacks %d  wall %7.2f s  stage %3.0f%%, "
               "about %.0f s left%s\n",
               step, g->name, t, h, (int)its, (double)rnorm, total_cutbacks, wall, 100 * frac, left,
               g->evp_rate_below > 0 ? " (or less: it ends at steady state)" : "");
        fflush(stdout);
      }
      cut = 0;
      if (sc.fields_every > 0 && step % sc.fields_every == 0) PetscCall(fe_output_write(&p, U, t, &out));
      int was_instant = pending_instant;
      if (pending_instant) pending_instant = 0;
      else if (g->steps.adaptive) dt = step_control_next(&g->steps, h, p.min_pnewdt);
      else dt *= g->steps.ratio;
      int done = !was_instant && g->evp_rate_below > 0 && stats.evp_rate < g->evp_rate_below;
      if (checkpoint_every > 0 && step % checkpoint_every == 0) {
        pr.step = step, pr.stage = done ? s + 1 : s, pr.in_stage = !done, pr.t = t, pr.t_stage = t_stage, pr.dt = dt;
        pr.pending_instant = pending_instant, pr.total_cutbacks = total_cutbacks;
        pr.nout = out.nout;
        pr.out_times = out.times;
        if (!rank) fflush(hist);
        long off = rank ? 0 : ftell(hist);
        if (write_checkpoint(&sc, &p, U, &pr, off, err, errlen)) {
          rc = 1;
          break;
        }
      }
      if (max_steps >= 0 && step >= max_steps) {
        PetscCall(PetscPrintf(comm, "stopped after %d steps (-max_steps)\n", step));
        stopped = 1;
        break;
      }
      if (done) break;
    }
    if (!rc && !stopped && (out.nout == 0 || out.times[out.nout - 1] != t)) PetscCall(fe_output_write(&p, U, t, &out)); /* stage end */
  }
  if (!stopped && (out.nout == 0 || out.times[out.nout - 1] != t)) PetscCall(fe_output_write(&p, U, t, &out));
  PetscCall(fe_output_close(&p, &out));
  if (!rank) {
    fclose(hist);
    printf("fe scene %s: %d steps, %d cutbacks, %d UMAT calls, assembly %.2f s -> %s\n", sc.name, step, total_cutbacks,
           (int)p.umat_calls, p.assembly_seconds, path);
    printf("  (%d tangent evaluations away from the last residual)\n", (int)p.tangent_recomputes);
  }
  PetscCall(VecDestroy(&U));
  PetscCall(VecDestroy(&U0));
  PetscCall(VecDestroy(&R));
  PetscCall(MatDestroy(&J));
  PetscCall(SNESDestroy(&snes));
  PetscCall(fe_problem_destroy(&p));
  PetscCall(DMDestroy(&dm));
  return rc;
}
