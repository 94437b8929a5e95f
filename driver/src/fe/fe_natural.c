#include "fe_natural.h"

static const char NATURAL_KEY[] = "cc9_natural";       /* IS: per local point, its index in its stratum of the serial mesh */
static const char SIZES_KEY[]   = "cc9_natural_sizes"; /* IS: the size of each depth stratum of the serial mesh */

PetscErrorCode fe_natural_setup(DM serial, DM dist, PetscSF migration) {
  MPI_Comm    comm = PetscObjectComm((PetscObject)serial);
  DM          dm   = dist ? dist : serial;
  PetscMPIInt rank;
  PetscInt    dim, start[4] = {0, 0, 0, 0}, size[4] = {0, 0, 0, 0}, pStart, pEnd, *nat;
  IS          is;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(DMGetDimension(serial, &dim));
  for (PetscInt d = 0; d <= dim; d++) { /* the serial mesh lives on rank 0 */
    PetscInt s, e;
    PetscCall(DMPlexGetDepthStratum(serial, d, &s, &e));
    start[d] = s, size[d] = e - s;
  }
  PetscCallMPI(MPI_Bcast(start, 4, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(size, 4, MPIU_INT, 0, comm));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscMalloc1(pEnd - pStart + 1, &nat));
  for (PetscInt p = pStart; p < pEnd; p++) nat[p - pStart] = -1;
  if (!dist || !migration) {
    for (PetscInt p = pStart; p < pEnd; p++) nat[p - pStart] = p; /* serial numbers themselves */
  } else {
    const PetscInt    *ilocal;
    const PetscSFNode *iremote;
    PetscInt           nleaves;
    PetscCall(PetscSFGetGraph(migration, NULL, &nleaves, &ilocal, &iremote));
    for (PetscInt l = 0; l < nleaves; l++) {
      PetscInt p = ilocal ? ilocal[l] : l;
      PetscCheck(iremote[l].rank == 0 && p >= pStart && p < pEnd, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "fe_natural: a point that does not come from the serial mesh on rank 0");
      nat[p - pStart] = iremote[l].index;
    }
  }
  for (PetscInt p = pStart; p < pEnd; p++) {
    PetscInt d;
    PetscCall(DMPlexGetPointDepth(dm, p, &d));
    PetscCheck(nat[p - pStart] >= start[d] && nat[p - pStart] < start[d] + size[d], PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "fe_natural: point %d (depth %d) has no place in the serial mesh", (int)p, (int)d);
    nat[p - pStart] -= start[d];
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, pEnd - pStart, nat, PETSC_OWN_POINTER, &is));
  PetscCall(PetscObjectCompose((PetscObject)dm, NATURAL_KEY, (PetscObject)is));
  PetscCall(ISDestroy(&is));
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, dim + 1, size, PETSC_COPY_VALUES, &is));
  PetscCall(PetscObjectCompose((PetscObject)dm, SIZES_KEY, (PetscObject)is));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

static PetscErrorCode natural_of(DM dm, const PetscInt **nat, const PetscInt **size) {
  IS a, b;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectQuery((PetscObject)dm, NATURAL_KEY, (PetscObject *)&a));
  PetscCall(PetscObjectQuery((PetscObject)dm, SIZES_KEY, (PetscObject *)&b));
  PetscCheck(a && b, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONGSTATE, "fe_natural: the mesh has no natural numbering (fe_mesh_create)");
  PetscCall(ISGetIndices(a, nat)); /* kept by the DM: the indices stay valid while it lives */
  PetscCall(ISGetIndices(b, size));
  PetscCall(ISRestoreIndices(a, nat));
  PetscCall(ISRestoreIndices(b, size));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_indices(DM dm, const PetscInt **nat) {
  const PetscInt *size;
  PetscFunctionBeginUser;
  PetscCall(natural_of(dm, nat, &size));
  PetscFunctionReturn(0);
}

