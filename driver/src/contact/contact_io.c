#include "contact_io.h"

#include <petscviewerhdf5.h>
#include <stdlib.h>

#include "../fe/fe_natural.h"

enum { NODE_VALUES = 4 }; /* lambda, its last increment, active, 1 (the entry is a contact node's) */

typedef struct {
  PetscReal x[3];
  PetscInt  v;
} Located;

static int by_coordinates(const void *a, const void *b) {
  const PetscReal *x = ((const Located *)a)->x, *y = ((const Located *)b)->x;
  for (int d = 0; d < 3; d++)
    if (x[d] != y[d]) return x[d] < y[d] ? -1 : 1;
  return 0;
}

/* Each contact node's vertex: the local vertex at its reference coordinates (contact.c copies them exactly). */
static PetscErrorCode node_vertices(const Contact *ct, DM dm, PetscInt *vert) {
  PetscInt           vStart, vEnd;
  PetscSection       cs;
  Vec                X;
  const PetscScalar *x;
  Located           *all;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscCalloc1(vEnd - vStart + 1, &all));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < ct->dim; d++) all[v - vStart].x[d] = PetscRealPart(x[off + d]);
    all[v - vStart].v = v;
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  qsort(all, (size_t)(vEnd - vStart), sizeof *all, by_coordinates);
  for (PetscInt i = 0; i < ct->n; i++) {
    Located key = {{0, 0, 0}, -1}, *hit;
    for (PetscInt d = 0; d < ct->dim; d++) key.x[d] = ct->X[i * ct->dim + d];
    hit = bsearch(&key, all, (size_t)(vEnd - vStart), sizeof *all, by_coordinates);
    PetscCheck(hit, PETSC_COMM_SELF, PETSC_ERR_PLIB, "contact_io: contact node %d is at no vertex of the mesh", (int)i);
    vert[i] = hit->v;
  }
  PetscCall(PetscFree(all));
  PetscFunctionReturn(0);
}

static PetscErrorCode contact_natural(const Contact *ct, DM dm, FeNatural *m) {
  PetscInt *vert;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(ct->n + 1, &vert));
  PetscCall(node_vertices(ct, dm, vert));
  PetscCall(fe_natural_create_points(dm, 0, ct->n, vert, m));
  PetscCall(PetscFree(vert));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_io_view(const Contact *ct, DM dm, PetscViewer v, Vec lam0, Vec ratelam) {
  FeNatural          m;
  PetscScalar       *leaf;
  const PetscScalar *l, *r;
  Vec                x;
  PetscFunctionBeginUser;
  PetscCall(contact_natural(ct, dm, &m));
  PetscCall(PetscMalloc1(NODE_VALUES * ct->n + 1, &leaf));
  PetscCall(VecGetArrayRead(lam0, &l));
  PetscCall(VecGetArrayRead(ratelam, &r));
  for (PetscInt i = 0; i < ct->n; i++) {
    leaf[NODE_VALUES * i] = l[i], leaf[NODE_VALUES * i + 1] = r[i];
    leaf[NODE_VALUES * i + 2] = ct->active[i] ? 1 : 0, leaf[NODE_VALUES * i + 3] = 1;
  }
  PetscCall(VecRestoreArrayRead(lam0, &l));
  PetscCall(VecRestoreArrayRead(ratelam, &r));
  PetscCall(fe_natural_gather(&m, NODE_VALUES, leaf, "nodes", &x));
  PetscCall(PetscViewerHDF5PushGroup(v, "/contact"));
  PetscCall(VecView(x, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscFree(leaf));
  PetscCall(fe_natural_destroy(&m));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_io_read(Contact *ct, DM dm, PetscViewer v, Vec lam0, Vec ratelam) {
  FeNatural    m;
  PetscScalar *leaf, *l, *r;
  Vec          x;
  PetscInt     missing = 0;
  PetscFunctionBeginUser;
  PetscCall(contact_natural(ct, dm, &m));
  PetscCall(fe_natural_vec(&m, NODE_VALUES, "nodes", &x));
  PetscCall(PetscViewerHDF5PushGroup(v, "/contact"));
  PetscCall(VecLoad(x, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscMalloc1(NODE_VALUES * ct->n + 1, &leaf));
  PetscCall(fe_natural_scatter(&m, NODE_VALUES, x, leaf));
  PetscCall(VecGetArray(lam0, &l));
  PetscCall(VecGetArray(ratelam, &r));
  for (PetscInt i = 0; i < ct->n; i++) {
    l[i] = leaf[NODE_VALUES * i], r[i] = leaf[NODE_VALUES * i + 1];
    ct->active[i] = PetscRealPart(leaf[NODE_VALUES * i + 2]) > 0.5 ? PETSC_TRUE : PETSC_FALSE;
    missing += PetscRealPart(leaf[NODE_VALUES * i + 3]) != 1;
  }
  PetscCall(VecRestoreArray(lam0, &l));
  PetscCall(VecRestoreArray(ratelam, &r));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscFree(leaf));
  PetscCall(fe_natural_destroy(&m));
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &missing, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)dm)));
  PetscCheck(!missing, PetscObjectComm((PetscObject)dm), PETSC_ERR_FILE_UNEXPECTED,
             "the checkpoint holds no multiplier for %d of the potential contact nodes (another contact surface)", (int)missing);
  PetscFunctionReturn(0);
}
