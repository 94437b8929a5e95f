#include "fe_state.h"

#include <petsclayouthdf5.h>
#include <petscviewerhdf5.h>

#include "fe_natural.h"

static PetscBool has_evp(const FeProblem *p) { return material_quantity_size(&p->pts.mat, MATERIAL_EVP) == 6 ? PETSC_TRUE : PETSC_FALSE; }

/* Component i of quantity q (material_point.h) at point k of the state array a (the committed or the trial one). */
static PetscReal point_quantity(const FeProblem *p, const PetscReal *a, PetscInt k, MaterialQuantity q, PetscInt i) {
  return material_quantity(&p->pts.mat, &a[k * p->pts.nsv + ST_STATEV], q, (int)i);
}

PetscErrorCode fe_state_commit(FeProblem *p, PetscReal h) {
  PetscFunctionBeginUser;
  if (has_evp(p)) {
    if (!p->pts.devp_prev) PetscCall(PetscCalloc1(6 * p->space.npoint + 1, &p->pts.devp_prev));
    for (PetscInt k = 0; k < p->space.npoint; k++)
      for (PetscInt i = 0; i < 6; i++)
        p->pts.devp_prev[6 * k + i] = point_quantity(p, p->pts.trial, k, MATERIAL_EVP, i) - point_quantity(p, p->pts.state, k, MATERIAL_EVP, i);
    p->pts.have_devp = h > 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(fe_problem_commit(p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_state_volume_error(FeProblem *p, PetscReal h, PetscReal h_prev, PetscReal *err) {
  PetscReal loc[3] = {0, 0, 0}, all[3];
  PetscFunctionBeginUser;
  *err = -1;
  if (!has_evp(p) || !p->pts.have_devp || !(h > 0 && h_prev > 0)) PetscFunctionReturn(0);
  PetscReal r = h / h_prev;
  for (PetscInt k = 0; k < p->space.npoint; k++) {
    PetscReal w = p->space.wdetJ[k];
    for (PetscInt i = 0; i < 6; i++) {
      PetscReal tr = point_quantity(p, p->pts.trial, k, MATERIAL_EVP, i), d = tr - point_quantity(p, p->pts.state, k, MATERIAL_EVP, i);
      loc[0] += w * PetscSqr(d - r * p->pts.devp_prev[6 * k + i]), loc[1] += w * d * d, loc[2] += w * tr * tr;
    }
  }
  PetscCall(MPIU_Allreduce(loc, all, 3, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)p->space.dm)));
  *err = PetscSqrtReal(all[0]) / PetscMax(PetscSqrtReal(all[1]), 1e-9 * PetscSqrtReal(all[2]) + 1e-300);
  PetscFunctionReturn(0);
}

/* The nodes of the field: the vertices, and the edges of P2. */
static PetscInt node_depths(const FeProblem *p, PetscInt depths[2]) {
  depths[0] = 0, depths[1] = 1;
  return p->space.order > 1 ? 2 : 1;
}

static PetscErrorCode view_in(PetscViewer v, const char *group, Vec x) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, group));
  PetscCall(VecView(x, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

static PetscErrorCode load_from(PetscViewer v, const char *group, Vec x) {
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(v, group));
  PetscCall(VecLoad(x, v));
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscFunctionReturn(0);
}

/* Per-cell blocks of the points' arrays (nc values per point: the state, or the viscoplastic increments). */
static PetscErrorCode cells_view(FeProblem *p, const FeNatural *m, PetscViewer v, const char *name, const PetscReal *a, PetscInt nc) {
  PetscScalar *leaf;
  Vec          x;
  const PetscInt bs = p->space.nq * nc;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m->n * bs + 1, &leaf));
  for (PetscInt k = 0; k < m->n; k++) PetscCall(PetscArraycpy(&leaf[k * bs], &a[(m->points[k] - p->space.cStart) * bs], bs));
  PetscCall(fe_natural_gather(m, bs, leaf, name, &x));
  PetscCall(view_in(v, "/cells", x));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscFree(leaf));
  PetscFunctionReturn(0);
}

