/* Adaptation by rerun (fe_adapt.h; docs/adapt.md). */
#include "fe_adapt.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../io/binfile.h"
#include "../io/fsutil.h"
#include "../io/options.h"

/* The options block (declared with the others by main, read again here over the scene's mesh.adapt). */
PetscErrorCode fe_adapt_declare(PetscInt *levels, PetscReal *growth, PetscBool *set_levels, PetscBool *set_growth) {
  PetscFunctionBeginUser;
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Mesh adaptation by rerun (FE and indentation scenes; docs/adapt.md)", NULL);
  PetscCall(options_int(PetscOptionsObject, "-adapt_levels", "reruns on meshes made from the error indicator, over mesh.adapt.levels (0: none)",
                        *levels, 0, 8, levels, set_levels));
  PetscCall(options_real(PetscOptionsObject, "-adapt_growth", "cells of a level over the previous level's, over mesh.adapt.growth", *growth,
                         1.2, 8, 0, growth, set_growth));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode fe_adapt_options(YdDoc *doc, FeScene *sc, PetscBool restart, char *err, size_t errlen, int *bad) {
  PetscInt  levels = sc->adapt.levels;
  PetscReal growth = sc->adapt.growth;
  PetscBool set_levels, set_growth;
  PetscFunctionBeginUser;
  *bad = 0;
  PetscCall(fe_adapt_declare(&levels, &growth, &set_levels, &set_growth));
  if (set_growth && !(growth >= 1.2 && growth <= 8)) {
    snprintf(err, errlen, "option -adapt_growth %g: expected the ratio of cells from one level to the next, 1.2 to 8", (double)growth);
    *bad = 2;
  } else if (levels > 0 && !sc->geometry[0]) {
    snprintf(err, errlen, "%s: option -adapt_levels %d: adaptation meshes the geometry again, but the scene gives mesh.file (a .msh without its "
             "geometry): give mesh.geometry (a gmsh .geo)", doc->file, (int)levels);
    *bad = 2;
  } else if (levels > 0 && restart) {
    snprintf(err, errlen, "%s: -restart with mesh adaptation (%s %d): a level is always run from its start; rerun without -restart", doc->file,
             set_levels ? "-adapt_levels" : "mesh.adapt.levels", (int)levels);
    *bad = 2;
  }
  sc->adapt.levels = (int)levels, sc->adapt.growth = growth;
  PetscFunctionReturn(0);
}

/* The .geo of level k: the scene's own, its physical groups and parameters unchanged, with the size field of
   the level before as its background field (a gmsh PostView field of the view in sizes). gmsh resolves the paths
   in an Include or a Merge against the including file's folder, not the working directory: both by their absolute
   paths (both exist: level 0 has meshed the scene's .geo, level k - 1 written its sizes). */
static int write_level_geo(const FeScene *sc, const char *geo, const char *sizes, char *err, size_t errlen) {
  char        abs_paths[2][PATH_MAX];
  const char *paths[2] = {sc->geometry, sizes}, *keys[2] = {"mesh.geometry", "mesh.adapt"};
  for (int i = 0; i < 2; i++) {
    if (!realpath(paths[i], abs_paths[i])) {
      snprintf(err, errlen, "%s: %s: cannot resolve the path for the adapted geometry", paths[i], keys[i]);
      return 1;
    }
    if (strchr(abs_paths[i], '"')) {
      snprintf(err, errlen, "%s: mesh.adapt: a path with a double quote cannot be named in a .geo", abs_paths[i]);
      return 1;
    }
  }
  FILE *fp = fopen(geo, "w");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot write the adapted geometry", geo);
    return 1;
  }
  fprintf(fp, "// The scene's geometry with the element sizes made from the error indicator of the level before (docs/adapt.md).\n"
              "Include \"%s\";\nMerge \"%s\";\nField[901] = PostView;\nField[901].ViewIndex = PostProcessing.NbViews - 1;\n"
              "Background Field = 901;\n", abs_paths[0], abs_paths[1]);
  return fclose(fp) ? (snprintf(err, errlen, "%s: cannot write the adapted geometry", geo), 1) : 0;
}

/* The answer's files into OUT (rank 0), once the last level is done. */
static int publish(const char *outdir, const char *level_dir, char *err, size_t errlen) {
  static const char *const files[] = {"history.csv", "fields.h5", "fields.xmf", "mesh.msh"};
  char                     src[1200], dst[1200];
  for (int i = 0; i < 4; i++) {
    snprintf(src, sizeof src, "%s/%s", level_dir, files[i]);
    snprintf(dst, sizeof dst, "%s/%s", outdir, files[i]);
    if (fs_copy_file(src, dst)) {
      snprintf(err, errlen, "%s: cannot copy the last level's %s into the output directory", dst, files[i]);
      return 1;
    }
  }
  return 0;
}

