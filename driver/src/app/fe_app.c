/* A finite-element scene (scene: fe), with or without a rigid indenter: read it, mesh its geometry, set up
 * the problem (mesh, field, material, phi, initial stress, PETSc options of the scene), then run its stages
 * on the stage runner with the SNES or the indentation step solver. */
#include "fe_app.h"

#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>

#include "../contact/indent_scene.h"
#include "../fe/fe_estimate.h"
#include "../fe/fe_groups.h"
#include "../fe/fe_problem.h"
#include "../fe/fe_scene.h"
#include "../io/fsutil.h"
#include "../io/gmsh_mesh.h"
#include "../io/options.h"
#include "../stepping/checkpoint.h"
#include "../stepping/fe_stepper.h"

PetscErrorCode app_runner_options(RunnerOptions *o) {
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof *o));
  PetscBool restart = PETSC_FALSE;
  PetscReal alpha = STEP_GAINS_PI.alpha, beta = STEP_GAINS_PI.beta;
  PetscInt  every = 0, max_steps = -1, progress = 0;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Stages and steps (every scene kind)", NULL);
  PetscCall(options_int(PetscOptionsObject, "-checkpoint_every", "write a checkpoint every N steps (0: none)", every, 0, PETSC_MAX_INT,
                        &every, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-restart", "continue from the last complete checkpoint in the output directory", restart,
                         &restart, NULL));
  PetscCall(options_int(PetscOptionsObject, "-max_steps", "stop after N steps in all (-1: no limit)", max_steps, -1, PETSC_MAX_INT,
                        &max_steps, NULL));
  PetscCall(options_int(PetscOptionsObject, "-progress_every", "a progress line every N steps (0: the scene's choice)", progress, 0,
                        PETSC_MAX_INT, &progress, NULL));
  PetscCall(options_real(PetscOptionsObject, "-step_alpha", "step controller: dt' = dt 0.9 ratio^-alpha ratio_prev^beta (1, 0: elementary)",
                         alpha, 0, 2, OPTIONS_LO_OPEN, &alpha, NULL));
  PetscCall(options_real(PetscOptionsObject, "-step_beta",
                         "step controller: the exponent of the previous step's error ratio (below -step_alpha)", beta, 0, 2, OPTIONS_HI_OPEN,
                         &beta, NULL));
  PetscOptionsEnd();
  PetscCheck(beta < alpha, PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE,
             "option -step_beta %g: expected a number below -step_alpha (%g): the controller would not damp the steps' ratio", (double)beta,
             (double)alpha);
  o->gains.alpha = alpha, o->gains.beta = beta;
  o->checkpoint_every = (int)every, o->restart = restart, o->max_steps = (int)max_steps, o->progress_every = (int)progress;
  PetscFunctionReturn(0);
}

/* Every group the scene names must be a physical group of the mesh, of the kind its key needs (fe/fe_groups.h):
   else *bad = 2 with err filled. */
static PetscErrorCode check_groups(YdDoc *doc, FeScene *sc, const char *contact_group, DM dm, char *err, size_t errlen, int *bad) {
  const char *missing = NULL;
  PetscBool   has;
  static char base[64];
  PetscFunctionBeginUser;
  if (contact_group) PetscCall(DMHasLabel(dm, contact_group, &has));
  if (contact_group && !has) missing = contact_group;
  for (int k = 0; k < sc->nfixed && !missing; k++) {
    PetscCall(DMHasLabel(dm, sc->fixed[k].group, &has));
    if (!has) missing = sc->fixed[k].group;
  }
  for (int k = 0; k < sc->npressure && !missing; k++) {
    snprintf(base, sizeof base, "%s", sc->pressure_group[k]);
    size_t len = strlen(base);
    if (len > 2 && base[len - 2] == '.' && strchr("xyz", base[len - 1])) base[len - 2] = '\0';
    PetscCall(DMHasLabel(dm, base, &has));
    if (!has) missing = base;
  }
  if (!missing) {
    PetscCall(fe_groups_check(doc, sc, contact_group, dm, err, errlen, bad));
    PetscFunctionReturn(0);
  }
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
  snprintf(err, errlen, "%s: key '%s': group '%s' is not a physical group of the mesh %s (it has: %s)", doc->file,
           missing == contact_group ? "indenter.contact" : "boundary", missing, sc->msh, groups);
  *bad = 2;
  PetscFunctionReturn(0);
}

/* Mesh the scene's geometry (or geo, a .geo that includes it with another size field) with gmsh (no shell) into the
 * output directory: mesh.part.msh for a fresh run (renamed once the run has produced its first step, so an earlier
 * run's mesh stays until then); for a restart mesh.restart.msh, which the checkpoint's hash of the mesh must match
 * (stepping/checkpoint.c: the earlier mesh.msh is never touched) and which is removed after the run. */
