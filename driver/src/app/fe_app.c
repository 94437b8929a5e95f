/* A finite-element scene (scene: fe), with or without a rigid indenter: read it, mesh its geometry, set up
 * the problem (mesh, field, material, phi, initial stress, PETSc options of the scene), then run its stages
 * on the stage runner with the SNES or the indentation step solver. */
#include "fe_app.h"

#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>

#include "../contact/indent_scene.h"
#include "../fe/fe_problem.h"
#include "../fe/fe_scene.h"
#include "../io/fsutil.h"
#include "../io/gmsh_mesh.h"
#include "../stepping/fe_stepper.h"

/* The scene's PETSc options, each unless the command line already gives it. */
static PetscErrorCode apply_scene_options(const char *options) {
  char buf[1024], *tok, *save = NULL, *keys[64], *vals[64];
  int  n = 0;
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

PetscErrorCode app_runner_options(RunnerOptions *o) {
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof *o));
  o->max_steps = -1;
  PetscBool restart = PETSC_FALSE, elementary = PETSC_FALSE;
  PetscInt  every = 0, max_steps = -1, progress = 0;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Stages and steps (every scene kind)", NULL);
  PetscCall(PetscOptionsInt("-checkpoint_every", "write a checkpoint every N steps (0: none)", NULL, every, &every, NULL));
  PetscCall(PetscOptionsBool("-restart", "continue from the last complete checkpoint in the output directory", NULL, restart, &restart, NULL));
  PetscCall(PetscOptionsInt("-max_steps", "stop after N steps in all (-1: no limit)", NULL, max_steps, &max_steps, NULL));
  PetscCall(PetscOptionsInt("-progress_every", "a progress line every N steps (0: the scene's choice)", NULL, progress, &progress, NULL));
  PetscCall(PetscOptionsBool("-step_elementary", "the elementary step controller (dt' = dt 0.9 / ratio) instead of the PI controller", NULL,
                             elementary, &elementary, NULL));
  PetscOptionsEnd();
  o->elementary = elementary;
  o->checkpoint_every = (int)every, o->restart = restart, o->max_steps = (int)max_steps, o->progress_every = (int)progress;
  PetscFunctionReturn(0);
}

static int petsc_failure(PetscErrorCode ierr, char *err);

/* Every mirror group must lie in a plane with the normal given: x . n the same at all its nodes (to 1e-6 of the
   mesh's size). */
static int check_mirror_planes(YdDoc *doc, FeScene *sc, DM dm, char *err, size_t errlen) {
  for (int k = 0; k < sc->nfixed; k++) {
    const FeFixed *m = &sc->fixed[k];
    PetscReal      spread, size;
    if (!m->mirror) continue;
    if (fe_constraint_plane_spread(dm, m->group, m->normal, &spread, &size)) return petsc_failure(1, err);
    if (spread > 1e-6 * size) {
      snprintf(err, errlen, "%s:%d: key 'boundary.mirror[%d].normal': the group '%s' is not a plane normal to [%.6g, %.6g, %.6g]: "
               "x . normal varies by %.3g over its nodes (the mesh %s is %.3g across; expected at most 1e-6 of that)", doc->file, m->line,
               m->index, m->group, m->normal[0], m->normal[1], m->normal[2], spread, sc->msh, size);
      return 2;
    }
  }
  return 0;
}

/* Every group the scene names must be a physical group of the mesh. */
static int check_groups(YdDoc *doc, FeScene *sc, DM dm, char *err, size_t errlen) {
  const char *missing = NULL;
  PetscBool   has;
  static char base[64];
  for (int k = 0; k < sc->nfixed && !missing; k++)
    if (!DMHasLabel(dm, sc->fixed[k].group, &has) && !has) missing = sc->fixed[k].group;
  for (int k = 0; k < sc->npressure && !missing; k++) {
    snprintf(base, sizeof base, "%s", sc->pressure_group[k]);
    size_t len = strlen(base);
    if (len > 2 && base[len - 2] == '.' && strchr("xyz", base[len - 1])) base[len - 2] = '\0';
    if (!DMHasLabel(dm, base, &has) && !has) missing = base;
  }
  if (!missing) return check_mirror_planes(doc, sc, dm, err, errlen);
  char     groups[512] = "";
  PetscInt nl;
  DMGetNumLabels(dm, &nl);
  for (PetscInt l = 0; l < nl; l++) {
    const char *ln;
    DMGetLabelName(dm, l, &ln);
    if (!strcmp(ln, "depth") || !strcmp(ln, "celltype")) continue;
    size_t len = strlen(groups);
    snprintf(groups + len, sizeof groups - len, "%s%s", len ? ", " : "", ln);
  }
  snprintf(err, errlen, "%s: key 'boundary': group '%s' is not a physical group of the mesh %s (it has: %s)", doc->file, missing, sc->msh,
           groups);
  return 2;
}

