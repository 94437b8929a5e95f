#include "sweep.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "../io/fsutil.h"
#include "../material/material_input.h"
#include "../material/material_point.h"
#include "../stepping/point_stepper.h"

#define MAXV 16

typedef struct {
  int    n;
  double v[MAXV];
} List;

static int read_list(YdDoc *doc, YdNode *m, const char *key, List *l, const double *dflt, int ndflt, char *err,
                     size_t errlen) {
  char path[64];
  snprintf(path, sizeof path, "matrix.%s", key);
  YdNode *nd = yd_get(m, key);
  if (!nd) {
    l->n = ndflt;
    memcpy(l->v, dflt, sizeof(double) * ndflt);
    return 0;
  }
  if (yd_doubles(doc, nd, path, l->v, -MAXV, &l->n, err, errlen)) return 1;
  if (l->n == 0) {
    snprintf(err, errlen, "%s:%d: key '%s': an empty list makes an empty sweep: expected 1 to %d values (omit the key "
             "for the default list)", doc->file, nd->line, path, MAXV);
    return 1;
  }
  return 0;
}

enum { START_CONFINED, START_TENSION, START_TINY_PC, NSTARTS };
static const char *start_names[NSTARTS] = {"confined", "tension", "tiny_pc"};

/* Initial stress and Cam-Clay IX state of a start: confined at -35 MPa (state from PROPS), isotropic
 * tension +5 MPa with pc = 30 MPa, or -1 MPa with pc = 1e-5 MPa (a collapsed surface). */
static void start_state(int which, PointScene *sc) {
  double s = which == START_CONFINED ? -35 : which == START_TENSION ? 5 : -1;
  double pc = which == START_TENSION ? 30 : 1e-5;
  memset(sc->statev0, 0, sizeof sc->statev0);
  for (int i = 0; i < 6; i++) sc->stress0[i] = i < 3 ? s : 0;
  if (which == START_CONFINED) return;
  material_state_isotropic(&sc->mat, sc->statev0, s, pc);
}

/* What a sweep scene gives: its name, the base material, the lists of the matrix, the reference steps, the output. */
typedef struct {
  const char *name;
  PointScene  base;
  List        dt, eta, inc, ang, phi;
  int         ref_steps;
  char        outdir[512];
} SweepInput;

/* Reads the sweep scene: name, material (no normal), matrix, reference_steps, output (or outdir_override). */
static int read_sweep(YdDoc *doc, const char *outdir_override, SweepInput *in, char *err, size_t errlen) {
  YdNode *root = doc->root, *m, *x;
  in->name     = "extremes";
  if ((x = yd_get(root, "name")) && yd_string(doc, x, "name", &in->name, err, errlen)) return 1;
  memset(&in->base, 0, sizeof in->base);
  if (!(x = yd_require(doc, root, "material", YD_MAPPING, "material", err, errlen)) ||
      material_read(doc, x, 6, &in->base.mat, err, errlen))
    return 1;
  if (!material_is_camclay9(&in->base.mat) || !material_has_phi(&in->base.mat)) {
    snprintf(err, errlen, "%s:%d: key 'material.umat': the extremes sweep sets Cam-Clay IX's PROPS and state; it runs "
             "with umat: camclay9 only", doc->file, x->line);
    return 1;
  }
  double b[3];
  if (material_normal(&in->base.mat, b)) {
    snprintf(err, errlen, "%s:%d: key 'material': the sweep sets the normal from matrix.bedding_angle: give no "
             "bedding_angle, normal or n1-n3 in the material", doc->file, x->line);
    return 1;
  }
  if (!(m = yd_require(doc, root, "matrix", YD_MAPPING, "matrix", err, errlen))) return 1;
  static const double d_dt[] = {0, 1e-12, 1e-8, 1e-4, 1, 1e4, 1e8, 1e12}, d_eta[] = {0, 1e10, 1e13, 1e20, 1e30},
                      d_inc[] = {1e-4, 1e-2, 0.1}, d_ang[] = {0, 45, 90}, d_phi[] = {0, 0.5, 1};
  if (read_list(doc, m, "dt", &in->dt, d_dt, 8, err, errlen) || read_list(doc, m, "eta", &in->eta, d_eta, 5, err, errlen) ||
      read_list(doc, m, "strain_increment", &in->inc, d_inc, 3, err, errlen) ||
      read_list(doc, m, "bedding_angle", &in->ang, d_ang, 3, err, errlen) ||
      read_list(doc, m, "phi", &in->phi, d_phi, 3, err, errlen))
    return 1;
  if (yd_check_unused(doc, m, "matrix", "dt, eta, strain_increment, bedding_angle, phi", err, errlen)) return 1;
  in->ref_steps = 400;
  if ((x = yd_get(root, "reference_steps")) && yd_int_range(doc, x, "reference_steps", 1, INT_MAX, &in->ref_steps, err, errlen)) return 1;
  snprintf(in->outdir, sizeof in->outdir, "out/sweep/%s", in->name);
  if ((x = yd_get(root, "output"))) {
    const char *d;
    if (yd_string(doc, yd_get(x, "directory"), "output.directory", &d, err, errlen)) return 1;
    snprintf(in->outdir, sizeof in->outdir, "%s", d);
    if (yd_check_unused(doc, x, "output", "directory", err, errlen)) return 1;
  }
  if (outdir_override && outdir_override[0]) snprintf(in->outdir, sizeof in->outdir, "%s", outdir_override);
  return yd_check_unused(doc, root, "", "scene, name, material, matrix, reference_steps, output", err, errlen);
}

