#include "fe_run.h"

#include <errno.h>
#include <math.h>
#include <petscsnes.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "../material/material_input.h"
#include "../point/point_run.h"
#include "fe_output.h"
#include "fe_problem.h"

#define MAXSTAGES 16

enum { FN_RAMP, FN_EXP, FN_TABLE };

typedef struct {
  char      name[64];
  double    duration;
  int       instant, adaptive, count, creep;
  double    ratio, dt_first, dt_min, dt_max, growth;
  double    pressure[FE_MAX_GROUPS]; /* at the end of the stage; NAN: keep */
  /* or a time function of the stage time: P0 exp(k t), or a table */
  int       fn[FE_MAX_GROUPS];       /* FN_RAMP (the target above), FN_EXP, FN_TABLE */
  double    P0[FE_MAX_GROUPS], k[FE_MAX_GROUPS];
  int       nrow[FE_MAX_GROUPS];
  double   *tab_t[FE_MAX_GROUPS], *tab_v[FE_MAX_GROUPS];
  double    evp_rate_below;          /* 0: no end condition */
} Stage;

typedef struct {
  char         name[128], outdir[512], msh[1024];
  char         geometry[1024], gmsh_params[1024]; /* a gmsh .geo meshed at run time, with -setnumber */
  int          order;
  Kinematics   kin;
  double       thickness;
  UmatMaterial mat;
  double       phi_mean, phi_std, phi_lo, phi_hi, phi_corr;
  int          phi_seed;
  double       stress0[6], pressure0[FE_MAX_GROUPS];
  int          nfixed;
  FeFixed      fixed[8];
  int          npressure;
  char         pressure_group[FE_MAX_GROUPS][64];
  int          nstage;
  Stage        stage[MAXSTAGES];
  int          axis;
  int          fields_every;
  char         solver_options[1024]; /* PETSc options from the scene; the command line wins */  /* field output every N steps, besides the start and each stage's end */
} FeScene;

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

static int read_steps(YdDoc *doc, YdNode *x, const char *path, Stage *st, char *err, size_t errlen) {
  YdNode *v;
  st->count = 1, st->ratio = 1, st->growth = 1.5;
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, path, err, errlen)) return 1;
  if ((v = yd_get(x, "adaptive")) && yd_bool(doc, v, path, &st->adaptive, err, errlen)) return 1;
  if (st->adaptive) {
    st->dt_first = st->duration / 100, st->dt_min = 1e-12 * fmax(st->duration, 1), st->dt_max = st->duration;
    if ((v = yd_get(x, "first")) && yd_double(doc, v, path, &st->dt_first, err, errlen)) return 1;
    if ((v = yd_get(x, "min")) && yd_double(doc, v, path, &st->dt_min, err, errlen)) return 1;
    if ((v = yd_get(x, "max")) && yd_double(doc, v, path, &st->dt_max, err, errlen)) return 1;
    if ((v = yd_get(x, "growth")) && yd_double(doc, v, path, &st->growth, err, errlen)) return 1;
    if (!(st->dt_first > 0 && st->dt_min > 0 && st->dt_max >= st->dt_min && st->growth >= 1))
      FAIL("%s:%d: key '%s': expected first > 0, min > 0, max >= min, growth >= 1", doc->file, x->line, path);
    return yd_check_unused(doc, x, path, "adaptive, first, min, max, growth", err, errlen);
  }
  if ((v = yd_get(x, "count")) && yd_int(doc, v, path, &st->count, err, errlen)) return 1;
  if (st->count < 1) FAIL("%s:%d: key '%s.count': expected >= 1", doc->file, x->line, path);
  if ((v = yd_get(x, "ratio")) && yd_double(doc, v, path, &st->ratio, err, errlen)) return 1;
  return yd_check_unused(doc, x, path, "count, ratio (fixed) or adaptive, first, min, max, growth", err, errlen);
}

/* A pressure of a stage: a number (reached at the stage's end), {exp: {P0, k}} (P0 exp(k t) in the
 * stage time t), or {table: {file, time, value, time_factor, factor}} (linear interpolation). */
