#include "fe_scene.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../io/csv_table.h"
#include "../io/gmsh_mesh.h"
#include "../io/keydecl.h"
#include "../io/paths.h"
#include "../material/material_input.h"
#include "../scene/scene_keys.h"

#define FAIL(...)                       \
  do {                                  \
    snprintf(err, errlen, __VA_ARGS__); \
    return 1;                           \
  } while (0)

/* A pressure of a stage (scene/time_function.h): a number (reached at the stage's end), {exp: {P0, k}} (P0 exp(k t)
 * in the stage time t), or {table: {file, time, value, time_factor, factor}} (linear interpolation). */
static int read_pressure(YdDoc *doc, YdNode *nd, const char *path, StageLoads *g, int gi, char *err, size_t errlen) {
  if (time_fn_read(doc, nd, path, TF_ALLOW_NUMBER | TF_ALLOW_EXP | TF_ALLOW_TABLE, "a number, {exp: {P0, k}} or {table: {...}}",
                   &g->fn[gi], err, errlen))
    return 1;
  if (g->fn[gi].kind == TF_RAMP) g->pressure[gi] = g->fn[gi].target;
  return 0;
}

double stage_pressure(const StageLoads *g, int k, double start, double target, double lambda, double ts) {
  TimeFn f = g->fn[k];
  if (f.kind == TF_RAMP) f.target = target; /* the caller's: a group the stage does not name keeps its value */
  return time_fn_value(&f, start, lambda, ts);
}


/* mesh.parameters: each a parameter the .geo defines (it tests Exists(NAME) or DefineConstant[NAME]). */
static int read_gmsh_parameters(YdDoc *doc, YdNode *v, FeScene *sc, char *err, size_t errlen) {
  char known[GMSH_MAX_PARAMS][64], list[GMSH_MAX_PARAMS * 66] = "";
  int  nknown;
  if (yd_expect(doc, v, YD_MAPPING, "mesh.parameters", err, errlen)) return 1;
  if (v->n > GMSH_MAX_PARAMS) FAIL("%s:%d: key 'mesh.parameters': at most %d, got %zu", doc->file, v->line, GMSH_MAX_PARAMS, v->n);
  if (gmsh_geo_parameters(sc->geometry, known, GMSH_MAX_PARAMS, &nknown, err, errlen)) return 1;
  for (int k = 0; k < nknown; k++) {
    size_t len = strlen(list);
    snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", known[k]);
  }
  for (size_t i = 0; i < v->n; i++) {
    char path[128];
    int  found = 0;
    snprintf(path, sizeof path, "mesh.parameters.%s", v->keys[i]);
    if (!gmsh_valid_name(v->keys[i]))
      FAIL("%s:%d: key '%s': not a gmsh parameter name (expected letters, digits and _, not starting with a digit)",
           doc->file, v->key_lines[i], path);
    for (int k = 0; k < nknown; k++) found |= !strcmp(known[k], v->keys[i]);
    if (!found)
      FAIL("%s:%d: unknown key '%s': %s defines no parameter '%s' (its parameters: %s)", doc->file, v->key_lines[i], path,
           sc->geometry, v->keys[i], nknown ? list : "none");
    v->used[i] = 1;
    if (yd_double(doc, v->items[i], path, &sc->gmsh_value[sc->ngmsh], err, errlen)) return 1;
    snprintf(sc->gmsh_name[sc->ngmsh++], 64, "%s", v->keys[i]);
  }
  return 0;
}

/* mesh.geometry (a .geo, meshed at run time) or mesh.file (a .msh, checked now), relative to the scene. */
static int read_mesh_source(YdDoc *doc, YdNode *mesh, YdNode *geo, YdNode *file, FeScene *sc, char *err, size_t errlen) {
  const char *key = geo ? "mesh.geometry" : "mesh.file", *path;
  char        where[1200];
  YdNode     *v;
  if (yd_string(doc, geo ? geo : file, key, &path, err, errlen)) return 1;
  snprintf(where, sizeof where, "%s:%d: key '%s'", doc->file, (geo ? geo : file)->line, key);
  if (path_input(doc->file, where, path, file ? sc->msh : sc->geometry, sizeof sc->msh, err, errlen)) return 1;
  if ((v = yd_get(mesh, "parameters"))) {
    if (file) FAIL("%s:%d: key 'mesh.parameters': only with mesh.geometry (a .msh is already meshed)", doc->file, v->line);
    if (read_gmsh_parameters(doc, v, sc, err, errlen)) return 1;
  }
  if (file) {
    char msg[1024];
    if (msh_check(sc->msh, sc->kin == KIN_3D ? 3 : 2, sc->kin == KIN_AXISYMMETRIC, NULL, msg, sizeof msg))
      FAIL("%s: %s", where, msg);
  }
  return 0;
}

