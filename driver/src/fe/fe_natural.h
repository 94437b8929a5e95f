/* The serial mesh's ("natural") order of the points, whatever the partition: every rank numbers its mesh
 * points as DMPlexDistribute left them, but each point keeps the number it has in the mesh as read from the
 * .msh file (the same on 1 or N ranks). Field output and checkpoints are written in this order, so that a
 * file written on N ranks reads the same on M (a restart on another number of ranks) and fields.h5 does not
 * depend on the partition. It is PETSc's natural ordering (DMSetUseNatural, DMPlexGlobalToNatural) taken
 * point by point from the migration SF, for any per-point data (nodes, cells, the contact nodes). */
#ifndef FE_NATURAL_H
#define FE_NATURAL_H

#include <petscdmplex.h>
#include <petscsf.h>

/* After distribution (dist NULL: one rank, nothing moved): each point's place in its depth stratum of the
 * serial mesh, kept on the DM (dist, or serial). Collective. */
PetscErrorCode fe_natural_setup(DM serial, DM dist, PetscSF migration);

/* The points of some depth strata (their natural numbers one after the other in the order given: vertices
 * then edges for P2 nodes) that this rank owns (ghosts: and those it shares, to read values back), and a star
 * forest from them (leaves 0..n-1) to their place in the natural layout (roots, PETSc's even split of N over the
 * ranks). */
typedef struct {
  PetscSF   sf;
  PetscInt  n, *points; /* owned points here, local mesh numbers */
  PetscInt  N, nroot;   /* points in the whole mesh; natural places held here */
  PetscInt  offset[4];  /* natural number of the first point of each depth given */
} FeNatural;
PetscErrorCode fe_natural_create(DM dm, PetscInt ndepth, const PetscInt depths[], PetscBool ghosts, FeNatural *m);
/* The same for some points of one depth (each on one rank: the contact nodes), in the layout of the whole stratum. */
PetscErrorCode fe_natural_create_points(DM dm, PetscInt depth, PetscInt n, const PetscInt points[], FeNatural *m);
PetscErrorCode fe_natural_destroy(FeNatural *m);
/* Every local point's place in its stratum of the serial mesh (ghosts included): the natural number of point p
 * of the k-th depth of m is m->offset[k] + nat[p]. Valid while the DM lives. */
PetscErrorCode fe_natural_indices(DM dm, const PetscInt **nat);

/* A vector in natural order: nroot x bs values here, N x bs in all (written by PETSc's HDF5 viewer as an (N, bs)
 * dataset under its name). */
PetscErrorCode fe_natural_vec(const FeNatural *m, PetscInt bs, const char *name, Vec *nat);
/* bs values per owned point (leaf order) into a new vector in natural order (nroot x bs here), and back. */
PetscErrorCode fe_natural_gather(const FeNatural *m, PetscInt bs, const PetscScalar leaf[], const char *name, Vec *nat);
PetscErrorCode fe_natural_scatter(const FeNatural *m, PetscInt bs, Vec nat, PetscScalar leaf[]);
/* The same for integers (nroot x bs of them here). */
PetscErrorCode fe_natural_gather_int(const FeNatural *m, PetscInt bs, const PetscInt leaf[], PetscInt root[]);

#endif