/* The ratio by which the reported quantities' errors fall from level l - 1 to level l (docs/adapt.md, "The error
   estimate"): the square of the fall of the error indicator, the run's own estimate of its energy error (an output's
   error goes as the energy errors of the problem and of its dual: Becker & Rannacher, Acta Numerica 10 (2001) 1-102).
   Where the indicator fell by less than 10 % the levels predict nothing: the assumed rate of uniform refinement,
   the energy error ~ cells^(-k/d), squared, in its place. */
static double error_ratio(const RunInfo *lv, int l, int order, int dim) {
  const double g = pow(lv[l - 1].eta / lv[l].eta, 2);
  return isfinite(g) && g > 1.21 ? g : pow((double)lv[l].cells / lv[l - 1].cells, 2.0 * order / dim);
}

/* One quantity's error from its values q on the levels 0..n-1 and the ratios g (g[l]: level l - 1's error over level
   l's): Richardson's, the last change over g - 1; from three levels, the level before's own estimate reduced by g
   when it is the larger, so that a last change small by chance (meshes of one density scatter) does not pass for
   convergence. */
static double quantity_error(const double *q, const double *g, int n) {
  double e = fabs(q[n - 1] - q[n - 2]) / (g[n - 1] - 1);
  if (n >= 3) e = fmax(e, fabs(q[n - 2] - q[n - 3]) / (g[n - 2] - 1) / g[n - 1]);
  return e;
}

/* The mesh error of every reported quantity from the levels' answers (docs/adapt.md, "The error estimate"). */
static void estimate(const RunInfo *levels, int n, int order, int dim, MeshError *me) {
  double g[16], end[16], change[16];
  memset(me, 0, sizeof *me);
  if (n < 2 || n > 16) return;
  const RunnerSummary *a = &levels[n - 1].sum;
  for (int l = 1; l < n; l++) g[l] = error_ratio(levels, l, order, dim);
  me->have = 1, me->ratio = g[n - 1];
  me->how  = n >= 3 ? "the larger of the last change and the level before's estimate, each over the fall of the squared error indicator (docs/adapt.md)"
                    : "the last change over the fall of the squared error indicator, from two levels: nothing checks it yet, "
                      "a further level does (docs/adapt.md)";
  for (int k = 0; k <= a->nstages_done; k++)
    for (int q = 0; q < a->nreport; q++) {
      for (int l = 0; l < n; l++) {
        const RunnerSummary *s = &levels[l].sum;
        end[l]    = k <= s->nstages_done ? s->report[k][q] : NAN;
        change[l] = k > 0 && k <= s->nstages_done ? s->report[k][q] - s->report[k - 1][q] : 0;
      }
      me->end[k][q]    = quantity_error(end, g, n);
      me->change[k][q] = quantity_error(change, g, n);
    }
}

/* The folder of level k of a run into outdir. */
static void level_dir(const char *outdir, int k, char *dir, size_t n) { snprintf(dir, n, "%.480s/adapt/level%d", outdir, k); }

/* Whether every reported quantity's estimated error is within tol of its size (the changes over the stages, and
   the values at the stages' ends). */
static int within_tol(const RunnerSummary *s, const MeshError *me, double tol) {
  for (int k = 1; k <= s->nstages_done; k++)
    for (int q = 0; q < s->nreport; q++) {
      const double change = fabs(s->report[k][q] - s->report[k - 1][q]), end = fabs(s->report[k][q]);
      if (me->end[k][q] > tol * end || (change > 1e-12 * end && me->change[k][q] > tol * change)) return 0;
    }
  return 1;
}

/* The estimate of the levels 0..n-1 into me, and whether it ends the adaptation (mesh.adapt.tol reached). */
static int estimate_levels(const FeScene *sc, const RunInfo *lv, int n, MeshError *me) {
  estimate(lv, n, sc->order, sc->kin == KIN_3D ? 3 : 2, me);
  return me->have && sc->adapt.tol > 0 && within_tol(&lv[n - 1].sum, me, sc->adapt.tol);
}