/* The star forest of m from its points' natural numbers gidx; readers: a natural place has exactly one point (1),
   at most one (0), or any number (-1: ghosts read it too). */
static PetscErrorCode natural_sf(MPI_Comm comm, FeNatural *m, const PetscInt gidx[], int readers) {
  PetscLayout layout;
  PetscInt   *one, *count, bad = 0, all;
  PetscFunctionBeginUser;
  PetscCall(PetscLayoutCreate(comm, &layout));
  PetscCall(PetscLayoutSetSize(layout, m->N));
  PetscCall(PetscLayoutSetBlockSize(layout, 1));
  PetscCall(PetscLayoutSetUp(layout));
  PetscCall(PetscLayoutGetLocalSize(layout, &m->nroot));
  PetscCall(PetscSFCreate(comm, &m->sf));
  PetscCall(PetscSFSetGraphLayout(m->sf, layout, m->n, NULL, PETSC_COPY_VALUES, (PetscInt *)gidx));
  PetscCall(PetscSFSetUp(m->sf));
  PetscCall(PetscLayoutDestroy(&layout));
  if (readers < 0) PetscFunctionReturn(0);
  PetscCall(PetscMalloc2(m->n + 1, &one, m->nroot + 1, &count));
  for (PetscInt i = 0; i < m->n; i++) one[i] = 1;
  for (PetscInt i = 0; i < m->nroot; i++) count[i] = 0;
  PetscCall(PetscSFReduceBegin(m->sf, MPIU_INT, one, count, MPI_SUM));
  PetscCall(PetscSFReduceEnd(m->sf, MPIU_INT, one, count, MPI_SUM));
  for (PetscInt i = 0; i < m->nroot; i++) bad += readers ? count[i] != 1 : count[i] > 1;
  PetscCall(PetscFree2(one, count));
  PetscCall(MPIU_Allreduce(&bad, &all, 1, MPIU_INT, MPI_SUM, comm));
  PetscCheck(!all, comm, PETSC_ERR_PLIB, "fe_natural: %d natural places without exactly one owner", (int)all);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_create(DM dm, PetscInt ndepth, const PetscInt depths[], PetscBool ghosts, FeNatural *m) {
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);
  const PetscInt    *nat, *size, *leaves;
  PetscInt           nleaves, *sorted = NULL, *gidx = NULL, pStart;
  PetscSF            psf;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof *m));
  PetscCall(natural_of(dm, &nat, &size));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCheck(pStart == 0, comm, PETSC_ERR_SUP, "fe_natural: a chart that does not start at 0");
  PetscCall(DMGetPointSF(dm, &psf));
  PetscCall(PetscSFGetGraph(psf, NULL, &nleaves, &leaves, NULL));
  nleaves = PetscMax(nleaves, 0);
  PetscCall(PetscMalloc1(nleaves + 1, &sorted));
  for (PetscInt l = 0; l < nleaves; l++) sorted[l] = leaves ? leaves[l] : l;
  PetscCall(PetscSortInt(nleaves, sorted));
  for (PetscInt pass = 0; pass < 2; pass++) { /* count, then fill */
    m->n = 0, m->N = 0;
    for (PetscInt k = 0; k < ndepth; k++) {
      PetscInt s, e;
      m->offset[k] = m->N, m->N += size[depths[k]];
      PetscCall(DMPlexGetDepthStratum(dm, depths[k], &s, &e));
      for (PetscInt p = s; p < e; p++) {
        PetscInt loc;
        PetscCall(PetscFindInt(p, nleaves, sorted, &loc));
        if (loc >= 0 && !ghosts) continue; /* a ghost: another rank owns it */
        if (pass) m->points[m->n] = p, gidx[m->n] = m->offset[k] + nat[p];
        m->n++;
      }
    }
    if (!pass) {
      PetscCall(PetscMalloc1(m->n + 1, &m->points));
      PetscCall(PetscMalloc1(m->n + 1, &gidx));
    }
  }
  PetscCall(PetscFree(sorted));
  PetscCall(natural_sf(comm, m, gidx, ghosts ? -1 : 1));
  PetscCall(PetscFree(gidx));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_create_points(DM dm, PetscInt depth, PetscInt n, const PetscInt points[], FeNatural *m) {
  const PetscInt *nat, *size;
  PetscInt       *gidx;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof *m));
  PetscCall(natural_of(dm, &nat, &size));
  m->n = n, m->N = size[depth];
  PetscCall(PetscMalloc1(n + 1, &m->points));
  PetscCall(PetscMalloc1(n + 1, &gidx));
  for (PetscInt i = 0; i < n; i++) m->points[i] = points[i], gidx[i] = nat[points[i]];
  PetscCall(natural_sf(PetscObjectComm((PetscObject)dm), m, gidx, 0));
  PetscCall(PetscFree(gidx));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_destroy(FeNatural *m) {
  PetscFunctionBeginUser;
  PetscCall(PetscSFDestroy(&m->sf));
  PetscCall(PetscFree(m->points));
  PetscFunctionReturn(0);
}

