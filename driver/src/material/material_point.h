/* The material-point adapter: one update of one material point through the linked UMAT, with the hard-frame
 * fraction phi and the UMAT's step control as arguments, and what it says back under names (docs/umat.md,
 * "PROPS" and "STATEV"). The FE element loop and the point scenes call the UMAT only through it, and read a
 * point's state only through material_point_state/material_quantity, so that no caller indexes a PROPS or STATEV
 * slot of Cam-Clay IX (material_read fills the slots from the model's own tables; any other UMAT has none). */
#ifndef MATERIAL_POINT_H
#define MATERIAL_POINT_H

#include <stdbool.h>

#include "umat_call.h"

/* What the local solve of a call recorded (docs/umat.md, STATEV 33-34; zero and false where the linked UMAT keeps
 * no such slot). */
typedef struct {
  int  iterations;                   /* the local Newton's iterations (the larger of the two frames) */
  int  flags;                        /* the diagnostic bits as stored, decoded below */
  bool pc_floor_hard, pc_floor_soft; /* a frame's pc at its floor (strong dilation) */
  bool tension_hard, tension_soft;   /* a frame in tension (p' < 0) */
  bool fallback_solver;              /* the local solve needed the fallback solver */
} MaterialLocalSolve;

/* What one update says. */
typedef struct {
  double             pnewdt;   /* the UMAT's PNEWDT: < 1 asks for a shorter step */
  bool               rejected; /* pnewdt < 1: the UMAT asks for a shorter step */
  MaterialLocalSolve local;
} MaterialPointDiag;

/* The named quantities of a point's STATEV. */
typedef enum {
  MATERIAL_SIG_HARD, MATERIAL_SIG_SOFT, /* the frames' stresses (6) */
  MATERIAL_EVP_HARD, MATERIAL_EVP_SOFT, /* the frames' viscoplastic strains (6, engineering shear) */
  MATERIAL_EVP,                         /* the total viscoplastic strain (6; eq. 3 of the paper) */
  MATERIAL_PC_HARD, MATERIAL_PC_SOFT,   /* the frames' preconsolidation pressures (1) */
  MATERIAL_NQUANTITY
} MaterialQuantity;

/* The components of quantity q the linked UMAT keeps (6 or 1), 0 if it keeps none. */
int material_quantity_size(const UmatMaterial *mat, MaterialQuantity q);
/* Component i of quantity q in a point's STATEV, 0 where the UMAT keeps none. */
double material_quantity(const UmatMaterial *mat, const double *statev, MaterialQuantity q, int i);

/* A point's state by name, for histories and progress lines (zero where the UMAT keeps no such slot). */
typedef struct {
  double sig_hard[6], sig_soft[6], evp_hard[6], evp_soft[6], evp[6];
  double             pc_hard, pc_soft;
  MaterialLocalSolve local; /* of the call that left this state */
} MaterialPointState;
void material_point_state(const UmatMaterial *mat, const double *statev, MaterialPointState *s);

/* The hard-frame fraction the material gives (PROPS 'phi'), 0 if the UMAT has none; whether it has one. */
double material_phi(const UmatMaterial *mat);
bool   material_has_phi(const UmatMaterial *mat);
/* The bedding normal the material gives in PROPS (n1-n3) into b; false (b untouched) if it gives none. */
bool material_normal(const UmatMaterial *mat, double b[3]);

/* The PROPS through the bedding normal's slots, the normal the UMAT's default e3 where the material gives none
 * (docs/umat.md); returns their number (mat->nprops where the UMAT has no normal slots). b: the normal, e3 if none. */
int material_props_with_normal(const UmatMaterial *mat, double props[UMAT_MAX_PROPS], double b[3]);

/* Whether the linked UMAT keeps Cam-Clay IX's named slots (the frames' viscosities, the normal, the frames' state):
 * what a study that varies them needs (app/sweep.c). */
bool material_is_camclay9(const UmatMaterial *mat);
/* Set, by name, the bedding normal b (unit) as the last three PROPS, the hard-frame fraction, both frames' viscosity
 * eta and the step-control tolerance tol (0: no control). Only for a material with material_is_camclay9. */
void material_set_normal(UmatMaterial *mat, const double b[3]);
void material_set_phi(UmatMaterial *mat, double phi);
void material_set_viscosity(UmatMaterial *mat, double eta);
void material_set_tolerance(UmatMaterial *mat, double tol);
/* A start state in statev: both frames' stresses isotropic at s (their stress sum is the point's) and their pc. */
void material_state_isotropic(const UmatMaterial *mat, double *statev, double s, double pc);

/* The material of one update: mat's PROPS with phi (where the UMAT has the slot) and the step control c. */
void material_effective(const UmatMaterial *mat, double phi, UmatControl c, UmatMaterial *eff);

/* One increment of one point: call holds the increment's start (stress, STATEV, STRAN), DSTRAN, TIME, DTIME and
 * the element/point numbers; it gets the end state, DDSDDE and PNEWDT back; diag says what the UMAT said. */
void material_point_update(const UmatMaterial *mat, double phi, UmatControl c, UmatCall *call, MaterialPointDiag *diag);

/* The first rejected call of an evaluation, kept for a replay scene (umat_write_replay). */
typedef struct {
  bool         have;
  UmatMaterial mat;     /* the effective material (phi and step control in PROPS) */
  UmatCall     in, out; /* the call as it was passed and as it came back */
} MaterialFailedCall;
/* Keep the call 'out' came from unless one is kept already: its input is 'out' with the stress and STATEV it had at
 * the start (stress0, statev0; a rejecting UMAT should return them unchanged, but this holds for any UMAT). */
void material_failed_call_keep(MaterialFailedCall *f, const UmatMaterial *mat, double phi, UmatControl c,
                               const double stress0[6], const double *statev0, const UmatCall *out);
/* Write the kept call's replay scene to path (0: written). */
int material_failed_call_write(const MaterialFailedCall *f, const char *path, const char *why);

#endif
