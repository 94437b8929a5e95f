/* The material as the driver sees it: any Abaqus UMAT, called through the standard argument list.
 * Nothing here knows which UMAT is linked (Cam-Clay IX by default; tests link a linear-elastic one). */
#ifndef UMAT_CALL_H
#define UMAT_CALL_H

#include <stdio.h>

#define UMAT_MAX_PROPS 64
#define UMAT_MAX_STATEV 256

/* The STATEV slots the driver reads (0-based; the first of six Voigt components for tensors), -1 where the linked
 * UMAT has none. material_read fills them from the UMAT's own header (Cam-Clay IX: camclay9.h, docs/umat.md
 * "STATEV"); only material/ reads them (material_point.h reads a state by name), so that nothing outside material/
 * knows a UMAT's layout. */
typedef struct {
  int sig_hard, evp_hard, pc_hard;  /* the hard frame's stress, viscoplastic strain, preconsolidation pressure */
  int sig_soft, evp_soft, pc_soft;  /* the soft frame's */
  int evp;                          /* the total viscoplastic strain */
  int iterations, flags;            /* the local Newton's iterations, the diagnostic flag bits */
} UmatStateSlots;

/* The PROPS slots the driver sets (0-based), -1 where the linked UMAT has none; filled by material_read (Cam-Clay IX:
 * docs/umat.md "PROPS"), read by material/ (material_point.h sets phi and the step control per update). */
typedef struct {
  int phi;                /* the hard frame's volume fraction */
  int eta_hard, eta_soft; /* the frames' viscosities */
  int tol;                /* the step-control tolerance (PNEWDT) */
  int normal;             /* the first of the bedding normal's three components */
} UmatPropSlots;

typedef struct {
  int    ntens;                  /* 6 (3D) or 4 (plane strain, axisymmetric) */
  int    nstatv;
  int    nprops;
  double props[UMAT_MAX_PROPS];
  char   cmname[80];             /* blank padded, as Fortran passes it */
  UmatPropSlots  pr;             /* the PROPS slots the driver sets */
  UmatStateSlots sv;             /* the STATEV slots the driver reads */
} UmatMaterial;


/* What the host passes in and gets back for one integration point and one increment. */
typedef struct {
  double stress[6];              /* in: start of increment; out: end */
  double statev[UMAT_MAX_STATEV];
  double ddsdde[36];             /* column-major, ntens x ntens: ddsdde[i + ntens*j] = dsigma_i/deps_j */
  double stran[6], dstran[6];
  double time[2];                /* step time, total time at the start of the increment */
  double dtime;
  double pnewdt;                 /* out: < 1 asks for a smaller increment */
  double sse, spd, scd;
  int    noel, npt, kstep, kinc;
} UmatCall;

/* How an evaluation sets the UMAT's own step control (its PROPS tol, hence PNEWDT): off (tol 0), as the material
 * gives it, or at a given tolerance (the worst_point error measure). While Newton iterates it is off: a point whose
 * step the UMAT would reject keeps its old stress with a new tangent, which no iteration can converge; the stepper
 * judges the converged state. OFF is 0, so a zeroed struct is off. */
typedef enum { UMAT_CONTROL_OFF = 0, UMAT_CONTROL_AS_GIVEN, UMAT_CONTROL_AT } UmatControlMode;
typedef struct {
  UmatControlMode mode;
  double          tol; /* UMAT_CONTROL_AT */
} UmatControl;

static inline UmatControl umat_control(UmatControlMode mode, double tol) {
  UmatControl c = {mode, mode == UMAT_CONTROL_AT ? tol : 0};
  return c;
}
/* The tolerance an evaluation under c uses (0: no control). */
static inline double umat_control_tol(const UmatMaterial *mat, UmatControl c) {
  if (c.mode == UMAT_CONTROL_AT) return c.tol;
  if (c.mode == UMAT_CONTROL_OFF) return 0;
  return mat->pr.tol >= 0 && mat->pr.tol < mat->nprops ? mat->props[mat->pr.tol] : 0;
}

void umat_material_set_name(UmatMaterial *mat, const char *name);
/* Call the linked UMAT. call->pnewdt is set large before the call, as Abaqus does. */
void umat_invoke(const UmatMaterial *mat, UmatCall *call);
/* The same with these PROPS in place of mat->props (nprops of them): material_point_update's. */
void umat_invoke_props(const UmatMaterial *mat, const double *props, UmatCall *call);

/* Write a scene that replays this exact call (scene: replay), with the results the call gave, so the
 * replay can check itself bit for bit. in = the call as it was passed, out = as it came back. */
int umat_write_replay(const char *path, const UmatMaterial *mat, const UmatCall *in, const UmatCall *out,
                      const char *why);

#endif