static PetscErrorCode cells_read(FeProblem *p, const FeNatural *m, PetscViewer v, const char *name, PetscReal *a, PetscInt nc) {
  PetscScalar *leaf;
  Vec          x;
  const PetscInt bs = p->space.nq * nc;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(m->n * bs + 1, &leaf));
  PetscCall(fe_natural_vec(m, bs, name, &x));
  PetscCall(load_from(v, "/cells", x));
  PetscCall(fe_natural_scatter(m, bs, x, leaf));
  for (PetscInt k = 0; k < m->n; k++) PetscCall(PetscArraycpy(&a[(m->points[k] - p->space.cStart) * bs], &leaf[k * bs], bs));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscFree(leaf));
  PetscFunctionReturn(0);
}

/* A global vector of the field at its nodes (constrained components 0, in the nodes' frames) in natural order. */
static PetscErrorCode nodes_view(FeProblem *p, const FeNatural *m, PetscViewer v, Vec U, const char *name) {
  Vec          L, x;
  PetscSection s;
  PetscScalar *u, *leaf;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(p->space.dm, &s));
  PetscCall(DMGetLocalVector(p->space.dm, &L));
  PetscCall(VecZeroEntries(L));
  PetscCall(DMGlobalToLocal(p->space.dm, U, INSERT_VALUES, L));
  PetscCall(VecGetArray(L, &u));
  PetscCall(PetscMalloc1(m->n * p->space.dim + 1, &leaf));
  for (PetscInt k = 0; k < m->n; k++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, m->points[k], &off));
    for (PetscInt c = 0; c < p->space.dim; c++) leaf[k * p->space.dim + c] = u[off + c];
  }
  PetscCall(VecRestoreArray(L, &u));
  PetscCall(DMRestoreLocalVector(p->space.dm, &L));
  PetscCall(fe_natural_gather(m, p->space.dim, leaf, name, &x));
  PetscCall(view_in(v, "/nodes", x));
  PetscCall(VecDestroy(&x));
  PetscCall(PetscFree(leaf));
  PetscFunctionReturn(0);
}

