/* Frictionless node-to-rigid-surface contact with one rigid indenter (Yin, Liu & Borja 2021, §2.2–2.3):
 * a Lagrange multiplier per potential contact node (the normal pressure there), diagonal
 * multiplier-displacement coupling from nodal quadrature (eq. 18), one indenter unknown u_r whose row
 * sums the contact forces (eq. 19), the active set from the complementarity function of eqs. 13–14,
 * and the blocks of the linearised system of eq. 15 for a MatNest over (u, u_r, lambda).
 *
 * Sign conventions: g >= 0 is the gap (eq. 5 with the opposite sign: positive when open), lambda >= 0
 * the contact pressure; the contact force on node i is lambda_i w_i n_i (n: dg/dx, away from the
 * indenter), and on the indenter -sum lambda_i w_i n_i, balanced along the indentation direction d by
 * the applied load P. Eqs. 13-14 read with this g: C(lambda, g) = lambda - max(0, lambda - c g), active where
 * lambda - c g > 0. Residuals (zero at a solution):
 *   R_u      = f_int - f_ext - sum_i lambda_i w_i n_i
 *   R_r      = sum_i lambda_i w_i (n_i . d) - P           (force control; k_n (u_r - h(t)) under depth control)
 *   R_lam,i  = -c w_i g_i on the active set,  w_i lambda_i elsewhere.
 * Every row is a force: the multiplier rows are eq. 12 and eq. 15's identity rows scaled by c w_i and w_i (the
 * complementarity function of eq. 13 times w_i, whose norm the Newton loop measures), the depth row by k_n, a
 * contact node's stiffness; so a Krylov solver's residual norm weighs all rows alike (the solution is unchanged). */
#ifndef CONTACT_H
#define CONTACT_H

#include <petscdmplex.h>
#include <petscmat.h>

#include "../fe/fe_problem.h"
#include "indenter_shape.h"

typedef struct {
  IndenterShape shape;
  PetscInt      dim, n, N, rstart; /* nodes here, on all ranks, first global multiplier index here */
  PetscReal    *X, *w;             /* reference coordinates (dim per node), weights int N_i dGamma (eq. 18) */
  PetscInt     *vtx;               /* the plex vertex of each node */
  PetscInt     *row;               /* dim per node: global displacement row of each component, < 0 if fixed */
  PetscReal    *R;                 /* dim x dim per node: its nodal frame (fe_constraint.h), u = R u_rows */
  PetscReal    *g, *nrm;           /* gap and normal (dim) of each node at the last evaluation */
  PetscBool    *active;
  PetscBool    *rim;               /* on the edge of the potential contact surface (not on a mirror plane) */
  PetscReal     c;                 /* complementarity constant of eq. 13 (stress per length) */
  PetscReal     kn;                /* a contact node's stiffness (force per length): the depth row's scale, and the
                                      indenter row's diagonal under force control with nothing in contact */
  PetscReal     weight_sum;        /* all ranks: area (3D), area per thickness x thickness, 2 pi r area */
  /* blocks of eq. 15, fixed nonzero pattern */
  Mat           Kr, Bt, Ct, B, C, D; /* (u_r,u_r), (u,lam), (u_r,lam), (lam,u), (lam,u_r), (lam,lam) */
  PetscReal     kr;                /* the value in Kr */
  PetscBool     depth_control;     /* of the last contact_jacobian */
  struct ContactMortar *mortar;    /* P2: the facet integrals of contact_mortar.c; NULL: P1, nodal quadrature */
  struct ContactEstimate *est;     /* the facets of the error indicator's contact term (contact_estimate.h) */
} Contact;

/* n_i . d of node i at the last gaps (d = -e_z in 3D, -e_y in 2D): the part of its pressure that bears
 * on the indenter's axis (eq. 19). */
static inline PetscReal contact_ndotd(const Contact *ct, PetscInt i) { return -ct->nrm[i * ct->dim + ct->dim - 1]; }
/* Node i's normal in its rows' frame, R^T n (nodes on an inclined mirror plane have a nodal frame). */
void contact_frame_normal(const Contact *ct, PetscInt i, PetscReal nf[]);

/* The potential contact nodes: the vertices of the faces (3D) or edges (2D) of the group, owned by this
 * rank, with their weights int N_i dGamma (eq. 18; plane strain: times the thickness; axisymmetric: with
 * 2 pi r), taken from fe_problem_unit_load, the integral the FE loads use. P2 (mesh.order 2): the same
 * vertices carry the multipliers of the mortar form of contact_mortar.h. */
PetscErrorCode contact_create(FeProblem *p, const char *group, const IndenterShape *shape, Contact *ct);
PetscErrorCode contact_destroy(Contact *ct);
/* Gaps and normals at displacement U (global vector of the problem's DM) and indenter position ur. */
PetscErrorCode contact_update_gaps(Contact *ct, Vec U, PetscReal ur);
/* Active set of eq. 14 from lambda and the gaps (lambda_ref: a pressure scale; a node whose lambda - c g
 * is below 1e-12 of it is inactive); returns the number of changes and the active count (all ranks). */
PetscErrorCode contact_update_active(Contact *ct, Vec lam, PetscReal lambda_ref, PetscInt *changes, PetscInt *nactive);
/* Add the contact forces to R_u (at the last gaps' normals), and write R_r (force control: target is the
 * load P; depth control: the depth; a force either way), and the 2-norm of w_i (lambda_i - max(0, lambda_i - c g_i)), the
 * complementarity residual of eq. 13 in force units (all ranks). */
PetscErrorCode contact_residual(Contact *ct, Vec lam, PetscReal ur, PetscBool depth_control, PetscReal target,
                                Vec Ru, PetscReal *Rr, PetscReal *ncp_norm);
/* R_lam for the current active set: -c w_i g_i on it (eq. 12), w_i lambda_i off it (force units). */
PetscErrorCode contact_constraint_residual(Contact *ct, Vec lam, Vec Rlam);
/* The contact blocks for the current active set and normals. shift: under force control, k_n on the indenter
 * row's diagonal (its row is empty while nothing is in contact). */
PetscErrorCode contact_jacobian(Contact *ct, PetscBool depth_control, PetscBool shift);
/* sum lambda_i w_i (n_i . d) over all ranks (the contact force on the indenter along d), the largest
 * penetration (-min g), and the smallest multiplier on the active set. */
PetscErrorCode contact_summary(Contact *ct, Vec lam, PetscReal *force, PetscReal *penetration, PetscReal *min_lambda);
/* Active nodes on the rim of the potential contact surface (all ranks): the contact has outgrown it. */
PetscErrorCode contact_on_rim(Contact *ct, PetscInt *count);
/* The indenter's travel along d to its first touch at the last gaps, over all ranks (PETSC_MAX_REAL if no point
 * faces it): the smallest g_i / (n_i . d) over the multipliers (P1: the nodes; P2: their mean gaps, where the
 * active set turns on), or with pointwise on P2 over the Gauss points and nodes of the contact facets (where the
 * surface itself touches: the mean gaps would set the tip into the surface by part of an element). */
PetscErrorCode contact_first_touch(Contact *ct, PetscBool pointwise, PetscReal *dmin);
/* The angle about the indenter's axis (through tip) that the potential contact surface spans [deg]; 2D: 0 or 180. */
PetscErrorCode contact_azimuth_span(Contact *ct, const double tip[], PetscReal *span);
/* k_n: the largest diagonal entry of the stiffness K on the contact nodes (a one-node stiffness). */
PetscErrorCode contact_node_stiffness(Contact *ct, Mat K);

#endif