static int read_pressure(YdDoc *doc, YdNode *nd, const char *path, Stage *g, int gi, char *err, size_t errlen) {
  YdNode *x;
  g->fn[gi] = FN_RAMP;
  if (nd->kind == YD_SCALAR) return yd_double(doc, nd, path, &g->pressure[gi], err, errlen);
  if (yd_expect(doc, nd, YD_MAPPING, path, err, errlen)) return 1;
  char sub[200];
  if ((x = yd_get(nd, "exp"))) {
    g->fn[gi] = FN_EXP;
    snprintf(sub, sizeof sub, "%s.exp", path);
    if (yd_double(doc, yd_get(x, "P0"), sub, &g->P0[gi], err, errlen) || yd_double(doc, yd_get(x, "k"), sub, &g->k[gi], err, errlen)) return 1;
    if (yd_check_unused(doc, x, sub, "P0, k", err, errlen)) return 1;
  } else if ((x = yd_get(nd, "table"))) {
    const char *file, *tc, *vc;
    double      tf = 1, vf = 1;
    YdNode     *y;
    g->fn[gi] = FN_TABLE;
    snprintf(sub, sizeof sub, "%s.table", path);
    if (yd_string(doc, yd_get(x, "file"), sub, &file, err, errlen) || yd_string(doc, yd_get(x, "time"), sub, &tc, err, errlen) ||
        yd_string(doc, yd_get(x, "value"), sub, &vc, err, errlen))
      return 1;
    if ((y = yd_get(x, "time_factor")) && yd_double(doc, y, sub, &tf, err, errlen)) return 1;
    if ((y = yd_get(x, "factor")) && yd_double(doc, y, sub, &vf, err, errlen)) return 1;
    if (yd_check_unused(doc, x, sub, "file, time, value, time_factor, factor", err, errlen)) return 1;
    FILE *fp = fopen(file, "r");
    if (!fp) FAIL("%s:%d: key '%s.file': cannot open '%s': %s", doc->file, x->line, sub, file, strerror(errno));
    char line[4096], *names[64];
    int  ti = -1, vi = -1, n = 0;
    do {
      if (!fgets(line, sizeof line, fp)) {
        fclose(fp);
        FAIL("%s: no header line", file);
      }
    } while (line[0] == '#');
    for (char *tok = strtok(line, ",\r\n"); tok && n < 64; tok = strtok(NULL, ",\r\n")) names[n++] = tok;
    for (int j = 0; j < n; j++) ti = !strcmp(names[j], tc) ? j : ti, vi = !strcmp(names[j], vc) ? j : vi;
    if (ti < 0 || vi < 0) {
      fclose(fp);
      FAIL("%s:%d: key '%s': the table %s has no column '%s'", doc->file, x->line, sub, file, ti < 0 ? tc : vc);
    }
    int cap = 64, rows = 0;
    g->tab_t[gi] = malloc(sizeof(double) * cap), g->tab_v[gi] = malloc(sizeof(double) * cap);
    while (fgets(line, sizeof line, fp)) {
      if (line[0] == '#' || line[0] == '\n') continue;
      double vals[64];
      int    m = 0;
      for (char *tok = strtok(line, ",\r\n"); tok && m < 64; tok = strtok(NULL, ",\r\n")) vals[m++] = strtod(tok, NULL);
      if (m <= (ti > vi ? ti : vi)) continue;
      if (rows == cap) cap *= 2, g->tab_t[gi] = realloc(g->tab_t[gi], sizeof(double) * cap), g->tab_v[gi] = realloc(g->tab_v[gi], sizeof(double) * cap);
      g->tab_t[gi][rows] = vals[ti] * tf, g->tab_v[gi][rows] = vals[vi] * vf, rows++;
    }
    fclose(fp);
    if (rows < 2) FAIL("%s: the table needs two rows at least", file);
    g->nrow[gi] = rows;
  } else {
    FAIL("%s:%d: key '%s': expected a number, {exp: {P0, k}} or {table: {...}}", doc->file, nd->line, path);
  }
  return yd_check_unused(doc, nd, path, "exp, table", err, errlen);
}