static PetscErrorCode unit(MPI_Datatype base, PetscInt bs, MPI_Datatype *t) {
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Type_contiguous((PetscMPIInt)bs, base, t));
  PetscCallMPI(MPI_Type_commit(t));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_vec(const FeNatural *m, PetscInt bs, const char *name, Vec *nat) {
  PetscFunctionBeginUser;
  PetscCall(VecCreate(PetscObjectComm((PetscObject)m->sf), nat));
  PetscCall(VecSetSizes(*nat, m->nroot * bs, m->N * bs));
  PetscCall(VecSetBlockSize(*nat, bs));
  PetscCall(VecSetType(*nat, VECSTANDARD));
  PetscCall(PetscObjectSetName((PetscObject)*nat, name));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_gather(const FeNatural *m, PetscInt bs, const PetscScalar leaf[], const char *name, Vec *nat) {
  MPI_Datatype t;
  PetscScalar *root;
  PetscFunctionBeginUser;
  PetscCall(fe_natural_vec(m, bs, name, nat));
  PetscCall(unit(MPIU_SCALAR, bs, &t));
  PetscCall(VecGetArray(*nat, &root));
  PetscCall(PetscSFReduceBegin(m->sf, t, leaf, root, MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(m->sf, t, leaf, root, MPI_REPLACE));
  PetscCall(VecRestoreArray(*nat, &root));
  PetscCallMPI(MPI_Type_free(&t));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_scatter(const FeNatural *m, PetscInt bs, Vec nat, PetscScalar leaf[]) {
  MPI_Datatype       t;
  const PetscScalar *root;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(nat, &n));
  PetscCheck(n == m->nroot * bs, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ, "fe_natural: %d values here, expected %d", (int)n, (int)(m->nroot * bs));
  PetscCall(unit(MPIU_SCALAR, bs, &t));
  PetscCall(VecGetArrayRead(nat, &root));
  PetscCall(PetscSFBcastBegin(m->sf, t, root, leaf, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(m->sf, t, root, leaf, MPI_REPLACE));
  PetscCall(VecRestoreArrayRead(nat, &root));
  PetscCallMPI(MPI_Type_free(&t));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_natural_gather_int(const FeNatural *m, PetscInt bs, const PetscInt leaf[], PetscInt root[]) {
  MPI_Datatype t;
  PetscFunctionBeginUser;
  PetscCall(unit(MPIU_INT, bs, &t));
  PetscCall(PetscSFReduceBegin(m->sf, t, leaf, root, MPI_REPLACE));
  PetscCall(PetscSFReduceEnd(m->sf, t, leaf, root, MPI_REPLACE));
  PetscCallMPI(MPI_Type_free(&t));
  PetscFunctionReturn(0);
}