static int component_of(const char *s) {
  return !strcmp(s, "x") || !strcmp(s, "0") ? 0 : !strcmp(s, "y") || !strcmp(s, "1") ? 1 : !strcmp(s, "z") || !strcmp(s, "2") ? 2 : -1;
}

/* name, units and output (directory, fields_every) of the scene. */
static int read_output(YdDoc *doc, YdNode *root, FeScene *sc, char *err, size_t errlen) {
  YdNode     *x, *v;
  const char *s;
  if ((x = yd_get(root, "name"))) {
    if (yd_string(doc, x, "name", &s, err, errlen)) return 1;
    snprintf(sc->name, sizeof sc->name, "%s", s);
  }
  if ((x = yd_get(root, "units")))
    for (size_t i = 0; i < x->n; i++) x->used[i] = 1;
  snprintf(sc->outdir, sizeof sc->outdir, "out/%s", sc->name);
  if ((x = yd_get(root, "output"))) {
    if (yd_expect(doc, x, YD_MAPPING, "output", err, errlen)) return 1;
    if ((v = yd_get(x, "directory"))) {
      if (yd_string(doc, v, "output.directory", &s, err, errlen)) return 1;
      snprintf(sc->outdir, sizeof sc->outdir, "%s", s);
    }
    if (keys_integer(doc, x, "fields_every", &sc->fields_every, NULL, err, errlen) || keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  }
  return 0;
}

/* mesh.adapt: {levels, growth, tol} (fe_scene.h); only with mesh.geometry, which adaptation meshes again. */
static int read_adapt(YdDoc *doc, YdNode *mesh, FeScene *sc, char *err, size_t errlen) {
  YdNode *x = yd_get(mesh, "adapt");
  sc->adapt = (MeshAdapt){.levels = 0, .growth = 2, .tol = 0, .line = 0};
  if (!x) return 0;
  if (yd_expect(doc, x, YD_MAPPING, "mesh.adapt", err, errlen)) return 1;
  sc->adapt.line = x->line, sc->adapt.levels = 2;
  if (!yd_get(mesh, "geometry"))
    FAIL("%s:%d: key 'mesh.adapt': adaptation meshes the geometry again: give mesh.geometry (a gmsh .geo), not mesh.file (a .msh "
         "without its geometry)", doc->file, x->line);
  if (keys_integer(doc, x, "levels", &sc->adapt.levels, NULL, err, errlen) || keys_number(doc, x, "growth", &sc->adapt.growth, NULL, err, errlen) ||
      keys_number(doc, x, "tol", &sc->adapt.tol, NULL, err, errlen))
    return 1;
  return keys_check_unused(doc, x, NULL, err, errlen);
}

/* mesh: a gmsh geometry (meshed now, with parameters), a .msh file; its order, kinematics and thickness. */
static int read_mesh(YdDoc *doc, YdNode *root, FeScene *sc, char *err, size_t errlen) {
  YdNode     *v;
  YdNode     *mesh = yd_require(doc, root, "mesh", YD_MAPPING, "mesh", err, errlen);
  if (!mesh) return 1;
  int     kin = 0; /* the choices 3d, plane_strain, axisymmetric */
  sc->order = 1;
  if (keys_integer(doc, mesh, "order", &sc->order, NULL, err, errlen)) return 1;
  YdNode *geo = yd_get(mesh, "geometry"), *file = yd_get(mesh, "file");
  if (!!geo + !!file != 1)
    FAIL("%s:%d: key 'mesh': give exactly one of geometry (a gmsh .geo, meshed now) or file (a .msh)", doc->file, mesh->line);
  sc->kin       = KIN_3D;
  sc->thickness = 1;
  if (keys_word(doc, mesh, "kinematics", NULL, &kin, NULL, err, errlen)) return 1;
  sc->kin = kin == 0 ? KIN_3D : kin == 1 ? KIN_PLANE_STRAIN : KIN_AXISYMMETRIC;
  if (keys_number(doc, mesh, "thickness", &sc->thickness, &v, err, errlen)) return 1;
  if (v && sc->kin != KIN_PLANE_STRAIN)
    FAIL("%s:%d: key 'mesh.thickness': %g, and kinematics: %s: only a plane-strain mesh has a thickness", doc->file, v->line, sc->thickness,
         kin == 0 ? "3d" : "axisymmetric");
  if (read_mesh_source(doc, mesh, geo, file, sc, err, errlen) || read_adapt(doc, mesh, sc, err, errlen)) return 1;
  return keys_check_unused(doc, mesh, NULL, err, errlen);
}

/* material (the UMAT's properties) and phi (the hard-frame fraction's field). */
static int read_material_phi(YdDoc *doc, YdNode *root, FeScene *sc, char *err, size_t errlen) {
  YdNode *x;
  if (!(x = yd_require(doc, root, "material", YD_MAPPING, "material", err, errlen)) ||
      material_read(doc, x, sc->kin == KIN_3D ? 6 : 4, &sc->mat, err, errlen))
    return 1;
  sc->phi_mean = material_phi(&sc->mat);
  sc->phi_lo = 0, sc->phi_hi = 1, sc->phi_seed = 1;
  if ((x = yd_get(root, "phi"))) {
    if (!material_has_phi(&sc->mat)) FAIL("%s:%d: key 'phi': this UMAT has no hard-frame fraction", doc->file, x->line);
    if (yd_expect(doc, x, YD_MAPPING, "phi", err, errlen) || keys_number(doc, x, "mean", &sc->phi_mean, NULL, err, errlen) ||
        keys_number(doc, x, "std", &sc->phi_std, NULL, err, errlen) || keys_number(doc, x, "min", &sc->phi_lo, NULL, err, errlen) ||
        keys_number(doc, x, "max", &sc->phi_hi, NULL, err, errlen) || keys_integer(doc, x, "seed", &sc->phi_seed, NULL, err, errlen) ||
        keys_number(doc, x, "correlation_length", &sc->phi_corr, NULL, err, errlen))
      return 1;
    if (!(0 <= sc->phi_lo && sc->phi_lo <= sc->phi_mean && sc->phi_mean <= sc->phi_hi && sc->phi_hi <= 1))
      FAIL("%s:%d: key 'phi': expected 0 <= min <= mean <= max <= 1, got min %g, mean %g, max %g", doc->file, x->line, sc->phi_lo, sc->phi_mean,
           sc->phi_hi);
    if (keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  }
  return 0;
}

/* initial.stress now; initial.pressure is handed back (read once the loaded groups are known). */
static int read_initial(YdDoc *doc, YdNode *root, FeScene *sc, YdNode **initial_pressure, char *err, size_t errlen) {
  YdNode *x, *v;
  *initial_pressure = NULL;
  if ((x = yd_get(root, "initial"))) {
    if ((v = yd_get(x, "stress")) && yd_doubles(doc, v, "initial.stress", sc->stress0, 6, NULL, err, errlen)) return 1;
    *initial_pressure = yd_get(x, "pressure");
    if (keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  }
  return 0;
}

/* boundary.fixed: groups with fixed displacement components. */
static int read_fixed(YdDoc *doc, YdNode *x, FeScene *sc, char *err, size_t errlen) {
  const char *s;
  if (yd_expect(doc, x, YD_SEQUENCE, "boundary.fixed", err, errlen)) return 1;
  if (x->n > FE_MAX_FIXED) FAIL("%s:%d: key 'boundary.fixed': at most %d entries, got %zu", doc->file, x->line, FE_MAX_FIXED, x->n);
  for (size_t k = 0; k < x->n; k++) {
    YdNode *f = x->items[k], *comps;
    char    path[64], sub[96];
    snprintf(path, sizeof path, "boundary.fixed[%zu]", k);
    if (yd_expect(doc, f, YD_MAPPING, path, err, errlen)) return 1;
    snprintf(sub, sizeof sub, "%s.group", path);
    if (yd_string(doc, yd_get(f, "group"), sub, &s, err, errlen)) return 1;
    snprintf(sc->fixed[k].group, sizeof sc->fixed[k].group, "%s", s);
    snprintf(sub, sizeof sub, "%s.components", path);
    if (yd_expect(doc, comps = yd_get(f, "components"), YD_SEQUENCE, sub, err, errlen)) return 1;
    if (comps->n < 1 || comps->n > 3) FAIL("%s:%d: key '%s': expected 1 to 3 components, got %zu", doc->file, comps->line, sub, comps->n);
    for (size_t j = 0; j < comps->n; j++) {
      int c = comps->items[j]->kind == YD_SCALAR ? component_of(comps->items[j]->text) : -1;
      if (c < 0 || (sc->kin != KIN_3D && c > 1))
        FAIL("%s:%d: key '%s[%zu]': expected x, y%s, got '%s'", doc->file, comps->items[j]->line, sub, j,
             sc->kin == KIN_3D ? " or z" : " (a 2D mesh; axisymmetric: x = r, y = z)",
             comps->items[j]->kind == YD_SCALAR ? comps->items[j]->text : "a list or mapping");
      sc->fixed[k].comp[sc->fixed[k].ncomp++] = c;
    }
    if (keys_check_unused(doc, f, NULL, err, errlen)) return 1;
    sc->nfixed++;
  }
  return 0;
}

/* boundary.mirror: mirror (symmetry) planes, u . n = 0 on a group, {group, normal}; the normal is normalised. */
static int read_mirror(YdDoc *doc, YdNode *x, FeScene *sc, char *err, size_t errlen) {
  const char *s;
  const int   dim = sc->kin == KIN_3D ? 3 : 2;
  if (yd_expect(doc, x, YD_SEQUENCE, "boundary.mirror", err, errlen)) return 1;
  if (sc->nfixed + (int)x->n > FE_MAX_FIXED)
    FAIL("%s:%d: key 'boundary.mirror': at most %d fixed and mirror entries together, got %d", doc->file, x->line, FE_MAX_FIXED,
         sc->nfixed + (int)x->n);
  for (size_t k = 0; k < x->n; k++) {
    YdNode  *f = x->items[k];
    FeFixed *m = &sc->fixed[sc->nfixed];
    char     path[64], sub[96];
    double   n[3] = {0, 0, 0}, norm = 0;
    snprintf(path, sizeof path, "boundary.mirror[%zu]", k);
    if (yd_expect(doc, f, YD_MAPPING, path, err, errlen)) return 1;
    snprintf(sub, sizeof sub, "%s.group", path);
    if (yd_string(doc, yd_get(f, "group"), sub, &s, err, errlen)) return 1;
    memset(m, 0, sizeof *m);
    snprintf(m->group, sizeof m->group, "%s", s);
    snprintf(sub, sizeof sub, "%s.normal", path);
    if (yd_doubles(doc, yd_get(f, "normal"), sub, n, dim, NULL, err, errlen)) return 1;
    for (int d = 0; d < dim; d++) norm += n[d] * n[d];
    if (!(norm > 0) || !isfinite(norm))
      FAIL("%s:%d: key '%s': expected the plane's normal, %d finite numbers not all zero, got [%g, %g, %g]", doc->file,
           yd_key_line(f, "normal"), sub, dim, n[0], n[1], n[2]);
    for (int d = 0; d < dim; d++) m->normal[d] = n[d] / sqrt(norm);
    m->mirror = PETSC_TRUE, m->index = (int)k, m->line = yd_key_line(f, "normal");
    if (keys_check_unused(doc, f, NULL, err, errlen)) return 1;
    sc->nfixed++;
  }
  return 0;
}

/* A mirror plane of the model must be one of the material: Cam-Clay IX's hard frame (phi > 0) is transversely
   isotropic about the bedding normal b (docs/umat.md), and the reflection x -> x - 2 (x . m) m maps b to itself
   or to -b (the same b b) only if b lies in the plane (b . m = 0) or is normal to it (|b . m| = 1). The soft
   frame is isotropic. Other UMATs are not checked. */
static int check_mirror_symmetry(YdDoc *doc, const FeScene *sc, char *err, size_t errlen) {
  const UmatMaterial *mat = &sc->mat;
  if (!material_has_phi(mat) || !(sc->phi_mean > 0 || (sc->phi_std > 0 && sc->phi_hi > 0))) return 0;
  double b[3] = {0, 0, 1}, nb = 0;
  material_normal(mat, b);
  for (int d = 0; d < 3; d++) nb += b[d] * b[d];
  for (int d = 0; d < 3; d++) b[d] /= sqrt(nb);
  for (int k = 0; k < sc->nfixed; k++) {
    const FeFixed *m = &sc->fixed[k];
    double         c = 0;
    if (!m->mirror) continue;
    for (int d = 0; d < 3; d++) c += b[d] * m->normal[d];
    if (fabs(c) > 1e-9 && fabs(fabs(c) - 1) > 1e-9)
      FAIL("%s:%d: key 'boundary.mirror[%d].normal': [%.6g, %.6g, %.6g] is not a mirror plane of the material: its bedding "
           "normal [%.6g, %.6g, %.6g] is neither in the plane nor normal to it (their dot product is %.6g), so the hard frame "
           "(phi > 0, transversely isotropic) is not symmetric about it. A 60-degree sector needs the load along the bedding "
           "normal (BN) or phi = 0; model a BP indentation on the half model (input/microindent_BP.yaml)",
           doc->file, m->line, m->index, m->normal[0], m->normal[1], m->normal[2], b[0], b[1], b[2], c);
  }
  return 0;
}

/* An axisymmetric body of Cam-Clay IX with a hard frame (phi > 0, transversely isotropic about its bedding normal b) is
   axisymmetric only when b lies along the axis (y): a normal with a radial part (bedding_angle 30, or 90) differs from
   one azimuth to the next, which the model cannot represent. Other UMATs and phi = 0 (an isotropic soft frame) pass. */
static int check_axisymmetric_material(YdDoc *doc, YdNode *root, const FeScene *sc, char *err, size_t errlen) {
  const UmatMaterial *mat = &sc->mat;
  double              b[3] = {0, 1, 0}, nb;
  char                where[400];
  if (sc->kin != KIN_AXISYMMETRIC || !material_has_phi(mat) || !(sc->phi_mean > 0 || (sc->phi_std > 0 && sc->phi_hi > 0))) return 0;
  material_normal(mat, b);
  nb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
  if (fabs(fabs(b[1]) - nb) <= 1e-9 * nb) return 0;
  YdNode *m = yd_get(root, "material"), *set = yd_get(m, "set"), *v = NULL;
  const char *names[] = {"n1", "n2", "n3"}, *named = NULL;
  for (int k = 0; k < 3 && set && !v; k++)
    if ((v = yd_get(set, names[k]))) named = names[k];
  if ((v = yd_get(m, "bedding_angle")))
    snprintf(where, sizeof where, "%s:%d: key 'material.bedding_angle': %s", doc->file, v->line, v->text ? v->text : "");
  else if ((v = yd_get(m, "normal"))) snprintf(where, sizeof where, "%s:%d: key 'material.normal': [%g, %g, %g]", doc->file, v->line, b[0], b[1], b[2]);
  else if (named && (v = yd_get(set, named)))
    snprintf(where, sizeof where, "%s:%d: key 'material.set.%s': %s", doc->file, yd_key_line(set, named), named, v->text ? v->text : "");
  else if ((v = yd_get(m, "props")) && v->kind == YD_SEQUENCE)
    snprintf(where, sizeof where, "%s:%d: key 'material.props': the normal n1, n2, n3 = %g, %g, %g", doc->file, v->line, b[0], b[1], b[2]);
  else snprintf(where, sizeof where, "option -material_set (scene %s): the normal n1, n2, n3 = %g, %g, %g", doc->file, b[0], b[1], b[2]);
  FAIL("%s in an axisymmetric scene (mesh.kinematics: axisymmetric, line %d): the bedding normal [%.6g, %.6g, %.6g] does not lie "
       "along the axis (y), so the hard frame (phi > 0, transversely isotropic about it) is not axisymmetric: the model would "
       "not be the problem stated. Give bedding_angle 0 (the load along the bedding normal), phi = 0, or a 3D model (a load "
       "parallel to the bedding: input/microindent_BP.yaml)", where, yd_key_line(yd_get(root, "mesh"), "kinematics"), b[0] / nb,
       b[1] / nb, b[2] / nb);
}

/* boundary: fixed groups, pressure groups and traction groups (loads GROUP.x, GROUP.y (, GROUP.z)). */
static int read_boundary(YdDoc *doc, YdNode *root, FeScene *sc, char *err, size_t errlen) {
  YdNode     *x;
  const char *s;
  YdNode     *bc = yd_require(doc, root, "boundary", YD_MAPPING, "boundary", err, errlen);
  if (!bc) return 1;
  if ((x = yd_get(bc, "fixed")) && read_fixed(doc, x, sc, err, errlen)) return 1;
  if ((x = yd_get(bc, "mirror")) && read_mirror(doc, x, sc, err, errlen)) return 1;
  if ((x = yd_get(bc, "pressure"))) {
    if (yd_expect(doc, x, YD_SEQUENCE, "boundary.pressure", err, errlen)) return 1;
    if (x->n > FE_MAX_GROUPS) FAIL("%s:%d: key 'boundary.pressure': at most %d groups, got %zu", doc->file, x->line, FE_MAX_GROUPS, x->n);
    for (size_t k = 0; k < x->n; k++) {
      char item[64];
      snprintf(item, sizeof item, "boundary.pressure[%zu]", k);
      if (yd_string(doc, x->items[k], item, &s, err, errlen)) return 1;
      snprintf(sc->pressure_group[sc->npressure++], 64, "%s", s);
    }
  }
  if ((x = yd_get(bc, "traction"))) { /* uniform tractions: loads GROUP.x, GROUP.y (, GROUP.z) */
    if (yd_expect(doc, x, YD_SEQUENCE, "boundary.traction", err, errlen)) return 1;
    int dim = sc->kin == KIN_3D ? 3 : 2;
    for (size_t k = 0; k < x->n; k++) {
      char item[64];
      snprintf(item, sizeof item, "boundary.traction[%zu]", k);
      if (yd_string(doc, x->items[k], item, &s, err, errlen)) return 1;
      if (sc->npressure + dim > FE_MAX_GROUPS) FAIL("%s:%d: key 'boundary': too many loaded groups", doc->file, x->line);
      for (int d = 0; d < dim; d++) snprintf(sc->pressure_group[sc->npressure++], 64, "%s.%c", s, 'x' + d);
    }
  }
  return keys_check_unused(doc, bc, NULL, err, errlen);
}

/* initial.pressure: the starting pressure of each loaded group named in it (0 otherwise). */
static int read_initial_pressure(YdDoc *doc, YdNode *initial_pressure, FeScene *sc, char *err, size_t errlen) {
  for (int k = 0; k < FE_MAX_GROUPS; k++) sc->pressure0[k] = 0;
  if (!initial_pressure) return 0;
  if (yd_expect(doc, initial_pressure, YD_MAPPING, "initial.pressure", err, errlen)) return 1;
  for (size_t k = 0; k < initial_pressure->n; k++) {
    int gi = -1;
    for (int j = 0; j < sc->npressure; j++)
      if (!strcmp(sc->pressure_group[j], initial_pressure->keys[k])) gi = j;
    if (gi < 0) FAIL("%s:%d: key 'initial.pressure.%s': not a group listed in boundary.pressure", doc->file,
                     initial_pressure->key_lines[k], initial_pressure->keys[k]);
    initial_pressure->used[k] = 1;
    char item[128];
    snprintf(item, sizeof item, "initial.pressure.%s", initial_pressure->keys[k]);
    if (yd_double(doc, initial_pressure->items[k], item, &sc->pressure0[gi], err, errlen)) return 1;
  }
  return 0;
}

/* A stage's pressure (a mapping group -> pressure) and traction (group -> vector) blocks. */
static int read_stage_loads(YdDoc *doc, YdNode *st, const char *path, const FeScene *sc, StageLoads *g, char *err, size_t errlen) {
  YdNode *v;
  char    sub[96];
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
        g->pressure[gi] = t[d], g->fn[gi] = (TimeFn){.kind = TF_RAMP, .target = t[d]};
      }
    }
  }
  return 0;
}