/* Back: every local node (ghosts too) gets its value, then the owned unconstrained ones make the global vector. */
static PetscErrorCode nodes_read(FeProblem *p, const FeNatural *m, PetscViewer v, Vec U, const char *name) {
  Vec          L, x;
  PetscSection s;
  PetscScalar *u, *leaf;
  PetscFunctionBeginUser;
  PetscCall(fe_natural_vec(m, p->space.dim, name, &x));
  PetscCall(load_from(v, "/nodes", x));
  PetscCall(PetscMalloc1(m->n * p->space.dim + 1, &leaf));
  PetscCall(fe_natural_scatter(m, p->space.dim, x, leaf));
  PetscCall(VecDestroy(&x));
  PetscCall(DMGetLocalSection(p->space.dm, &s));
  PetscCall(DMGetLocalVector(p->space.dm, &L));
  PetscCall(VecZeroEntries(L));
  PetscCall(VecGetArray(L, &u));
  for (PetscInt k = 0; k < m->n; k++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(s, m->points[k], &off));
    for (PetscInt c = 0; c < p->space.dim; c++) u[off + c] = leaf[k * p->space.dim + c];
  }
  PetscCall(VecRestoreArray(L, &u));
  PetscCall(DMLocalToGlobal(p->space.dm, L, INSERT_VALUES, U));
  PetscCall(DMRestoreLocalVector(p->space.dm, &L));
  PetscCall(PetscFree(leaf));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_state_view(FeProblem *p, PetscViewer v, PetscInt nvec, Vec vecs[], const char *const names[]) {
  FeNatural   nodes, cells;
  PetscInt    depths[2], nd = node_depths(p, depths);
  PetscMPIInt rank, size;
  Vec         calls;
  MPI_Comm    comm = PetscObjectComm((PetscObject)p->space.dm);
  PetscFunctionBeginUser;
  PetscCall(fe_natural_create(p->space.dm, nd, depths, PETSC_FALSE, &nodes));
  PetscCall(fe_natural_create(p->space.dm, 1, &p->space.dim, PETSC_FALSE, &cells));
  for (PetscInt k = 0; k < nvec; k++) PetscCall(nodes_view(p, &nodes, v, vecs[k], names[k]));
  PetscCall(cells_view(p, &cells, v, "state", p->pts.state, p->pts.nsv));
  if (has_evp(p)) {
    if (!p->pts.devp_prev) PetscCall(PetscCalloc1(6 * p->space.npoint + 1, &p->pts.devp_prev));
    PetscCall(cells_view(p, &cells, v, "devp", p->pts.devp_prev, 6));
  }
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(VecCreateMPI(comm, 1, size, &calls));
  PetscCall(PetscObjectSetName((PetscObject)calls, "umat_calls"));
  PetscCall(VecSetValue(calls, rank, (PetscScalar)p->diag.umat_calls, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(calls));
  PetscCall(VecAssemblyEnd(calls));
  PetscCall(view_in(v, "/", calls));
  PetscCall(VecDestroy(&calls));
  PetscCall(fe_natural_destroy(&nodes));
  PetscCall(fe_natural_destroy(&cells));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_state_read(FeProblem *p, PetscViewer v, PetscInt nvec, Vec vecs[], const char *const names[]) {
  FeNatural   nodes, cells;
  PetscInt    depths[2], nd = node_depths(p, depths), bs, nold;
  PetscMPIInt rank, size;
  Vec         calls;
  MPI_Comm    comm = PetscObjectComm((PetscObject)p->space.dm);
  PetscFunctionBeginUser;
  PetscCall(fe_natural_create(p->space.dm, nd, depths, PETSC_TRUE, &nodes));
  PetscCall(fe_natural_create(p->space.dm, 1, &p->space.dim, PETSC_FALSE, &cells));
  for (PetscInt k = 0; k < nvec; k++) PetscCall(nodes_read(p, &nodes, v, vecs[k], names[k]));
  PetscCall(cells_read(p, &cells, v, "state", p->pts.state, p->pts.nsv));
  if (has_evp(p)) {
    if (!p->pts.devp_prev) PetscCall(PetscCalloc1(6 * p->space.npoint + 1, &p->pts.devp_prev));
    PetscCall(cells_read(p, &cells, v, "devp", p->pts.devp_prev, 6));
  }
  PetscCall(PetscArraycpy(p->pts.trial, p->pts.state, p->space.npoint * p->pts.nsv));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscViewerHDF5ReadSizes(v, "umat_calls", &bs, &nold));
  PetscCall(VecCreateMPI(comm, nold == size ? 1 : PETSC_DECIDE, nold, &calls));
  PetscCall(PetscObjectSetName((PetscObject)calls, "umat_calls"));
  PetscCall(load_from(v, "/", calls));
  if (nold == size) {
    const PetscScalar *c;
    PetscCall(VecGetArrayRead(calls, &c));
    p->diag.umat_calls = (PetscInt)PetscRealPart(c[0]);
    PetscCall(VecRestoreArrayRead(calls, &c));
  } else {
    PetscScalar sum;
    PetscCall(VecSum(calls, &sum));
    p->diag.umat_calls = rank ? 0 : (PetscInt)PetscRealPart(sum);
  }
  PetscCall(VecDestroy(&calls));
  PetscCall(fe_natural_destroy(&nodes));
  PetscCall(fe_natural_destroy(&cells));
  PetscFunctionReturn(0);
}

/* ---- volume statistics (fe_problem.h) ---- */

static int cmp_real(const void *a, const void *b) {
  PetscReal x = *(const PetscReal *)a, y = *(const PetscReal *)b;
  return (x > y) - (x < y);
}

PetscErrorCode fe_problem_stats(FeProblem *p, PetscInt axis, FeStats *s, PetscBool use_trial, PetscBool quantiles) {
  MPI_Comm        comm = PetscObjectComm((PetscObject)p->space.dm);
  PetscReal       loc[14] = {0}, glob[14];
  const PetscReal *src = use_trial ? p->pts.trial : p->pts.state;
  PetscMPIInt     size, rank;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(s, sizeof *s));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscReal *vals;
  PetscCall(PetscMalloc1(2 * p->space.npoint + 1, &vals));
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    for (PetscInt q = 0; q < p->space.nq; q++) {
      const PetscInt   k  = SV(p, c, q);
      const PetscReal *st = &src[k * p->pts.nsv];
      PetscReal        w  = p->space.wdetJ[k];
      loc[0] += w;
      for (PetscInt vI = 0; vI < 6; vI++) loc[1 + vI] += w * st[ST_STRAN + vI], loc[7 + vI] += w * st[ST_STRESS + vI];
      if (has_evp(p)) {
        PetscReal d2 = 0;
        for (PetscInt vI = 0; vI < 6; vI++) d2 += PetscSqr(point_quantity(p, src, k, MATERIAL_EVP, vI) - point_quantity(p, p->pts.state, k, MATERIAL_EVP, vI));
        loc[13] += w * PetscSqrtReal(d2);
        vals[k]             = point_quantity(p, src, k, MATERIAL_EVP_HARD, axis); /* axial vp strain */
        vals[p->space.npoint + k] = point_quantity(p, src, k, MATERIAL_EVP_SOFT, axis);
      }
    }
  }
  PetscCall(MPIU_Allreduce(loc, glob, 14, MPIU_REAL, MPIU_SUM, comm));
  s->volume = glob[0];
  for (PetscInt vI = 0; vI < 6; vI++) s->strain_mean[vI] = glob[1 + vI] / glob[0], s->stress_mean[vI] = glob[7 + vI] / glob[0];
  s->evp_rate = p->dt > 0 ? glob[13] / glob[0] / p->dt : 0;
  PetscReal spread = 0;
  for (PetscInt k = 0; k < p->space.npoint; k++)
    for (PetscInt vI = 0; vI < 6; vI++) spread = PetscMax(spread, PetscAbsReal(src[k * p->pts.nsv + ST_STRAN + vI] - s->strain_mean[vI]));
  PetscCall(MPIU_Allreduce(&spread, &s->strain_spread, 1, MPIU_REAL, MPIU_MAX, comm));
  if (quantiles && has_evp(p)) {
    /* Gather both frames' values on rank 0 for the quantiles. */
    PetscMPIInt n = (PetscMPIInt)p->space.npoint, *counts = NULL, *displs = NULL, total = 0;
    if (!rank) PetscCall(PetscMalloc2(size, &counts, size, &displs));
    PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    if (!rank)
      for (PetscMPIInt r = 0; r < size; r++) displs[r] = total, total += counts[r];
    PetscReal *all = NULL;
    if (!rank) PetscCall(PetscMalloc1(total + 1, &all));
    for (PetscInt f = 0; f < 2; f++) {
      PetscCallMPI(MPI_Gatherv(vals + f * p->space.npoint, n, MPIU_REAL, all, counts, displs, MPIU_REAL, 0, comm));
      if (!rank && total) {
        qsort(all, (size_t)total, sizeof(PetscReal), cmp_real);
        PetscReal mean = 0;
        for (PetscMPIInt k = 0; k < total; k++) mean += all[k];
        s->frame_evp[f][0] = mean / total;
        s->frame_evp[f][1] = all[0];
        s->frame_evp[f][2] = all[total / 4];
        s->frame_evp[f][3] = all[total / 2];
        s->frame_evp[f][4] = all[(3 * total) / 4];
        s->frame_evp[f][5] = all[total - 1];
      }
    }
    if (!rank) {
      PetscCall(PetscFree(all));
      PetscCall(PetscFree2(counts, displs));
    }
  }
  PetscCall(PetscFree(vals));
  PetscFunctionReturn(0);
}