/* One case of the matrix: a single step of the strain increment dir, and (converged, dt > 0) the same with
 * ref_steps steps; returns its status (0 converged, 1 cut back, 2 failed), its summary and its error. */
static int sweep_case(const SweepInput *in, int a, int f, int e, int s, int i, const double dir[6], int t, PointSummary *one,
                      double *error) {
  PointScene sc = in->base;
  Segment    sg;
  memset(&sg, 0, sizeof sg);
  double th = in->ang.v[a] * M_PI / 180, nn[3] = {sin(th), 0, cos(th)}, norm = 0;
  material_set_normal(&sc.mat, nn);
  material_set_phi(&sc.mat, in->phi.v[f]);
  material_set_viscosity(&sc.mat, in->eta.v[e]);
  material_set_tolerance(&sc.mat, 0); /* no accuracy control: the single step is judged, not resized */
  start_state(s, &sc);
  for (int k = 0; k < 6; k++) norm += dir[k] * dir[k];
  for (int k = 0; k < 6; k++) {
    sg.eq[k].kind         = EQ_STRAIN;
    sg.eq[k].target       = in->inc.v[i] * dir[k] / sqrt(norm);
    sg.eq[k].table_column = -1;
  }
  snprintf(sg.stage.name, sizeof sg.stage.name, "step");
  sg.stage.duration    = in->dt.v[t];
  sg.stage.steps.count = 1;
  sg.stage.steps.ratio = 1;
  sg.stage.instant     = in->dt.v[t] == 0;
  sc.seg      = &sg;
  sc.nseg     = 1;
  sc.outdir[0] = '\0';
  PointSummary fine;
  char         e1[1024];
  int          rc = point_run(&sc, NULL, one, e1, sizeof e1);
  int status = rc ? 2 : one->cutbacks ? 1 : 0; /* converged / cut back / failed */
  *error = NAN;
  if (!rc && in->dt.v[t] > 0) {
    sg.stage.steps.count = in->ref_steps;
    if (!point_run(&sc, NULL, &fine, e1, sizeof e1)) {
      double num = 0, den = 0;
      for (int k = 0; k < 6; k++) {
        num += pow(one->final_stress[k] - fine.final_stress[k], 2);
        den += pow(fine.final_stress[k], 2);
      }
      *error = sqrt(num) / fmax(sqrt(den), 1.0);
    }
  } else if (!rc) *error = 0; /* dt = 0 is the elastic update by definition */
  return status;
}

int sweep_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen) {
  SweepInput in;
  if (read_sweep(doc, outdir_override, &in, err, errlen)) return 1;
  const List *dt = &in.dt, *eta = &in.eta, *inc = &in.inc, *ang = &in.ang, *phi = &in.phi;

  /* Two directions of the strain increment: compression with shear, and extension with shear. */
  static const double dirs[2][6] = {{-0.5, 0.2, -1.0, 0.4, -0.3, 0.2}, {0.6, 0.3, 0.8, -0.4, 0.2, 0.3}};
  char path[600];
  if (fs_prepare_output_dir(in.outdir, err, errlen)) return 2;
  snprintf(path, sizeof path, "%s/sweep.csv", in.outdir);
  FILE *fp = fopen(path, "w");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
    return 1;
  }
  fprintf(fp, "dt,eta,strain_increment,direction,bedding_angle,phi,start,status,cutbacks,finite,error_vs_reference\n");
  int    count[3] = {0}, cases = 0, nonfinite = 0;
  double worst_err = 0;
  /* error statistics per time-step decade: converged single steps only */
  for (int a = 0; a < ang->n; a++)
    for (int f = 0; f < phi->n; f++)
      for (int e = 0; e < eta->n; e++)
        for (int s = 0; s < NSTARTS; s++)
          for (int i = 0; i < inc->n; i++)
            for (int d = 0; d < 2; d++)
              for (int t = 0; t < dt->n; t++) {
                PointSummary one;
                double       error;
                int          status = sweep_case(&in, a, f, e, s, i, dirs[d], t, &one, &error);
                if (!isnan(error)) worst_err = fmax(worst_err, error);
                count[status]++;
                cases++;
                if (!one.finite) nonfinite++;
                fprintf(fp, "%g,%g,%g,%s,%g,%g,%s,%s,%d,%d,%.3e\n", dt->v[t], eta->v[e], inc->v[i],
                        d ? "extension" : "compression", ang->v[a], phi->v[f], start_names[s],
                        status == 0 ? "converged" : status == 1 ? "cut back" : "failed", one.cutbacks, one.finite,
                        error);
              }
  fclose(fp);
  printf("extremes sweep %s: %d cases: %d converged in one step, %d cut back, %d failed, %d non-finite; "
         "largest error of a single step against %d steps: %.3e -> %s\n",
         in.name, cases, count[0], count[1], count[2], nonfinite, in.ref_steps, worst_err, path);
  if (count[2] || nonfinite) {
    snprintf(err, errlen, "extremes sweep: %d failed and %d non-finite cases (see %s)", count[2], nonfinite, path);
    return 1;
  }
  return 0;
}
