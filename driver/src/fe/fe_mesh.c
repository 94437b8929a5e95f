/* Reading a gmsh mesh into a distributed DMPlex (declared in fe_problem.h). The file is checked first
 * (io/gmsh_mesh.h: a gmsh file, complete, of the right dimension), so that a bad mesh is reported by
 * one sentence naming the file rather than by an error deep inside PETSc's reader. */
#include <petscdmplex.h>

#include "../io/gmsh_mesh.h"
#include "fe_natural.h"
#include "fe_problem.h"

PetscErrorCode fe_mesh_create(MPI_Comm comm, const char *msh, PetscInt dim, DM *dm) {
  DM          dist = NULL;
  char        sdim[8], msg[1024] = "";
  int         bad = 0;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) bad = msh_check(msh, (int)dim, 0, msg, sizeof msg);
  PetscCallMPI(MPI_Bcast(&bad, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, comm));
  PetscCheck(!bad, comm, PETSC_ERR_FILE_UNEXPECTED, "%s", msg);
  PetscCall(PetscSNPrintf(sdim, sizeof sdim, "%d", (int)dim)); /* gmsh writes 3 coordinates even in 2D */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_spacedim", sdim));
  /* Physical groups become labels named after them, points included. */
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_use_regions", "true"));
  PetscCall(PetscOptionsSetValue(NULL, "-dm_plex_gmsh_mark_vertices", "true"));
  PetscCall(DMPlexCreateFromFile(comm, msh, "mesh", PETSC_TRUE, dm));
  { /* a deterministic partition by default, so that a restart finds the same cells on each rank
       (graph partitioners may differ from run to run); -petscpartitioner_type chooses another */
    PetscPartitioner part;
    PetscCall(DMPlexGetPartitioner(*dm, &part));
    PetscCall(PetscPartitionerSetType(part, PETSCPARTITIONERSIMPLE));
    PetscCall(PetscPartitionerSetFromOptions(part));
  }
  PetscSF migration = NULL;
  PetscCall(DMPlexDistribute(*dm, 0, &migration, &dist));
  PetscCall(fe_natural_setup(*dm, dist, migration)); /* the serial mesh's numbers, for output and checkpoints */
  PetscCall(PetscSFDestroy(&migration));
  if (dist) {
    PetscCall(DMDestroy(dm));
    *dm = dist;
  }
  PetscFunctionReturn(0);
}