/* The pressure of group k at stage time ts (lambda: the ramp's fraction then). */
static double stage_pressure(const Stage *g, int k, double start, double target, double lambda, double ts) {
  switch (g->fn[k]) {
  case FN_EXP: return g->P0[k] * exp(g->k[k] * ts);
  case FN_TABLE: {
    const double *t = g->tab_t[k], *v = g->tab_v[k];
    int           n = g->nrow[k], j = 0;
    if (ts <= t[0]) return v[0];
    if (ts >= t[n - 1]) return v[n - 1];
    while (t[j + 1] < ts) j++;
    return v[j] + (v[j + 1] - v[j]) * (ts - t[j]) / (t[j + 1] - t[j]);
  }
  default: return start + lambda * (target - start);
  }
}

static int component_of(const char *s) {
  return !strcmp(s, "x") || !strcmp(s, "0") ? 0 : !strcmp(s, "y") || !strcmp(s, "1") ? 1 : !strcmp(s, "z") || !strcmp(s, "2") ? 2 : -1;
}

static int fe_scene_read(YdDoc *doc, FeScene *sc, char *err, size_t errlen) {
  YdNode     *root = doc->root, *x, *v;
  const char *s;
  memset(sc, 0, sizeof *sc);
  snprintf(sc->name, sizeof sc->name, "fe");
  yd_get(root, "scene");
  if ((x = yd_get(root, "name"))) {
    if (yd_string(doc, x, "name", &s, err, errlen)) return 1;
    snprintf(sc->name, sizeof sc->name, "%s", s);
  }
  if ((x = yd_get(root, "units")))
    for (size_t i = 0; i < x->n; i++) x->used[i] = 1;
  snprintf(sc->outdir, sizeof sc->outdir, "out/%s", sc->name);
  if ((x = yd_get(root, "output"))) {
    if ((v = yd_get(x, "directory"))) {
      if (yd_string(doc, v, "output.directory", &s, err, errlen)) return 1;
      snprintf(sc->outdir, sizeof sc->outdir, "%s", s);
    }
    if ((v = yd_get(x, "fields_every")) && yd_int(doc, v, "output.fields_every", &sc->fields_every, err, errlen)) return 1;
    if (yd_check_unused(doc, x, "output", "directory, fields_every", err, errlen)) return 1;
  }
  /* Mesh: a gmsh geometry (meshed now, with parameters), a .msh file, or a box (tests). */
  YdNode *mesh = yd_get(root, "mesh");
  if (yd_expect(doc, mesh, YD_MAPPING, "mesh", err, errlen)) return 1;
  sc->order = 1;
  if ((v = yd_get(mesh, "order")) && yd_int(doc, v, "mesh.order", &sc->order, err, errlen)) return 1;
  if (sc->order != 1 && sc->order != 2) FAIL("%s:%d: key 'mesh.order': expected 1 or 2, got %d", doc->file, v->line, sc->order);
  YdNode *geo = yd_get(mesh, "geometry"), *file = yd_get(mesh, "file");
  if (!!geo + !!file != 1)
    FAIL("%s:%d: key 'mesh': give exactly one of geometry (a gmsh .geo, meshed now) or file (a .msh)", doc->file, mesh->line);
  {
    const char *path;
    if (yd_string(doc, geo ? geo : file, geo ? "mesh.geometry" : "mesh.file", &path, err, errlen)) return 1;
    FILE *fp = fopen(path, "r");
    if (!fp) FAIL("%s:%d: key 'mesh.%s': cannot open '%s': %s", doc->file, (geo ? geo : file)->line,
                  geo ? "geometry" : "file", path, strerror(errno));
    fclose(fp);
    snprintf(file ? sc->msh : sc->geometry, sizeof sc->msh, "%s", path);
    if ((v = yd_get(mesh, "parameters"))) {
      if (yd_expect(doc, v, YD_MAPPING, "mesh.parameters", err, errlen)) return 1;
      for (size_t i = 0; i < v->n; i++) {
        double val;
        v->used[i] = 1;
        if (yd_double(doc, v->items[i], "mesh.parameters", &val, err, errlen)) return 1;
        size_t len = strlen(sc->gmsh_params);
        snprintf(sc->gmsh_params + len, sizeof sc->gmsh_params - len, " -setnumber %s %.17g", v->keys[i], val);
      }
    }
  }
  sc->kin       = KIN_3D;
  sc->thickness = 1;
  if ((v = yd_get(mesh, "kinematics"))) {
    if (yd_string(doc, v, "mesh.kinematics", &s, err, errlen)) return 1;
    if (!strcmp(s, "3d")) sc->kin = KIN_3D;
    else if (!strcmp(s, "plane_strain")) sc->kin = KIN_PLANE_STRAIN;
    else if (!strcmp(s, "axisymmetric")) sc->kin = KIN_AXISYMMETRIC;
    else FAIL("%s:%d: key 'mesh.kinematics': expected 3d, plane_strain or axisymmetric, got '%s'", doc->file, v->line, s);
  }
  if ((v = yd_get(mesh, "thickness"))) {
    if (yd_double(doc, v, "mesh.thickness", &sc->thickness, err, errlen)) return 1;
    if (!(sc->thickness > 0) || sc->kin != KIN_PLANE_STRAIN)
      FAIL("%s:%d: key 'mesh.thickness': expected > 0, and only with kinematics: plane_strain", doc->file, v->line);
  }
  if (yd_check_unused(doc, mesh, "mesh", "geometry, parameters, file, order, kinematics, thickness", err, errlen)) return 1;

  if (material_read(doc, yd_get(root, "material"), sc->kin == KIN_3D ? 6 : 4, &sc->mat, err, errlen)) return 1;
  sc->phi_mean = sc->mat.phi_slot >= 0 ? sc->mat.props[sc->mat.phi_slot] : 0;
  sc->phi_lo = 0, sc->phi_hi = 1, sc->phi_seed = 1;
  if ((x = yd_get(root, "phi"))) {
    if (sc->mat.phi_slot < 0) FAIL("%s:%d: key 'phi': this UMAT has no hard-frame fraction", doc->file, x->line);
    if (yd_double(doc, yd_get(x, "mean"), "phi.mean", &sc->phi_mean, err, errlen)) return 1;
    if ((v = yd_get(x, "std")) && yd_double(doc, v, "phi.std", &sc->phi_std, err, errlen)) return 1;
    if ((v = yd_get(x, "min")) && yd_double(doc, v, "phi.min", &sc->phi_lo, err, errlen)) return 1;
    if ((v = yd_get(x, "max")) && yd_double(doc, v, "phi.max", &sc->phi_hi, err, errlen)) return 1;
    if ((v = yd_get(x, "seed")) && yd_int(doc, v, "phi.seed", &sc->phi_seed, err, errlen)) return 1;
    if ((v = yd_get(x, "correlation_length")) &&
        (yd_double(doc, v, "phi.correlation_length", &sc->phi_corr, err, errlen) || sc->phi_corr < 0))
      FAIL("%s:%d: key 'phi.correlation_length': expected a length >= 0", doc->file, v->line);
    if (!(0 <= sc->phi_lo && sc->phi_lo <= sc->phi_mean && sc->phi_mean <= sc->phi_hi && sc->phi_hi <= 1 && sc->phi_std >= 0))
      FAIL("%s:%d: key 'phi': expected 0 <= min <= mean <= max <= 1 and std >= 0", doc->file, x->line);
    if (yd_check_unused(doc, x, "phi", "mean, std, min, max, seed, correlation_length", err, errlen)) return 1;
  }
  YdNode *initial_pressure = NULL;
  if ((x = yd_get(root, "initial"))) {
    if ((v = yd_get(x, "stress")) && yd_doubles(doc, v, "initial.stress", sc->stress0, 6, NULL, err, errlen)) return 1;
    initial_pressure = yd_get(x, "pressure");
    if (yd_check_unused(doc, x, "initial", "stress (both frames), pressure (in equilibrium with it)", err, errlen)) return 1;
  }
  YdNode *bc = yd_get(root, "boundary");
  if (yd_expect(doc, bc, YD_MAPPING, "boundary", err, errlen)) return 1;
  if ((x = yd_get(bc, "fixed"))) {
    if (yd_expect(doc, x, YD_SEQUENCE, "boundary.fixed", err, errlen)) return 1;
    for (size_t k = 0; k < x->n && k < 8; k++) {
      YdNode *f = x->items[k], *comps;
      char    path[64];
      snprintf(path, sizeof path, "boundary.fixed[%zu]", k);
      if (yd_expect(doc, f, YD_MAPPING, path, err, errlen)) return 1;
      if (yd_string(doc, yd_get(f, "group"), path, &s, err, errlen)) return 1;
      snprintf(sc->fixed[k].group, sizeof sc->fixed[k].group, "%s", s);
      if (yd_expect(doc, comps = yd_get(f, "components"), YD_SEQUENCE, path, err, errlen)) return 1;
      for (size_t j = 0; j < comps->n && j < 3; j++) {
        int c = comps->items[j]->kind == YD_SCALAR ? component_of(comps->items[j]->text) : -1;
        if (c < 0 || (sc->kin != KIN_3D && c > 1))
          FAIL("%s:%d: key '%s.components': expected x, y%s", doc->file, comps->items[j]->line, path,
               sc->kin == KIN_3D ? " or z" : " (a 2D mesh; axisymmetric: x = r, y = z)");
        sc->fixed[k].comp[sc->fixed[k].ncomp++] = c;
      }
      if (yd_check_unused(doc, f, path, "group, components", err, errlen)) return 1;
      sc->nfixed++;
    }
  }
  if ((x = yd_get(bc, "pressure"))) {
    if (yd_expect(doc, x, YD_SEQUENCE, "boundary.pressure", err, errlen)) return 1;
    for (size_t k = 0; k < x->n && k < FE_MAX_GROUPS; k++) {
      if (yd_string(doc, x->items[k], "boundary.pressure", &s, err, errlen)) return 1;
      snprintf(sc->pressure_group[sc->npressure++], 64, "%s", s);
    }
  }
  if ((x = yd_get(bc, "traction"))) { /* uniform tractions: loads GROUP.x, GROUP.y (, GROUP.z) */
    if (yd_expect(doc, x, YD_SEQUENCE, "boundary.traction", err, errlen)) return 1;
    int dim = sc->kin == KIN_3D ? 3 : 2;
    for (size_t k = 0; k < x->n; k++) {
      if (yd_string(doc, x->items[k], "boundary.traction", &s, err, errlen)) return 1;
      if (sc->npressure + dim > FE_MAX_GROUPS) FAIL("%s:%d: key 'boundary': too many loaded groups", doc->file, x->line);
      for (int d = 0; d < dim; d++) snprintf(sc->pressure_group[sc->npressure++], 64, "%s.%c", s, 'x' + d);
    }
  }
  if (yd_check_unused(doc, bc, "boundary", "fixed, pressure, traction", err, errlen)) return 1;
  for (int k = 0; k < FE_MAX_GROUPS; k++) sc->pressure0[k] = 0;
  if (initial_pressure) {
    if (yd_expect(doc, initial_pressure, YD_MAPPING, "initial.pressure", err, errlen)) return 1;
    for (size_t k = 0; k < initial_pressure->n; k++) {
      int gi = -1;
      for (int j = 0; j < sc->npressure; j++)
        if (!strcmp(sc->pressure_group[j], initial_pressure->keys[k])) gi = j;
      if (gi < 0) FAIL("%s:%d: key 'initial.pressure.%s': not a group listed in boundary.pressure", doc->file,
                       initial_pressure->key_lines[k], initial_pressure->keys[k]);
      initial_pressure->used[k] = 1;
      if (yd_double(doc, initial_pressure->items[k], "initial.pressure", &sc->pressure0[gi], err, errlen)) return 1;
    }
  }

  YdNode *stages = yd_get(root, "stages");
  if (yd_expect(doc, stages, YD_SEQUENCE, "stages", err, errlen)) return 1;
  if (stages->n == 0 || stages->n > MAXSTAGES) FAIL("%s:%d: key 'stages': expected 1 to %d stages", doc->file, stages->line, MAXSTAGES);
  sc->nstage = (int)stages->n;
  for (int i = 0; i < sc->nstage; i++) {
    YdNode *st = stages->items[i];
    Stage  *g  = &sc->stage[i];
    char    path[64], sub[96];
    snprintf(path, sizeof path, "stages[%d]", i);
    if (yd_expect(doc, st, YD_MAPPING, path, err, errlen)) return 1;
    snprintf(g->name, sizeof g->name, "stage%d", i);
    if ((v = yd_get(st, "name"))) {
      if (yd_string(doc, v, path, &s, err, errlen)) return 1;
      snprintf(g->name, sizeof g->name, "%s", s);
    }
    snprintf(sub, sizeof sub, "%s.duration", path);
    if (yd_double(doc, yd_get(st, "duration"), sub, &g->duration, err, errlen)) return 1;
    if (g->duration < 0) FAIL("%s:%d: key '%s': expected >= 0", doc->file, st->line, sub);
    if ((v = yd_get(st, "load"))) {
      if (yd_string(doc, v, path, &s, err, errlen)) return 1;
      if (strcmp(s, "instant") && strcmp(s, "linear")) FAIL("%s:%d: key '%s.load': expected instant or linear", doc->file, v->line, path);
      g->instant = !strcmp(s, "instant");
    }
    for (int k = 0; k < FE_MAX_GROUPS; k++) g->pressure[k] = NAN;
    if ((v = yd_get(st, "pressure"))) {
      snprintf(sub, sizeof sub, "%s.pressure", path);
      if (yd_expect(doc, v, YD_MAPPING, sub, err, errlen)) return 1;
      for (size_t k = 0; k < v->n; k++) {
        int gi = -1;
        for (int j = 0; j < sc->npressure; j++)
          if (!strcmp(sc->pressure_group[j], v->keys[k])) gi = j;
        if (gi < 0) FAIL("%s:%d: key '%s.%s': not a group listed in boundary.pressure", doc->file, v->key_lines[k], sub, v->keys[k]);
        v->used[k] = 1;
        char sub2[160];
        snprintf(sub2, sizeof sub2, "%s.%s", sub, v->keys[k]);
        if (read_pressure(doc, v->items[k], sub2, g, gi, err, errlen)) return 1;
      }
    }
    if ((v = yd_get(st, "traction"))) {
      snprintf(sub, sizeof sub, "%s.traction", path);
      if (yd_expect(doc, v, YD_MAPPING, sub, err, errlen)) return 1;
      int dim = sc->kin == KIN_3D ? 3 : 2;
      for (size_t k = 0; k < v->n; k++) {
        double t[3];
        char   sub2[200];
        snprintf(sub2, sizeof sub2, "%s.%s", sub, v->keys[k]);
        v->used[k] = 1;
        if (yd_doubles(doc, v->items[k], sub2, t, dim, NULL, err, errlen)) return 1;
        for (int d = 0; d < dim; d++) {
          char name[72];
          int  gi = -1;
          snprintf(name, sizeof name, "%s.%c", v->keys[k], 'x' + d);
          for (int j = 0; j < sc->npressure; j++)
            if (!strcmp(sc->pressure_group[j], name)) gi = j;
          if (gi < 0) FAIL("%s:%d: key '%s': not a group listed in boundary.traction", doc->file, v->key_lines[k], sub2);
          g->pressure[gi] = t[d], g->fn[gi] = FN_RAMP;
        }
      }
    }
    snprintf(sub, sizeof sub, "%s.steps", path);
    if (read_steps(doc, yd_get(st, "steps"), sub, g, err, errlen)) return 1;
    if ((v = yd_get(st, "until"))) {
      if (yd_double(doc, yd_get(v, "evp_rate_below"), "until.evp_rate_below", &g->evp_rate_below, err, errlen)) return 1;
      if (yd_check_unused(doc, v, "until", "evp_rate_below", err, errlen)) return 1;
    }
    if ((v = yd_get(st, "creep")) && yd_bool(doc, v, path, &g->creep, err, errlen)) return 1;
    if (yd_check_unused(doc, st, path, "name, duration, load, pressure, traction, steps, until, creep", err, errlen)) return 1;
  }
  if ((x = yd_get(root, "solver"))) {
    if ((v = yd_get(x, "options"))) {
      if (yd_string(doc, v, "solver.options", &s, err, errlen)) return 1;
      if (s[0] != '-') FAIL("%s:%d: key 'solver.options': expected PETSc options such as '-snes_monitor', got '%s'", doc->file, v->line, s);
      snprintf(sc->solver_options, sizeof sc->solver_options, "%s", s);
    }
    if (yd_check_unused(doc, x, "solver", "options (PETSc options; the command line overrides them)", err, errlen)) return 1;
  }
  sc->axis = sc->kin == KIN_3D ? 2 : 1;   /* the loading axis: x3 in 3D, x2 (= z) in 2D */
  return yd_check_unused(doc, root, "", "scene, name, units, mesh, material, phi, initial, boundary, stages, output, solver",
                         err, errlen);
}

