#include "material_input.h"

#include <math.h>
#include <petscsys.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camclay9.h"
#include "../io/keydecl.h"
#include "../io/options.h"
#include "../io/text.h"

/* Cam-Clay IX PROPS slot names, from the model's own table (ccix_props, camclay9_prop_name). */
enum { NSLOTS = CAMCLAY9_NPROPS_WITH_NORMAL };
static const char *slot_name(int k) {
  static char name[NSLOTS][16]; /* filled on first use (the driver reads its input on one thread) */
  if (k < 0 || k >= NSLOTS) return "?";
  if (!name[k][0]) camclay9_prop_name(k, name[k], sizeof name[k]);
  return name[k];
}

const char *material_slot_list(char *buf, size_t n) {
  size_t len = 0;
  buf[0]     = '\0';
  for (int k = 0; k < NSLOTS && len < n; k++) len += (size_t)snprintf(buf + len, n - len, "%s%s", k ? ", " : "", slot_name(k));
  return buf;
}

/* Yin, Liu & Borja (2021), Tables 1-2 (docs/umat.md). */
static const double woodford[19] = {0.5,  2900, 18000, 13000, 4100, 6900, 1.46,   0.00013, 0.73,  -0.20,
                                    0.40, 2.0,  1.3e13, 4600, 3100, 1.46, 0.0026, 35.0,    1.3e10};

int material_slot(const char *name) {
  for (int i = 0; i < NSLOTS; i++)
    if (!strcmp(slot_name(i), name)) return i;
  return -1;
}

/* Set a named slot, growing nprops as 'set' does; *normal set when it is one of n1..n3. */
static void set_slot(UmatMaterial *mat, int slot, double v, int *normal) {
  const int n1 = mat->pr.normal >= 0 ? mat->pr.normal : UMAT_MAX_PROPS; /* the normal's first slot */
  mat->props[slot] = v;
  if (slot >= n1) *normal = 1;
  if (slot + 1 > mat->nprops) mat->nprops = slot < n1 ? slot + 1 : n1 + 3; /* one component: the whole normal */
}