/* Mesh the scene's geometry with gmsh (no shell) into the output directory: mesh.part.msh for a fresh run
 * (renamed once the run has produced its first step, so an earlier run's mesh stays until then),
 * mesh.msh for a restart (the same scene gives the same mesh). */
static int mesh_geometry(FeScene *sc, const RunnerOptions *opt, char *err, size_t errlen) {
  int rank, rc = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  snprintf(sc->msh, sizeof sc->msh, "%s/mesh%s.msh", sc->outdir, opt->restart ? "" : ".part");
  if (!rank) rc = gmsh_mesh(sc->geometry, sc->kin == KIN_3D ? 3 : 2, sc->ngmsh, (const char(*)[64])sc->gmsh_name, sc->gmsh_value, sc->msh,
                            err, errlen);
  MPI_Bcast(&rc, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
  return rc;
}

static PetscErrorCode print_sizes(FeScene *sc, FeProblem *p) {
  PetscInt ncell = p->cEnd - p->cStart, nall, ndof;
  Vec      tmp;
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(&ncell, &nall, 1, MPIU_INT, MPI_SUM, PETSC_COMM_WORLD));
  PetscCall(DMCreateGlobalVector(p->dm, &tmp));
  PetscCall(VecGetSize(tmp, &ndof));
  PetscCall(VecDestroy(&tmp));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "fe scene %s: %d cells, P%d, %d quadrature points per cell, %d unknowns, %d UMAT state slots per point\n",
              sc->name, (int)nall, sc->order, (int)p->nq, (int)ndof, (int)p->nsv));
  PetscFunctionReturn(0);
}

/* A PETSc error: main prints PETSc's own message for it (err left empty). */
static int petsc_failure(PetscErrorCode ierr, char *err) {
  err[0] = '\0';
  return (int)ierr;
}

static int run_problem(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, char *err, size_t errlen) {
  DM        dm;
  FeProblem p;
  PetscMemzero(&p, sizeof p);
  PetscErrorCode ierr = fe_mesh_create(PETSC_COMM_WORLD, sc->msh, sc->kin == KIN_3D ? 3 : 2, &dm);
  if (ierr) return petsc_failure(ierr, err);
  int rc = check_groups(doc, sc, dm, err, errlen);
  if (rc) {
    DMDestroy(&dm);
    return rc;
  }
  ierr = fe_problem_setup(&p, dm, sc->kin, sc->thickness, sc->order, &sc->mat, sc->fixed, sc->nfixed, (const char(*)[64])sc->pressure_group,
                          sc->npressure);
  if (ierr) return petsc_failure(ierr, err);
  snprintf(p.outdir, sizeof p.outdir, "%s", sc->outdir);
  if ((ierr = print_sizes(sc, &p)) || (ierr = fe_problem_set_initial_stress(&p, sc->stress0)) ||
      (ierr = fe_problem_set_phi(&p, sc->phi_mean, sc->phi_std, sc->phi_lo, sc->phi_hi, sc->phi_seed, sc->phi_corr)))
    return petsc_failure(ierr, err);
  opt->outdir = sc->outdir, opt->scene_file = doc->file, opt->fields_every = sc->fields_every;
  opt->part_file = sc->geometry[0] && !opt->restart ? sc->msh : NULL;
  rc = sc->indenter ? indent_stepper_run(sc, isc, &p, opt, err, errlen) : fe_stepper_run(sc, &p, opt, err, errlen);
  fe_problem_destroy(&p);
  DMDestroy(&dm);
  return rc;
}

int fe_app_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen) {
  static FeScene     sc; /* large: kept off the stack */
  static IndentScene isc;
  RunnerOptions      opt;
  if (fe_scene_read(doc, &sc, err, errlen)) return 2;
  if (sc.indenter && indent_scene_read(doc, &sc, &isc, err, errlen)) return 2;
  if (outdir_override && outdir_override[0]) snprintf(sc.outdir, sizeof sc.outdir, "%s", outdir_override);
  if (app_runner_options(&opt)) return 1;
  int rank, bad = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (!rank) bad = fs_prepare_output_dir(sc.outdir, err, errlen);
  MPI_Bcast(&bad, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
  if (bad) return 2;
  if (sc.geometry[0] && mesh_geometry(&sc, &opt, err, errlen)) return 1;
  if (apply_scene_options(sc.solver_options)) return 1;
  return run_problem(doc, &sc, &isc, &opt, err, errlen);
}