/* Where a run is: what a checkpoint saves (with U and the state of every quadrature point). */
typedef struct {
  int        step, stage, in_stage, pending_instant, total_cutbacks;
  double     t, t_stage, dt, start[FE_MAX_GROUPS], pressure_now[FE_MAX_GROUPS];
  PetscInt   nout;
  PetscReal *out_times;
} Progress;

#define CHECKPOINT_MAGIC 0x43433943 /* "CC9C" */

static void checkpoint_path(const FeScene *sc, int rank, char *path, size_t n) {
  snprintf(path, n, "%s/checkpoint.rank%d.bin", sc->outdir, rank);
}

/* One file per rank, written to a temporary name and renamed, so a crash never leaves half a file. */
static int write_checkpoint(const FeScene *sc, FeProblem *p, Vec U, const Progress *pr, long history_offset,
                            char *err, size_t errlen) {
  PetscMPIInt rank, size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  char path[700], tmp[710];
  checkpoint_path(sc, rank, path, sizeof path);
  snprintf(tmp, sizeof tmp, "%s.tmp", path);
  FILE *fp = fopen(tmp, "wb");
  if (!fp) {
    snprintf(err, errlen, "%s: cannot write the checkpoint: %s", tmp, strerror(errno));
    return 1;
  }
  PetscInt           nloc, npoint = p->npoint, nsv = p->nsv;
  const PetscScalar *u;
  int                magic = CHECKPOINT_MAGIC;
  VecGetLocalSize(U, &nloc);
  VecGetArrayRead(U, &u);
  fwrite(&magic, sizeof magic, 1, fp);
  fwrite(&size, sizeof size, 1, fp);
  fwrite(pr, sizeof *pr, 1, fp);
  fwrite(pr->out_times, sizeof(PetscReal), (size_t)pr->nout, fp);
  fwrite(&history_offset, sizeof history_offset, 1, fp);
  fwrite(&p->umat_calls, sizeof p->umat_calls, 1, fp);
  fwrite(&nloc, sizeof nloc, 1, fp);
  fwrite(u, sizeof(PetscScalar), (size_t)nloc, fp);
  fwrite(&npoint, sizeof npoint, 1, fp);
  fwrite(&nsv, sizeof nsv, 1, fp);
  fwrite(p->state, sizeof(PetscReal), (size_t)(npoint * nsv), fp);
  fwrite(&magic, sizeof magic, 1, fp);
  VecRestoreArrayRead(U, &u);
  if (fclose(fp) || rename(tmp, path)) {
    snprintf(err, errlen, "%s: cannot write the checkpoint: %s", path, strerror(errno));
    return 1;
  }
  return 0;
}