/* Level k into OUT/adapt/level<k>: meshed from the scene (k = 0) or from the sizes of level k - 1. */
static int run_level(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, const char *outdir, int k, const RunInfo *prev, RunInfo *info,
                     char *err, size_t errlen) {
  char dir[512], geo[700], sizes[700], prev_sizes[700];
  int  rank, rc = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  level_dir(outdir, k, dir, sizeof dir);
  snprintf(sc->outdir, sizeof sc->outdir, "%s", dir);
  snprintf(sizes, sizeof sizes, "%s/sizes.pos", dir);
  snprintf(geo, sizeof geo, "%s/adapted.geo", dir);
  if (k > 0) {
    snprintf(prev_sizes, sizeof prev_sizes, "%s/sizes.pos", prev->dir);
    if (!rank) rc = fs_prepare_output_dir(dir, err, errlen) ? 2 : write_level_geo(sc, geo, prev_sizes, err, errlen);
    MPI_Bcast(&rc, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
    if (rc) return rc;
  }
  if (!rank) { /* kept only once the level is run to its end (level_save): a failed or stopped level is never reused */
    char kept[700];
    snprintf(kept, sizeof kept, "%s/level.txt", dir);
    remove(kept);
  }
  PetscPrintf(PETSC_COMM_WORLD, "adapt: level %d of %d into %s\n", k, sc->adapt.levels, dir);
  /* gmsh makes more cells than a size field predicts (its gradation, the boundary's sizes), by a ratio that
     changes little from level to level: the targets grow by growth from the last prediction, not from the cells
     made, so that the levels grow by about growth */
  const double base = k > 0 ? prev->predicted : 0;
  rc = fe_app_run_once(doc, sc, isc, opt, k > 0 ? geo : NULL, k < sc->adapt.levels ? sizes : NULL, sc->adapt.growth, base, info, err, errlen);
  return rc;
}

/* What shapes the levels' meshes (docs/adapt.md, "Kept meshes"): the scene file, its .geo, the driver's executable
   (with the UMAT linked into it), the growth and the PROPS overrides of the command line. A level kept from an earlier run with the same key is reused, not run again. */
static unsigned long long level_key(const YdDoc *doc, const FeScene *sc) {
  char               set[2048] = "", text[2200];
  PetscBool          given;
  unsigned long long h = (binfile_hash(doc->file) * 1099511628211ULL ^ binfile_hash(sc->geometry)) * 1099511628211ULL ^ binfile_hash("/proc/self/exe");
  if (PetscOptionsGetString(NULL, NULL, "-material_set", set, sizeof set, &given)) set[0] = '\0';
  snprintf(text, sizeof text, "%.6g|%s", sc->adapt.growth, set);
  for (const char *c = text; *c; c++) h = (h ^ (unsigned char)*c) * 1099511628211ULL;
  return h;
}

/* level.txt of a level run to its end (rank 0): its key, its RunInfo's numbers and reported quantities. */
static void level_save(const RunInfo *r, unsigned long long key) {
  char  path[700];
  if (r->sum.failed || r->sum.stopped) return; /* stopped by -max_steps: not the level a later run may reuse */
  snprintf(path, sizeof path, "%s/level.txt", r->dir);
  FILE *fp = fopen(path, "w");
  if (!fp) return; /* only a cache: the next run runs the level again */
  const RunnerSummary *s = &r->sum;
  fprintf(fp, "camclay9-adapt-level 1 %llu\n%ld %ld %.17g %.17g %.17g %.17g %d %d %d %ld %d %d\n", key, r->cells, r->unknowns, r->eta, r->cpu,
          r->predicted, s->wall, s->steps, s->cutbacks, s->its, s->umat_calls, s->nstages_done, s->nreport);
  for (int k = 0; k <= s->nstages_done; k++)
    for (int q = 0; q < s->nreport; q++) fprintf(fp, "%.17g%s", s->report[k][q], q + 1 < s->nreport ? " " : "\n");
  fclose(fp);
}

/* A level kept with this key (and its size field, when a level follows it): 1 and r filled, else 0. */
static int level_load(const char *dir, unsigned long long key, int need_sizes, RunInfo *r) {
  char               path[700];
  unsigned long long got = 0;
  int                ok = 1, version = 0;
  RunnerSummary     *s = &r->sum;
  memset(r, 0, sizeof *r);
  snprintf(r->dir, sizeof r->dir, "%s", dir);
  snprintf(path, sizeof path, "%s/sizes.pos", dir);
  if (need_sizes && access(path, R_OK)) return 0;
  snprintf(path, sizeof path, "%s/level.txt", dir);
  FILE *fp = fopen(path, "r");
  if (!fp) return 0;
  ok = fscanf(fp, "camclay9-adapt-level %d %llu", &version, &got) == 2 && version == 1 && got == key;
  ok = ok && fscanf(fp, "%ld %ld %lg %lg %lg %lg %d %d %d %ld %d %d", &r->cells, &r->unknowns, &r->eta, &r->cpu, &r->predicted, &s->wall, &s->steps,
                    &s->cutbacks, &s->its, &s->umat_calls, &s->nstages_done, &s->nreport) == 12;
  ok = ok && s->nstages_done >= 0 && s->nstages_done <= RUNNER_MAX_STAGES && s->nreport >= 0 && s->nreport <= RUNNER_MAX_REPORT;
  for (int k = 0; ok && k <= s->nstages_done; k++)
    for (int q = 0; ok && q < s->nreport; q++) ok = fscanf(fp, "%lg", &s->report[k][q]) == 1;
  fclose(fp);
  return ok;
}

/* Level k kept from an earlier run (rank 0 decides, every rank gets it): 1 and lv filled. */
static int reuse_level(const char *outdir, int k, int last, unsigned long long key, RunInfo *lv) {
  int  rank, ok = 0;
  char dir[512];
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  level_dir(outdir, k, dir, sizeof dir);
  if (!rank) ok = k < last && level_load(dir, key, 1, lv);
  MPI_Bcast(&ok, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  if (ok) MPI_Bcast(lv, (int)sizeof *lv, MPI_BYTE, 0, PETSC_COMM_WORLD);
  lv->kept = ok;
  return ok;
}

int fe_adapt_run(YdDoc *doc, FeScene *sc, IndentScene *isc, RunnerOptions *opt, char *err, size_t errlen) {
  static RunInfo lv[9];
  char           outdir[512];
  MeshError      me;
  int            rank, rc = 0, n = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  snprintf(outdir, sizeof outdir, "%s", sc->outdir);
  memset(&me, 0, sizeof me);
  unsigned long long key = level_key(doc, sc);
  int                fresh = 0; /* a level was run: the levels after it are run too */
  for (int k = 0; k <= sc->adapt.levels && !rc; k++) {
    int stop, kept = !fresh && reuse_level(outdir, k, sc->adapt.levels, key, &lv[k]);
    if (kept) {
      stop = estimate_levels(sc, lv, k + 1, &me);
      PetscPrintf(PETSC_COMM_WORLD, "adapt: level %d kept from an earlier run of this scene (%s, %ld cells; docs/adapt.md, \"Kept meshes\")%s\n", k,
                  lv[k].dir, lv[k].cells, stop ? ": the answer, run again" : "");
      n = k + 1;
      if (!stop) continue;
    }
    fresh = 1, lv[k].kept = 0; /* run here, also where a kept level is the answer and runs again */
    rc    = run_level(doc, sc, isc, opt, outdir, k, k ? &lv[k - 1] : NULL, &lv[k], err, errlen);
    if (rc && !rank) { /* the level's summary beside its files; OUT's as summary.json.part: nothing of OUT was replaced */
      run_summary_failed(sc, lv[k].dir, lv, k + 1, k, lv[k].sum.replaced, rc, err);
      run_summary_failed(sc, outdir, lv, k + 1, k, 0, rc, err);
    }
    if (rc) break;
    if (!rank) level_save(&lv[k], key);
    n    = k + 1;
    stop = estimate_levels(sc, lv, n, &me);
    if (!rank) {
      printf("adapt: level %d: %ld cells, %ld unknowns, %.1f s CPU\n", k, lv[k].cells, lv[k].unknowns, lv[k].cpu);
      run_summary_print(sc, &lv[k], me.have ? &me : NULL);
      /* the level's own summary.json, its estimate from the levels so far */
      RunEnd end = {NULL, -1, lv[k].sum.replaced};
      if (run_summary_write(sc, lv[k].dir, lv, n, &me, &end, err, errlen)) printf("adapt: %s\n", err);
    }
    if (stop) break;
  }
  snprintf(sc->outdir, sizeof sc->outdir, "%s", outdir);
  if (rc) return rc;
  if (!rank) rc = publish(outdir, lv[n - 1].dir, err, errlen) || run_summary_write(sc, outdir, lv, n, &me, NULL, err, errlen);
  MPI_Bcast(&rc, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(err, (int)errlen, MPI_CHAR, 0, PETSC_COMM_WORLD);
  return rc;
}
