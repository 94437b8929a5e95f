/* Essential boundary conditions with zero values: fixed displacement components on groups (u_x = 0 ...) and
 * mirror (symmetry) planes of any orientation (u . n = 0 on a group with a given normal n).
 *
 * A node on an inclined plane keeps its unknowns in a nodal frame of its own (as Abaqus' *TRANSFORM): its
 * first k axes span the constraint normals at the node (orthonormalised), and those k components are held at
 * zero as PetscSection constraints, like any fixed component; the remaining axes take the global axes from
 * the last on (z first), so that on a vertical mirror plane the frame's last axis is e_z. Everything else of
 * the driver stays in the global axes: the element loop sees the displacement in global axes (the framed
 * nodes rotated after DMGlobalToLocal) and its forces are rotated back into the frames before
 * DMLocalToGlobal; element matrices are rotated on the framed nodes, T^T K T. This is the pattern of PETSc
 * issue #566 (J. Brown: rotate in place after DMGlobalToLocal, R^T on the local residual, a constrained
 * component for slip); DMPlexCreateBasisRotation is one rotation for the whole mesh, and anchors
 * (DMPlexSetAnchors) tie points to other points, not components of a point to each other.
 * Nodes without a mirror plane keep the global axes, so fixed components alone give the section that
 * DMAddBoundary would give (the groups' closures, the constrained components united). */
#ifndef FE_CONSTRAINT_H
#define FE_CONSTRAINT_H

#include <petscdmplex.h>
#include <petscfe.h>

typedef struct {
  char      group[64];      /* a physical group of the mesh (a DMLabel) */
  PetscInt  ncomp, comp[3]; /* fixed components (x = 0, y = 1, z = 2) */
  PetscBool mirror;         /* or a mirror plane: u . normal = 0 (ncomp = 0) */
  PetscReal normal[3];      /* its unit normal */
  int       index, line;    /* the mirror's entry in boundary.mirror and its line in the scene */
} FeFixed;

typedef struct {
  PetscInt   dim;
  PetscInt   n;          /* local points (owned and ghost) with a constrained component */
  PetscInt  *off, *mask; /* their offsets in the local vector; bit j: component j (in the point's frame) is zero */
  PetscInt  *frame;      /* the frame of each, or -1: the global axes */
  PetscInt   nframe;
  PetscReal *R;          /* dim x dim per frame, R[f dim^2 + i dim + j] = component i of frame axis j:
                            u_global = R u_frame */
  PetscInt   nnode;      /* nodes of the local vector (storage / dim) ... */
  PetscInt  *node_frame; /* ... and the frame of each (by offset / dim), or -1 */
} FeConstraint;

/* The constraints of the fixed and mirror groups: completes their labels (closures), creates the DM's local
 * section with the constrained components (DMPlexCreateSection) and the nodal frames. Collective. */
PetscErrorCode fe_constraint_setup(FeConstraint *con, DM dm, PetscFE fe, const FeFixed *fixed, PetscInt nfixed);
PetscErrorCode fe_constraint_destroy(FeConstraint *con);
/* A local vector's values (u: its array): constrained components set to zero, framed nodes to global axes. */
PetscErrorCode fe_constraint_to_global(const FeConstraint *con, PetscScalar *u);
/* Local forces in global axes (f: its array) into the nodes' frames; reaction (or NULL): adds the force on the
 * constrained components, sum over them of e_j (e_j . f), in global axes. */
PetscErrorCode fe_constraint_to_frame(const FeConstraint *con, PetscScalar *f, PetscReal reaction[3]);
/* An element matrix (nb x nb, row-major; dofs: its local-vector indices) from global axes into the frames of its
 * framed nodes: T^T Ke T. */
PetscErrorCode fe_constraint_rotate_cell(const FeConstraint *con, const PetscInt dofs[], PetscInt nb, PetscScalar *Ke);
/* The frame of the node at local offset off (identity if it has none), dim x dim as in R. */
PetscErrorCode fe_constraint_node_frame(const FeConstraint *con, PetscInt off, PetscReal R[9]);
/* All points of a label, whatever their values (a gmsh physical group may carry several), this rank's. */
PetscErrorCode fe_label_points(DMLabel label, IS *points);

#endif