static int read_checkpoint(const FeScene *sc, FeProblem *p, Vec U, Progress *pr, long *history_offset, char *err,
                           size_t errlen) {
  PetscMPIInt rank, size, saved_size;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  char path[700];
  checkpoint_path(sc, rank, path, sizeof path);
  FILE *fp = fopen(path, "rb");
  if (!fp) {
    snprintf(err, errlen, "-restart: %s: cannot open: %s (run with -checkpoint_every N first)", path, strerror(errno));
    return 1;
  }
  int         magic = 0, end = 0, ok = 1;
  PetscInt    nloc, mine, npoint, nsv;
  PetscScalar *u;
  ok &= fread(&magic, sizeof magic, 1, fp) == 1 && magic == CHECKPOINT_MAGIC;
  ok &= fread(&saved_size, sizeof saved_size, 1, fp) == 1;
  if (ok && saved_size != size) {
    fclose(fp);
    snprintf(err, errlen, "-restart: %s was written by %d ranks; restart with mpiexec -n %d", path, saved_size, saved_size);
    return 1;
  }
  ok &= fread(pr, sizeof *pr, 1, fp) == 1;
  if (ok) {
    pr->out_times = malloc(sizeof(PetscReal) * (size_t)(pr->nout > 0 ? pr->nout : 1));
    ok &= fread(pr->out_times, sizeof(PetscReal), (size_t)pr->nout, fp) == (size_t)pr->nout;
  }
  ok &= fread(history_offset, sizeof *history_offset, 1, fp) == 1;
  ok &= fread(&p->umat_calls, sizeof p->umat_calls, 1, fp) == 1;
  ok &= fread(&nloc, sizeof nloc, 1, fp) == 1;
  VecGetLocalSize(U, &mine);
  if (ok && nloc != mine) {
    fclose(fp);
    snprintf(err, errlen, "-restart: %s holds %d unknowns on this rank, the scene gives %d: not the same scene or mesh",
             path, (int)nloc, (int)mine);
    return 1;
  }
  VecGetArray(U, &u);
  ok &= fread(u, sizeof(PetscScalar), (size_t)nloc, fp) == (size_t)nloc;
  VecRestoreArray(U, &u);
  ok &= fread(&npoint, sizeof npoint, 1, fp) == 1 && fread(&nsv, sizeof nsv, 1, fp) == 1;
  ok &= npoint == p->npoint && nsv == p->nsv;
  ok &= ok && fread(p->state, sizeof(PetscReal), (size_t)(npoint * nsv), fp) == (size_t)(npoint * nsv);
  ok &= fread(&end, sizeof end, 1, fp) == 1 && end == CHECKPOINT_MAGIC;
  fclose(fp);
  if (!ok) {
    snprintf(err, errlen, "-restart: %s is not a complete checkpoint of this scene", path);
    return 1;
  }
  memcpy(p->trial, p->state, sizeof(PetscReal) * (size_t)(npoint * nsv));
  return 0;
}

