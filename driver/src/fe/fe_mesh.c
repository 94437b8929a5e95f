/* Reading a gmsh mesh into a distributed DMPlex (declared in fe_problem.h). The file is checked first
 * (io/gmsh_mesh.h: a gmsh file, complete, of the right dimension), so that a bad mesh is reported by
 * one sentence naming the file rather than by an error deep inside PETSc's reader. */
#include <petscdmplex.h>

#include "../io/gmsh_mesh.h"
#include "fe_natural.h"
#include "fe_problem.h"

/* On more than one rank, one line on how the partition cuts the mesh: the vertices, and the copies of them held by a
 * rank that does not own them (the point SF's leaves among the vertices). A graph partitioner keeps the copies to the
 * ranks' interfaces; many more mean ghost data and communication on the order of the whole mesh. */
static PetscErrorCode print_partition(DM dm, PetscPartitioner part) {
  PetscMPIInt          size;
  PetscSF              sf;
  PetscInt             nleaves, vs, ve, n[2] = {0, 0}, all[2];
  const PetscInt      *leaves;
  PetscPartitionerType type;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)dm), &size));
  if (size == 1) PetscFunctionReturn(0);
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vs, &ve));
  for (PetscInt i = 0; i < nleaves; i++) {
    const PetscInt pt = leaves ? leaves[i] : i;
    n[1] += pt >= vs && pt < ve;
  }
  n[0] = ve - vs - n[1];
  PetscCallMPI(MPIU_Allreduce(n, all, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCall(PetscPartitionerGetType(part, &type));
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)dm), "partition: %d ranks (%s), %d vertices, %d copies on ranks that do not own them (%.1f %%)\n",
                        (int)size, type, (int)all[0], (int)all[1], 100.0 * (double)all[1] / (double)all[0]));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_mesh_create(MPI_Comm comm, const char *msh, PetscInt dim, DM *dm) {
  DM          dist = NULL;
  char        sdim[8], msg[1024] = "";
  int         bad = 0, periodic = 0;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) bad = msh_check(msh, (int)dim, 0, &periodic, msg, sizeof msg);
  PetscCallMPI(MPI_Bcast(&bad, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, comm));
  PetscCheck(!bad, comm, PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
  if (periodic)
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "mesh: %s lists periodic copies ($Periodic): read as one mesh joined along them, not as "
                                           "periodic boundary conditions (the driver has none)\n", msh));
  PetscCall(PetscSNPrintf(sdim, sizeof sdim, "%d", (int)dim)); /* gmsh writes 3 coordinates even in 2D */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_spacedim", sdim));
  /* Physical groups become labels named after them, points included. */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_mark_vertices", "true"));
  /* A mesh copied by gmsh through an affine map (a block meshed as two mirror halves: meshes/indent_block2d.geo,
     mirror = 1) lists the copy in its $Periodic section; the two halves are joined, not identified, so the section
     must not make the mesh periodic. */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_periodic", "false"));
  PetscCall(DMPlexCreateFromFile(comm, msh, "mesh", PETSC_TRUE, dm));
  /* A graph partitioner where PETSc has one. The simple partitioner cuts the cells in the file's order, which gmsh
     does not make spatial: on the kerogen sector it left nearly every vertex on both of 2 ranks (docs/parallel.md,
     "The partition"). A restart reads its state by the serial mesh's numbers and needs no particular partition.
     -petscpartitioner_type chooses another. */
  PetscPartitioner part;
  PetscCall(DMPlexGetPartitioner(*dm, &part));
#if defined(PETSC_HAVE_PARMETIS)
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPARMETIS));
#elif defined(PETSC_HAVE_PTSCOTCH)
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERPTSCOTCH));
#else
  PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
#endif
  PetscCall(PetscPartitionerSetFromOptions(part));
  PetscSF migration = NULL;
  PetscCall(DMPlexDistribute(*dm, 0, &migration, &dist));
  PetscCall(fe_natural_setup(*dm, dist, migration)); /* the serial mesh's numbers, for output and checkpoints */
  PetscCall(PetscSFDestroy(&migration));
  PetscCall(print_partition(dist ? dist : *dm, part));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}