PetscErrorCode material_options(char *set, size_t n, PetscBool *given) {
  PetscFunctionBeginUser;
  set[0] = '\0';
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Material", NULL);
  PetscCall(options_string(PetscOptionsObject, "-material_set",
                           "PROPS overrides NAME=VALUE[,NAME=VALUE...] (names as in material.set), applied after the scene's material.set",
                           set, set, n, given));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* Where each PROPS slot's value came from, for the message of a value the UMAT refuses. */
typedef struct {
  int  line[UMAT_MAX_PROPS]; /* the scene line of material.set.NAME or material.props[k] (0: the preset) */
  char set[UMAT_MAX_PROPS];  /* given by material.set (else by material.props) */
  char option[UMAT_MAX_PROPS]; /* overridden by -material_set */
} SlotSources;

/* -material_set NAME=VALUE[,NAME=VALUE...]: PROPS overrides from the command line, applied after the
 * scene's material.set with the same names and checks (the calibrate scene's forward runs use it). */
static int apply_option_set(UmatMaterial *mat, int *normal, SlotSources *src, char *err, size_t errlen) {
  char      buf[2048] = "", *tok, *save = NULL;
  PetscBool given     = PETSC_FALSE;
  if (material_options(buf, sizeof buf, &given)) {
    snprintf(err, errlen, "option -material_set: could not be read");
    return 1;
  }
  if (!given) return 0;
  for (tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
    char *eq = strchr(tok, '=');
    if (!eq) {
      snprintf(err, errlen, "option -material_set: '%s': expected NAME=VALUE", tok);
      return 1;
    }
    *eq      = '\0';
    int slot = material_slot(tok);
    if (slot < 0) {
      char list[400];
      snprintf(err, errlen, "option -material_set: unknown PROPS name '%s': the names are %s", tok, material_slot_list(list, sizeof list));
      return 1;
    }
    double v;
    if (text_real(eq + 1, &v)) {
      snprintf(err, errlen, "option -material_set: '%s=%s': expected a finite number", tok, eq + 1);
      return 1;
    }
    set_slot(mat, slot, v, normal);
    src->option[slot] = 1;
  }
  return 0;
}

/* The UMAT's message on a refused slot (1-based), with where its value came from. */
static void refused_slot(const YdDoc *doc, const YdNode *node, const SlotSources *src, const UmatMaterial *mat, int code,
                         const char *msg, char *err, size_t errlen) {
  int k = code - 1;
  if (code < 1 || code > UMAT_MAX_PROPS) snprintf(err, errlen, "%s:%d: material: %s", doc->file, node->line, msg);
  else if (src->option[k])
    snprintf(err, errlen, "option -material_set: %s=%.17g (scene %s): %s", slot_name(k), mat->props[k], doc->file,
             msg);
  else if (src->set[k]) snprintf(err, errlen, "%s:%d: key 'material.set.%s': %s", doc->file, src->line[k], slot_name(k), msg);
  else if (src->line[k]) snprintf(err, errlen, "%s:%d: key 'material.props[%d]': %s", doc->file, src->line[k], k, msg);
  else snprintf(err, errlen, "%s:%d: material: %s", doc->file, node->line, msg);
}

/* material.props (woodford or a list of numbers) and material.set (named slots); *props_out: the props node;
 * *normal_in_props set when set names n1..n3. */
static int read_props_set(const YdDoc *doc, YdNode *node, UmatMaterial *mat, YdNode **props_out, int *normal_in_props,
                          SlotSources *src, char *err, size_t errlen) {
  YdNode *nd, *props = yd_get(node, "props");
  *props_out = props;
  if (!props) {
    snprintf(err, errlen, "%s:%d: key 'material.props' is missing: expected 'woodford' or a list of numbers",
             doc->file, node->line);
    return 1;
  }
  if (props->kind == YD_SCALAR && !strcmp(props->text, "woodford")) {
    memcpy(mat->props, woodford, sizeof woodford);
    mat->nprops = (int)(sizeof woodford / sizeof woodford[0]); /* no normal: the UMAT's material 3-axis, unless given below */
  } else if (props->kind == YD_SCALAR) {
    snprintf(err, errlen, "%s:%d: key 'material.props': unknown preset '%s': expected woodford or a list of numbers",
             doc->file, props->line, props->text);
    return 1;
  } else if (yd_doubles(doc, props, "material.props", mat->props, -UMAT_MAX_PROPS, &mat->nprops, err, errlen)) {
    return 1;
  } else {
    for (int k = 0; k < mat->nprops; k++) src->line[k] = props->items[k]->line;
  }
  if ((nd = yd_get(node, "set"))) {
    if (yd_expect(doc, nd, YD_MAPPING, "material.set", err, errlen)) return 1;
    for (size_t i = 0; i < nd->n; i++) {
      int  slot = material_slot(nd->keys[i]);
      char path[128];
      snprintf(path, sizeof path, "material.set.%s", nd->keys[i]);
      if (slot < 0) {
        char list[400];
        snprintf(err, errlen, "%s:%d: unknown key '%s': the PROPS slot names are %s", doc->file, nd->key_lines[i], path,
                 material_slot_list(list, sizeof list));
        return 1;
      }
      nd->used[i] = 1;
      double v;
      if (yd_double(doc, nd->items[i], path, &v, err, errlen)) return 1;
      set_slot(mat, slot, v, normal_in_props);
      src->line[slot] = nd->key_lines[i], src->set[slot] = 1;
    }
  }
  return 0;
}

/* Bedding: an angle theta to the loading axis (theory.md §4.1), or the normal itself (PROPS(21-23)); 2D
 * camclay9 without one: n = e2. *nprops_given: nprops before a normal from bedding_angle fills PROPS(21-23). */
static int read_bedding(const YdDoc *doc, YdNode *node, int ntens, int camclay, int normal_in_props, UmatMaterial *mat,
                        int *nprops_given, char *err, size_t errlen) {
  YdNode *bed = yd_get(node, "bedding_angle"), *normal = yd_get(node, "normal");
  if (bed && normal) {
    snprintf(err, errlen, "%s:%d: give either 'material.bedding_angle' or 'material.normal', not both", doc->file,
             yd_key_line(node, "normal"));
    return 1;
  }
  if (mat->pr.normal >= 0 && mat->nprops > mat->pr.normal) normal_in_props = 1;
  *nprops_given = mat->nprops; /* before a normal from bedding_angle fills PROPS(21-23) */
  if (bed && normal_in_props) {
    snprintf(err, errlen, "%s:%d: key 'material.bedding_angle': the normal (n1, n2, n3: PROPS(21-23)) is already given "
             "in material.props or material.set: give one of them", doc->file, yd_key_line(node, "bedding_angle"));
    return 1;
  }
  if (normal && normal_in_props) {
    snprintf(err, errlen, "%s:%d: key 'material.normal': the normal (n1, n2, n3: PROPS(21-23)) is already given in "
             "material.props or material.set: give one of them", doc->file, yd_key_line(node, "normal"));
    return 1;
  }
  if (bed) {
    double theta;
    if (yd_double(doc, bed, "material.bedding_angle", &theta, err, errlen)) return 1;
    theta *= M_PI / 180;
    /* 3D: load along x3, n = (sin, 0, cos); plane strain / axisymmetric: load along x2, n = (sin, cos, 0). */
    double n[3] = {sin(theta), ntens == 6 ? 0.0 : cos(theta), ntens == 6 ? cos(theta) : 0.0};
    memcpy(&mat->props[mat->pr.normal], n, sizeof n);
    mat->nprops = mat->pr.normal + 3;
  } else if (normal) {
    if (yd_doubles(doc, normal, "material.normal", &mat->props[mat->pr.normal], 3, NULL, err, errlen)) return 1;
    mat->nprops = mat->pr.normal + 3;
  } else if (camclay && ntens == 4 && mat->nprops < mat->pr.normal + 3) {
    /* 2D without a normal: theta = 0 with the load along x2, n = e2 (the UMAT needs it in-plane) */
    mat->props[mat->pr.normal] = 0, mat->props[mat->pr.normal + 1] = 1, mat->props[mat->pr.normal + 2] = 0;
    mat->nprops    = mat->pr.normal + 3;
  }
  return 0;
}

/* The STATEV slot of the model's block 'name' (camclay9_statev_block), -1 if it has none. */
static int statev_block(const char *name) {
  char block[16];
  int  first, size;
  for (int k = 0; camclay9_statev_block(k, block, sizeof block, &first, &size); k++)
    if (!strcmp(block, name)) return first;
  return -1;
}

void material_slots(int camclay, UmatPropSlots *pr, UmatStateSlots *sv) {
  const UmatPropSlots  pnone = {-1, -1, -1, -1, -1};
  const UmatStateSlots none  = {-1, -1, -1, -1, -1, -1, -1, -1, -1};
  *pr = pnone, *sv = none;
  if (!camclay) return;
  pr->phi = material_slot("phi"), pr->eta_hard = material_slot("eta_hard"), pr->eta_soft = material_slot("eta_soft");
  pr->tol = material_slot("tol"), pr->normal = material_slot("n1");
  sv->sig_hard = statev_block("sig_hard"), sv->evp_hard = statev_block("evp_hard"), sv->pc_hard = statev_block("pc_hard");
  sv->sig_soft = statev_block("sig_soft"), sv->evp_soft = statev_block("evp_soft"), sv->pc_soft = statev_block("pc_soft");
  sv->evp = statev_block("evp"), sv->iterations = statev_block("iterations"), sv->flags = statev_block("flags");
}

int material_read(const YdDoc *doc, YdNode *node, int ntens, UmatMaterial *mat, char *err, size_t errlen) {
  if (yd_expect(doc, node, YD_MAPPING, "material", err, errlen)) return 1;
  const char *umat_name = "camclay9", *name = "CAMCLAY9";
  YdNode     *nd, *props;
  if ((nd = yd_get(node, "umat")) && yd_string(doc, nd, "material.umat", &umat_name, err, errlen)) return 1;
  if ((nd = yd_get(node, "name")) && yd_string(doc, nd, "material.name", &name, err, errlen)) return 1;
  int camclay = !strcmp(umat_name, "camclay9");
  memset(mat, 0, sizeof *mat);
  mat->ntens  = ntens;
  mat->nstatv = camclay ? CAMCLAY9_NSTATV_DIAGNOSTICS : 0;
  material_slots(camclay, &mat->pr, &mat->sv);
  umat_material_set_name(mat, name);

  int         normal_in_props = 0; /* n1..n3 given in props or set: bedding_angle would override them */
  int         nprops_given;
  SlotSources src;
  memset(&src, 0, sizeof src);
  if (read_props_set(doc, node, mat, &props, &normal_in_props, &src, err, errlen)) return 1;
  if (camclay && apply_option_set(mat, &normal_in_props, &src, err, errlen)) return 1;
  if (read_bedding(doc, node, ntens, camclay, normal_in_props, mat, &nprops_given, err, errlen)) return 1;
  if (keys_integer(doc, node, "nstatv", &mat->nstatv, NULL, err, errlen) || keys_check_unused(doc, node, NULL, err, errlen)) return 1;
  if (camclay && nprops_given < mat->pr.tol) { /* the slots before tol are the material's */
    snprintf(err, errlen, "%s:%d: key 'material.props': %d PROPS given, at least %d needed by camclay9 (%d: with tol; "
             "%d: with the normal n1, n2, n3)", doc->file, props->line, nprops_given, mat->pr.tol, mat->pr.tol + 1,
             mat->pr.normal + 3);
    return 1;
  }
  if (camclay) {
    char msg[256];
    int  code;
    camclay9_check_props(mat->props, mat->nprops, mat->nstatv, ntens, 3, &code, msg, sizeof msg);
    if (code) {
      refused_slot(doc, node, &src, mat, code, msg, err, errlen);
      return 1;
    }
  }
  return 0;
}