static int mesh_geometry(FeScene *sc, const char *geo, const RunnerOptions *opt, char *err, size_t errlen) {
  int rank, rc = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  snprintf(sc->msh, sizeof sc->msh, "%s/mesh%s.msh", sc->outdir, opt->restart ? ".restart" : ".part");
  if (!rank) rc = gmsh_mesh(geo ? geo : sc->geometry, sc->kin == KIN_3D ? 3 : 2, sc->ngmsh, (const char(*)[64])sc->gmsh_name, sc->gmsh_value,
                            sc->msh, err, errlen);
  MPI_Bcast(&rc, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
  return rc;
}

static PetscErrorCode print_sizes(FeScene *sc, FeProblem *p, RunInfo *info) {
  const FeSpace *sp    = fe_problem_space(p);
  PetscInt       ncell = sp->cEnd - sp->cStart, nall, ndof;
  Vec      tmp;
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&ncell, &nall, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(DMCreateGlobalVector(sp->dm, &tmp));
  PetscCall(VecGetSize(tmp, &ndof));
  PetscCall(VecDestroy(&tmp));
  info->cells = (long)nall, info->unknowns = (long)ndof;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "fe scene %s: %d cells, P%d, %d quadrature points per cell, %d unknowns, %d UMAT state slots per point\n",
              sc->name, (int)nall, sc->order, (int)sp->nq, (int)ndof, (int)fe_problem_point_size(p)));
  PetscFunctionReturn(0);
}

/* After the stages: the indicator's norm and, when asked, the size field for the next mesh (fe/fe_estimate.h). */
static PetscErrorCode after_run(FeProblem *p, const char *sizes, double growth, double base, RunInfo *info) {
  PetscReal norm;
  PetscFunctionBeginUser;
  PetscCall(fe_estimate_norm(p, &norm));
  info->eta = norm;
  if (sizes) PetscCall(fe_estimate_write_sizes(p, growth * (base > 0 ? base : (double)info->cells), sizes, &info->predicted));
  PetscFunctionReturn(0);
}

static int run_problem(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, const char *sizes, double growth, double base, RunInfo *info,
                       char *err, size_t errlen) {
  DM        dm;
  FeProblem p;
  int       bad = 0;
  memset(&p, 0, sizeof p);
  PetscErrorCode ierr = fe_mesh_create(PETSC_COMM_WORLD, sc->msh, sc->kin == KIN_3D ? 3 : 2, &dm);
  if (ierr) return stage_runner_status(ierr, err);
  ierr = check_groups(doc, sc, sc->indenter ? isc->contact_group : NULL, dm, err, errlen, &bad);
  if (ierr || bad) {
    DMDestroy(&dm); /* after a failure: its own is not the one to report */
    return ierr ? stage_runner_status(ierr, err) : bad;
  }
  ierr = fe_problem_setup(&p, dm, sc->kin, sc->thickness, sc->order, &sc->mat, sc->fixed, sc->nfixed, (const char(*)[64])sc->pressure_group,
                          sc->npressure);
  if (ierr) return stage_runner_status(ierr, err);
  if ((ierr = print_sizes(sc, &p, info)) || (ierr = fe_problem_set_initial_stress(&p, sc->stress0)) ||
      (ierr = fe_problem_set_phi(&p, sc->phi_mean, sc->phi_std, sc->phi_lo, sc->phi_hi, sc->phi_seed, sc->phi_corr)))
    return stage_runner_status(ierr, err);
  opt->outdir = sc->outdir, opt->scene_file = doc->file, opt->fields_every = sc->fields_every, opt->summary = &info->sum;
  opt->part_file = sc->geometry[0] && !opt->restart ? sc->msh : NULL;
  opt->mesh_file = sc->msh;
  int rc = sc->indenter ? indent_stepper_run(sc, isc, &p, opt, err, errlen) : fe_stepper_run(sc, &p, opt, err, errlen);
  ierr   = rc ? 0 : after_run(&p, sizes, growth, base, info);
  if (!ierr) ierr = fe_problem_destroy(&p);
  if (!ierr) ierr = DMDestroy(&dm);
  return rc ? rc : stage_runner_status(ierr, err);
}

/* CPU seconds of this process so far (user and system). */
static double cpu_seconds(void) {
  struct rusage u;
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

int fe_app_run_once(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, const char *geo, const char *sizes, double growth, double base,
                    RunInfo *info, char *err, size_t errlen) {
  double t0 = cpu_seconds();
  int    rank, bad = 0;
  memset(info, 0, sizeof *info);
  info->eta = NAN; /* until after_run: a failed run's summary says null */
  snprintf(info->dir, sizeof info->dir, "%s", sc->outdir);
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (!rank) bad = fs_prepare_output_dir(sc->outdir, err, errlen);
  MPI_Bcast(&bad, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
  if (bad) return 2;
  if (sc->geometry[0] && mesh_geometry(sc, geo, opt, err, errlen)) return 1;
  if (opt->restart) { /* the checkpoint is this scene's and this mesh's, before the earlier fields are opened */
    RunnerOptions check = *opt;
    check.outdir = sc->outdir, check.scene_file = doc->file, check.mesh_file = sc->msh;
    if (!rank) bad = checkpoint_precheck(&check, err, errlen);
    MPI_Bcast(&bad, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
    if (bad) {
      if (!rank && sc->geometry[0]) remove(sc->msh);
      return bad;
    }
  }
  int rc = run_problem(doc, sc, isc, opt, sizes, growth, base, info, err, errlen);
  if (!rank && opt->restart && sc->geometry[0]) remove(sc->msh); /* mesh.restart.msh: mesh.msh, by the checkpoint's hash */
  double cpu = cpu_seconds() - t0;
  MPI_Allreduce(&cpu, &info->cpu, 1, MPI_DOUBLE, MPI_SUM, PETSC_COMM_WORLD);
  return rc;
}
