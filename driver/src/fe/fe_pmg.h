/* The P1 space of a P2 problem's own mesh as the coarse level of a two-level p-multigrid (docs/contact.md, "The field
 * split"). Its unknowns are the P2 space's vertex unknowns (the same components, constraints and nodal frames), so the
 * prolongation P1 -> P2 is the identity on the vertices and, on an edge's midpoint, the mean of its two vertices'
 * values, rotated from their frames into the midpoint's (u_frame = R^T u_global, fe_constraint.h). The coarse matrix
 * is then the Galerkin product P^T K P, the P1 stiffness of the same mesh. */
#ifndef FE_PMG_H
#define FE_PMG_H

#include "fe_problem.h"

/* P (rows: the P2 space's global unknowns; columns: the coarse P1 unknowns) and the coarse space's rigid-body modes
 * (3D: 6, plane strain: 3; axisymmetric: the two translations, the radial one not a rigid mode but GAMG's coarse space
 * must carry every component; orthonormal, in the nodes' frames), for GAMG on the coarse level. P2 on simplices only (unknowns on vertices and edges). Collective. */
PetscErrorCode fe_p1_prolongation(const FeSpace *sp, Mat *P, MatNullSpace *rbm);

#endif
