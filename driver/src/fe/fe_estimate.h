/* The mesh's error indicator per cell and the size field made from it (docs/adapt.md).
 *
 * Indicator: Zienkiewicz & Zhu's recovery estimate (Int. J. Numer. Meth. Eng. 24, 337-357, 1987) on the
 * stress. Each cell's stress, linear in the cell for P2 (the least-squares plane through its quadrature
 * points, exact for the 3 or 4 points of the P2 rule) and constant for P1, is evaluated at the cell's
 * vertices; the values are averaged over the cells that share a vertex (weights: the cells' volumes), which
 * gives a continuous P1 stress sigma*. The indicator of cell K is
 *     eta_K = ( int_K |sigma* - sigma_h|^2 dV )^(1/2),   |s|^2 = s_11^2 + s_22^2 + s_33^2 + 2 (s_12^2 + s_13^2 + s_23^2),
 * with the scene's volume weight (thickness, 2 pi r). Where the solution is smooth it falls as h^(k + d/2) per
 * cell (k the element order) and its sum of squares as h^k, the energy error's rate.
 * The same recovery on the viscoplastic strain (the material's total, STATEV by name; its engineering shears
 * halved in the norm) gives eta_e,K. The stress's indicator alone sends the cells to the indenter's tip, where
 * the stress is singular, and leaves the edge of the viscoplastic zone coarse, which carries the creep depth
 * (docs/adapt.md, "Which field"). So the indicator is both fields' shares, each relative to its own norm:
 *     eta_K = |eta_s| ( (eta_s,K / |eta_s|)^2 + (eta_e,K / |eta_e|)^2 )^(1/2),   |eta|^2 = sum_K eta_K^2,
 * in the stress indicator's units; with no viscoplastic strain (an elastic run) it is eta_s,K.
 * A boundary term (est.surface: an indentation's contact surface, contact_estimate.h) adds the residual of the
 * traction on the cell's facets there to eta_s,K^2 before the shares are taken: the stress's recovery alone does not
 * see a traction that disagrees with the contact pressure, and the creep and residual depths are carried by the
 * contact surface's resolution (docs/adapt.md, "The contact surface").
 *
 * History: every field output writes the indicator of the committed state; at the times the run reports at (its
 * start, each stage's output times and end) it also keeps the largest value of every cell (eta_max), the quantity
 * the size field equidistributes, since the mesh must serve every time the run reports. Fields written only
 * because output.fields_every asks for them do not enter eta_max: how often a user looks at the fields does not
 * change the adapted meshes. */
#ifndef FE_ESTIMATE_H
#define FE_ESTIMATE_H

#include "fe_problem.h"

/* The indicator of the committed state (per local cell, into p->est.eta) and, at a report time (report), its running
   maximum (eta_max). Collective. */
PetscErrorCode fe_estimate_update(FeProblem *p, PetscBool report);

/* The stress of local plex cell 'cell' at the point x (the cell's own linear fit through its quadrature points, the
   field the recovery compares with), Voigt order 11, 22, 33, 12 (, 13, 23). */
PetscErrorCode fe_estimate_stress_at(FeProblem *p, PetscInt cell, const PetscReal x[], PetscReal s[6]);
/* Add e2 to the boundary share of local plex cell 'cell' at this output: called by est.surface only. */
void fe_estimate_add_surface(FeProblem *p, PetscInt cell, PetscReal e2);

/* The indicator's norm, sqrt(sum over all cells of eta_max^2) (collective), for the summary; 0 before any output. */
PetscErrorCode fe_estimate_norm(FeProblem *p, PetscReal *norm);

/* A size field that equidistributes eta_max over about 'target_cells' cells (Zienkiewicz & Zhu 1987, sec. 5;
 * docs/adapt.md): with eta_K ~ h_K^s, s = order + dim/2, the new size of cell K is
 *     h'_K = h_K (eta_t / eta_K)^(1/s),   eta_t = ( sum_K eta_K^(d/s) / target )^(s/d),
 * so that the predicted number of cells sum_K (h_K / h'_K)^d is the target; the change per cell is kept within
 * [1/4, 2]. Written as a gmsh view (path, a .pos file: one scalar triangle or tetrahedron per cell, the size at
 * each vertex the smallest of its cells'), which a .geo reads as a PostView background field. Collective; rank
 * 0 writes. *predicted: the predicted number of cells. */
PetscErrorCode fe_estimate_write_sizes(FeProblem *p, PetscReal target_cells, const char *path, PetscReal *predicted);

/* Free what fe_estimate_update allocated. */
PetscErrorCode fe_estimate_destroy(FeProblem *p);

#endif
