/* The material as the driver sees it: any Abaqus UMAT, called through the standard argument list.
 * Nothing here knows which UMAT is linked (Cam-Clay IX by default; tests link a linear-elastic one). */
#ifndef UMAT_CALL_H
#define UMAT_CALL_H

#include <stdio.h>

#define UMAT_MAX_PROPS 64
#define UMAT_MAX_STATEV 256

typedef struct {
  int    ntens;                  /* 6 (3D) or 4 (plane strain, axisymmetric) */
  int    nstatv;
  int    nprops;
  double props[UMAT_MAX_PROPS];
  char   cmname[80];             /* blank padded, as Fortran passes it */
  int    phi_slot;               /* PROPS index of the hard-frame fraction (Cam-Clay IX: 0), -1 if none */
  int    tol_slot;               /* PROPS index of the step-control tolerance (Cam-Clay IX: 19), -1 if none */
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

void umat_material_set_name(UmatMaterial *mat, const char *name);
/* Call the linked UMAT. call->pnewdt is set large before the call, as Abaqus does. */
void umat_invoke(const UmatMaterial *mat, UmatCall *call);

/* Write a scene that replays this exact call (scene: replay), with the results the call gave, so the
 * replay can check itself bit for bit. in = the call as it was passed, out = as it came back. */
int umat_write_replay(const char *path, const UmatMaterial *mat, const UmatCall *in, const UmatCall *out,
                      const char *why);

#endif
