/* The contact surface's share of the mesh's error indicator (fe_estimate.h; docs/adapt.md, "The contact surface").
 *
 * On each facet F of the potential contact surface, the residual of the traction: the stress of the facet's cell
 * (the linear fit the recovery compares with, fe_estimate_stress_at) against the pressure the multipliers put there,
 *     eta_F^2 = h_F int_F |sigma_h n_F - (lambda n)_h|^2 dA,
 * (lambda n)_h the nodes' lambda_i n_i interpolated linearly over the facet (contact.h's signs: sigma n_F = lambda n
 * at a solution; zero where the surface is free), h_F the facet's size, dA with the scene's weight (thickness,
 * 2 pi r). It is the Neumann and contact term of a residual estimator for contact (B. I. Wohlmuth, "An a posteriori
 * error estimator for two-body contact problems on non-matching meshes", J. Sci. Comput. 33 (2007) 25-45; P. Hild
 * and S. Nicaise, Math. Models Methods Appl. Sci. 17 (2007) 1241-1271), in the units of the stress's recovery
 * indicator (stress^2 x volume), and joins that share of each cell's indicator. The same on P1 (nodal multipliers)
 * and P2 (the mortar's vertex multipliers), 2D and 3D, on any number of ranks. */
#ifndef CONTACT_ESTIMATE_H
#define CONTACT_ESTIMATE_H

#include "contact.h"

/* The facets of the group (label) on this rank, their cells, outward normals and sizes; after the nodes (ct->vtx). */
PetscErrorCode contact_estimate_setup(FeProblem *p, DMLabel label, Contact *ct);
PetscErrorCode contact_estimate_destroy(Contact *ct);
/* Add each facet's eta_F^2 to its cell (fe_estimate_add_surface) for the multipliers lam at the last gaps' normals.
   Collective. */
PetscErrorCode contact_estimate(Contact *ct, Vec lam, FeProblem *p);

#endif
