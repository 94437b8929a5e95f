/* Contact on quadratic (P2) elements: a mortar-type weak form of the contact constraints (docs/contact.md,
 * "Quadratic elements"). Nodal quadrature cannot serve P2 faces (a P2 triangle's corners get no weight), so:
 * one multiplier per vertex of the potential contact surface with a piecewise-linear basis psi_j on it
 * (Wohlmuth 2000, 2011; the linear multipliers for quadratic displacements of Popp, Wohlmuth, Gee & Wall
 * 2012), the weighted gap gt_j = int psi_j g(u_h) dA (Hueber & Wohlmuth 2005; Popp, Gee & Wall 2009) and the
 * contact work int lambda_h n . du_h dA, both integrated at Gauss points of the contact facets (edges with the
 * thickness or 2 pi r, triangles in 3D). The Contact's per-multiplier arrays keep their meaning:
 *   w_j = int psi_j dA,   g_j = gt_j / w_j (a mean gap),   n_j = int psi_j n dA / w_j,
 * so that w_j g_j is the weighted gap, w_j (n_j . d) = int psi_j (n . d) dA is the multiplier's share of the
 * indenter force (eq. 19), and the active set, the indenter row and the multiplier rows are those of P1. Only
 * R_u and the coupling block Bt (and B, its transpose on the active rows) are integrals over the facets.
 * A facet node on an inclined mirror plane (fe_constraint.h) has its unknowns in a frame of its own: its
 * displacement is R u_rows in the gaps, its rows of R_u, Bt and B the global ones times R^T. */
#ifndef CONTACT_MORTAR_H
#define CONTACT_MORTAR_H

#include "contact.h"

/* Starts ct->mortar; mark (over the chart): 1 at the vertices of the group's boundary facets, on their owners too
   (the multiplier nodes are the marked owned vertices with a free axial component: contact.c's contact_nodes). */
PetscErrorCode contact_mortar_mark(FeProblem *p, DMLabel label, Contact *ct, PetscInt **mark);
/* The group's boundary facets on this rank (a boundary facet has one cell, so it lives on one rank only). */
PetscErrorCode contact_facets(DM dm, DMLabel label, PetscInt *nf, PetscInt **list);
/* A Gauss rule of the given degree on a facet (dimension dim - 1): the barycentric coordinates of its nq points
   (L: nq x dim) and their weights (w: nq; the reference facet has measure 2); free with PetscFree2(*L, *w). */
PetscErrorCode contact_facet_rule(PetscInt dim, PetscInt degree, PetscInt *nq, PetscReal **L, PetscReal **w);
/* After the multipliers are numbered (ct->N, ct->rstart): the facets here, their quadrature, the weights
   w_j (wsum: their sum here) and the coupling blocks Bt and B with their fixed nonzero pattern. */
PetscErrorCode contact_mortar_setup(FeProblem *p, DMLabel label, Contact *ct, PetscReal *wsum);
PetscErrorCode contact_mortar_destroy(Contact *ct);
/* Weighted gaps and mean normals of the multipliers (g_j, n_j) and the normal at every Gauss point. */
PetscErrorCode contact_mortar_gaps(Contact *ct, Vec U, PetscReal ur);
/* R_u -= int lambda_h N_k n dA (the contact work, at the last gaps' normals). */
PetscErrorCode contact_mortar_forces(Contact *ct, Vec lam, Vec Ru);
/* Bt = dR_u/dlambda = -int psi_j N_k n dA, all multipliers; B = c times its transpose on the active rows (the
   multiplier rows in force units, contact.h). */
PetscErrorCode contact_mortar_coupling(Contact *ct);
/* The indenter's travel to its first touch of the surface at the last gaps, pointwise: the smallest
   g / (n . d) over the Gauss points and the P2 nodes of the facets (this rank). */
PetscErrorCode contact_mortar_first_touch(Contact *ct, PetscReal *dmin);

#endif