/* stages[i]: name, duration, load, pressure, traction, steps, until, creep, output (indenter: the contact module's). */
/* Stage i: what every scene kind's stage has (scene/stage.h), then its loads and indenter settings. */
static int read_stage(YdDoc *doc, YdNode *st, int i, FeScene *sc, char *err, size_t errlen) {
  char path[64];
  snprintf(path, sizeof path, "stages[%d]", i);
  if (stage_read(doc, st, path, i, "stage", "evp_rate_below, q_above, q_below, p_above", &sc->stage[i], err, errlen)) return 1;
  if (read_stage_loads(doc, st, path, sc, &sc->loads[i], err, errlen)) return 1;
  sc->loads[i].indenter = yd_get(st, "indenter"); /* read by the contact module */
  return keys_check_unused(doc, st, NULL, err, errlen);
}

/* solver.options: PETSc options (the command line overrides them). */
static int read_solver(YdDoc *doc, YdNode *root, FeScene *sc, char *err, size_t errlen) {
  YdNode     *x, *v;
  const char *s;
  if ((x = yd_get(root, "solver"))) {
    if ((v = yd_get(x, "options"))) {
      if (yd_string(doc, v, "solver.options", &s, err, errlen)) return 1;
      if (s[0] != '-') FAIL("%s:%d: key 'solver.options': expected PETSc options such as '-snes_monitor', got '%s'", doc->file, v->line, s);
      snprintf(sc->solver_options, sizeof sc->solver_options, "%s", s);
    }
    if (keys_check_unused(doc, x, NULL, err, errlen)) return 1;
  }
  return 0;
}

