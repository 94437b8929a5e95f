/* The material-point adapter (material_point.h): the only place that knows which PROPS slot holds phi and the
 * step-control tolerance, and which STATEV slots hold what the driver reads. */
#include "material_point.h"

#include <string.h>

/* Component i of the quantity at STATEV slot s (a UmatStateSlots entry), 0 where the UMAT has no such slot (s < 0, or
 * beyond NSTATV); whether it holds n components from slot s. */
static double statev_at(const UmatMaterial *mat, const double *statev, int s, int i) {
  return s >= 0 && s + i < mat->nstatv ? statev[s + i] : 0.0;
}
static bool has_slots(const UmatMaterial *mat, int s, int n) { return s >= 0 && s + n <= mat->nstatv; }

/* The first STATEV slot of quantity q (UmatStateSlots, filled by material_read), and its components. */
static int quantity_slot(const UmatMaterial *mat, MaterialQuantity q, int *n) {
  const UmatStateSlots *sv = &mat->sv;
  *n                       = q == MATERIAL_PC_HARD || q == MATERIAL_PC_SOFT ? 1 : 6;
  switch (q) {
  case MATERIAL_SIG_HARD: return sv->sig_hard;
  case MATERIAL_SIG_SOFT: return sv->sig_soft;
  case MATERIAL_EVP_HARD: return sv->evp_hard;
  case MATERIAL_EVP_SOFT: return sv->evp_soft;
  case MATERIAL_EVP: return sv->evp;
  case MATERIAL_PC_HARD: return sv->pc_hard;
  case MATERIAL_PC_SOFT: return sv->pc_soft;
  default: return -1;
  }
}

int material_quantity_size(const UmatMaterial *mat, MaterialQuantity q) {
  int n, s = quantity_slot(mat, q, &n);
  return has_slots(mat, s, n) ? n : 0;
}

double material_quantity(const UmatMaterial *mat, const double *statev, MaterialQuantity q, int i) {
  int n, s = quantity_slot(mat, q, &n);
  return i < n ? statev_at(mat, statev, s, i) : 0.0;
}

/* The diagnostic slots (docs/umat.md: STATEV 33 iterations, 34 flags: 1, 2 pc at the floor, 4, 8 tension, 16 the
 * fallback solver, 32, 64 the step outruns the frame's softening). */
static MaterialLocalSolve local_solve(const UmatMaterial *mat, const double *statev) {
  MaterialLocalSolve l;
  l.iterations      = (int)statev_at(mat, statev, mat->sv.iterations, 0);
  l.flags           = (int)statev_at(mat, statev, mat->sv.flags, 0);
  l.pc_floor_hard   = l.flags & 1, l.pc_floor_soft = l.flags & 2;
  l.tension_hard    = l.flags & 4, l.tension_soft = l.flags & 8;
  l.fallback_solver = l.flags & 16;
  return l;
}

void material_point_state(const UmatMaterial *mat, const double *statev, MaterialPointState *s) {
  double *six[5] = {s->sig_hard, s->sig_soft, s->evp_hard, s->evp_soft, s->evp};
  for (int q = MATERIAL_SIG_HARD; q <= MATERIAL_EVP; q++)
    for (int i = 0; i < 6; i++) six[q - MATERIAL_SIG_HARD][i] = material_quantity(mat, statev, (MaterialQuantity)q, i);
  s->pc_hard = material_quantity(mat, statev, MATERIAL_PC_HARD, 0);
  s->pc_soft = material_quantity(mat, statev, MATERIAL_PC_SOFT, 0);
  s->local   = local_solve(mat, statev);
}

bool   material_has_phi(const UmatMaterial *mat) { return mat->pr.phi >= 0; }
double material_phi(const UmatMaterial *mat) { return mat->pr.phi >= 0 ? mat->props[mat->pr.phi] : 0; }

bool material_normal(const UmatMaterial *mat, double b[3]) {
  if (mat->pr.normal < 0 || mat->nprops < mat->pr.normal + 3) return false;
  for (int d = 0; d < 3; d++) b[d] = mat->props[mat->pr.normal + d];
  return true;
}