int fe_run(YdDoc *doc, const char *outdir_override, char *err, size_t errlen) {
  FeScene     sc;
  MPI_Comm    comm = PETSC_COMM_WORLD;
  PetscMPIInt rank;
  MPI_Comm_rank(comm, &rank);
  if (fe_scene_read(doc, &sc, err, errlen)) return 2;
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
    if (sc.solver_options[0]) { /* the scene's options, each unless the command line already gives it */
      char  buf[1024], *tok, *save = NULL;
      snprintf(buf, sizeof buf, "%s", sc.solver_options);
      char *keys[64], *vals[64];
      int   n = 0;
      for (tok = strtok_r(buf, " \t", &save); tok && n < 64; tok = strtok_r(NULL, " \t", &save)) {
        if (tok[0] == '-' && !(tok[1] >= '0' && tok[1] <= '9') && tok[1] != '.') keys[n] = tok, vals[n++] = NULL;
        else if (n > 0 && !vals[n - 1]) vals[n - 1] = tok;
      }
      for (int k = 0; k < n; k++) {
        PetscBool set;
        PetscCall(PetscOptionsHasName(NULL, NULL, keys[k], &set));
        if (!set) PetscCall(PetscOptionsSetValue(NULL, keys[k], vals[k]));
      }
    }
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
    double dt_plan = g->adaptive ? g->dt_first : g->ratio == 1 ? g->duration / g->count : g->duration * (g->ratio - 1) / (pow(g->ratio, g->count) - 1);
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
      PetscCall(SNESSolve(snes, NULL, U));
      PetscCall(SNESGetConvergedReason(snes, &reason));
      PetscCall(SNESGetIterationNumber(snes, &its));
      if (reason > 0) PetscCall(fe_residual(snes, U, R, &p)); /* trial state at the solution */
      if (reason <= 0 || p.min_pnewdt < 1) {
        PetscCall(VecCopy(U0, U));
        total_cutbacks++;
        double factor = reason > 0 ? fmax(fmin(p.min_pnewdt, 0.5), 0.1) : 0.25;
        if (h == 0 || ++cut > 30 || (g->adaptive && h * factor < g->dt_min)) {
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
      else if (g->adaptive) dt = fmin(fmax(h * fmin(p.min_pnewdt, g->growth), g->dt_min), g->dt_max);
      else dt *= g->ratio;
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