int fe_scene_read(YdDoc *doc, FeScene *sc, char *err, size_t errlen) {
  YdNode *root = doc->root, *initial_pressure;
  memset(sc, 0, sizeof *sc);
  snprintf(sc->name, sizeof sc->name, "fe");
  scene_keys_attach(doc, SCENE_FE);
  yd_get(root, "scene");
  if (read_output(doc, root, sc, err, errlen) || read_mesh(doc, root, sc, err, errlen) || read_material_phi(doc, root, sc, err, errlen) ||
      check_axisymmetric_material(doc, root, sc, err, errlen) || read_initial(doc, root, sc, &initial_pressure, err, errlen) ||
      read_boundary(doc, root, sc, err, errlen) || read_initial_pressure(doc, initial_pressure, sc, err, errlen) ||
      check_mirror_symmetry(doc, sc, err, errlen))
    return 1;
  YdNode *stages = yd_require(doc, root, "stages", YD_SEQUENCE, "stages", err, errlen);
  if (!stages) return 1;
  if (stages->n == 0 || stages->n > MAXSTAGES) FAIL("%s:%d: key 'stages': expected 1 to %d stages", doc->file, stages->line, MAXSTAGES);
  sc->nstage = (int)stages->n;
  for (int i = 0; i < sc->nstage; i++)
    if (read_stage(doc, stages->items[i], i, sc, err, errlen)) return 1;
  if (read_solver(doc, root, sc, err, errlen)) return 1;
  sc->axis = sc->kin == KIN_3D ? 2 : 1;   /* the loading axis: x3 in 3D, x2 (= z) in 2D */
  sc->indenter = yd_get(root, "indenter");
  for (int i = 0; i < sc->nstage; i++)
    if (sc->loads[i].indenter && !sc->indenter)
      FAIL("%s:%d: key 'stages[%d].indenter': the scene has no top-level 'indenter' block", doc->file, sc->loads[i].indenter->line, i);
  return keys_check_unused(doc, root, NULL, err, errlen);
}