bool material_is_camclay9(const UmatMaterial *mat) {
  return mat->pr.normal >= 0 && mat->pr.eta_hard >= 0 && mat->pr.eta_soft >= 0 && mat->pr.tol >= 0 &&
         mat->sv.sig_hard >= 0 && mat->sv.sig_soft >= 0 && mat->sv.pc_hard >= 0 && mat->sv.pc_soft >= 0;
}

void material_set_normal(UmatMaterial *mat, const double b[3]) {
  memcpy(&mat->props[mat->pr.normal], b, 3 * sizeof(double));
  mat->nprops = mat->pr.normal + 3;
}

void material_set_phi(UmatMaterial *mat, double phi) { mat->props[mat->pr.phi] = phi; }
void material_set_viscosity(UmatMaterial *mat, double eta) { mat->props[mat->pr.eta_hard] = mat->props[mat->pr.eta_soft] = eta; }
void material_set_tolerance(UmatMaterial *mat, double tol) { mat->props[mat->pr.tol] = tol; }

void material_state_isotropic(const UmatMaterial *mat, double *statev, double s, double pc) {
  for (int i = 0; i < 3; i++) statev[mat->sv.sig_hard + i] = statev[mat->sv.sig_soft + i] = s;
  statev[mat->sv.pc_hard] = statev[mat->sv.pc_soft] = pc;
}

int material_props_with_normal(const UmatMaterial *mat, double props[UMAT_MAX_PROPS], double b[3]) {
  const int n3 = mat->pr.normal, np = n3 >= 0 ? n3 + 3 : mat->nprops;
  memset(props, 0, sizeof(double) * UMAT_MAX_PROPS);
  memcpy(props, mat->props, sizeof(double) * (size_t)(mat->nprops < np ? mat->nprops : np));
  if (n3 >= 0 && mat->nprops < np) props[n3 + 2] = 1;
  b[0] = 0, b[1] = 0, b[2] = 1;
  if (n3 >= 0) memcpy(b, &props[n3], 3 * sizeof(double));
  return np;
}

/* PROPS of one update: the material's, with the step control's tolerance and phi. */
static void effective_props(const UmatMaterial *mat, double phi, UmatControl c, double *props) {
  memcpy(props, mat->props, sizeof(double) * (size_t)mat->nprops);
  if (c.mode != UMAT_CONTROL_AS_GIVEN && mat->pr.tol >= 0 && mat->pr.tol < mat->nprops) props[mat->pr.tol] = umat_control_tol(mat, c);
  if (mat->pr.phi >= 0) props[mat->pr.phi] = phi;
}

void material_effective(const UmatMaterial *mat, double phi, UmatControl c, UmatMaterial *eff) {
  *eff = *mat;
  effective_props(mat, phi, c, eff->props);
}

void material_point_update(const UmatMaterial *mat, double phi, UmatControl c, UmatCall *call, MaterialPointDiag *diag) {
  double props[UMAT_MAX_PROPS];
  effective_props(mat, phi, c, props);
  umat_invoke_props(mat, props, call);
  diag->pnewdt   = call->pnewdt;
  diag->rejected = call->pnewdt < 1;
  diag->local    = local_solve(mat, call->statev);
}

void material_failed_call_keep(MaterialFailedCall *f, const UmatMaterial *mat, double phi, UmatControl c,
                               const double stress0[6], const double *statev0, const UmatCall *out) {
  if (f->have) return;
  f->have = true;
  material_effective(mat, phi, c, &f->mat);
  f->out = *out, f->in = *out;
  memcpy(f->in.stress, stress0, sizeof f->in.stress);
  memcpy(f->in.statev, statev0, sizeof(double) * (size_t)mat->nstatv);
}

int material_failed_call_write(const MaterialFailedCall *f, const char *path, const char *why) {
  return umat_write_replay(path, &f->mat, &f->in, &f->out, why);
}
