#include "fe_state.h"

#include "camclay9.h"

static PetscBool has_evp(const FeProblem *p) { return p->mat.nstatv >= CAMCLAY9_NSTATV_MIN ? PETSC_TRUE : PETSC_FALSE; }

PetscErrorCode fe_state_commit(FeProblem *p, PetscReal h) {
  PetscFunctionBeginUser;
  if (has_evp(p)) {
    if (!p->devp_prev) PetscCall(PetscCalloc1(6 * p->npoint + 1, &p->devp_prev));
    for (PetscInt k = 0; k < p->npoint; k++)
      for (PetscInt i = 0; i < 6; i++)
        p->devp_prev[6 * k + i] = p->trial[k * p->nsv + ST_STATEV + CAMCLAY9_SV_EVP + i] - p->state[k * p->nsv + ST_STATEV + CAMCLAY9_SV_EVP + i];
    p->have_devp = h > 0 ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCall(fe_problem_commit(p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_state_volume_error(FeProblem *p, PetscReal h, PetscReal h_prev, PetscReal *err) {
  PetscReal loc[3] = {0, 0, 0}, all[3];
  PetscFunctionBeginUser;
  *err = -1;
  if (!has_evp(p) || !p->have_devp || !(h > 0 && h_prev > 0)) PetscFunctionReturn(0);
  PetscReal r = h / h_prev;
  for (PetscInt k = 0; k < p->npoint; k++) {
    const PetscReal *tr = &p->trial[k * p->nsv + ST_STATEV + CAMCLAY9_SV_EVP], *st = &p->state[k * p->nsv + ST_STATEV + CAMCLAY9_SV_EVP];
    PetscReal        w  = p->wdetJ[k];
    for (PetscInt i = 0; i < 6; i++) {
      PetscReal d = tr[i] - st[i];
      loc[0] += w * PetscSqr(d - r * p->devp_prev[6 * k + i]), loc[1] += w * d * d, loc[2] += w * tr[i] * tr[i];
    }
  }
  PetscCall(MPIU_Allreduce(loc, all, 3, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)p->dm)));
  *err = PetscSqrtReal(all[0]) / PetscMax(PetscSqrtReal(all[1]), 1e-9 * PetscSqrtReal(all[2]) + 1e-300);
  PetscFunctionReturn(0);
}

int fe_state_save(FeProblem *p, Vec U, BinFile *f) {
  PetscInt           nloc, has = p->devp_prev != NULL;
  const PetscScalar *u;
  if (VecGetLocalSize(U, &nloc) || VecGetArrayRead(U, &u)) return 1;
  binfile_write(f, &nloc, sizeof nloc, 1);
  binfile_write(f, u, sizeof(PetscScalar), (size_t)nloc);
  if (VecRestoreArrayRead(U, &u)) return 1;
  binfile_write(f, &p->npoint, sizeof p->npoint, 1);
  binfile_write(f, &p->nsv, sizeof p->nsv, 1);
  binfile_write(f, p->state, sizeof(PetscReal), (size_t)(p->npoint * p->nsv));
  binfile_write(f, &has, sizeof has, 1);
  if (has) binfile_write(f, p->devp_prev, sizeof(PetscReal), (size_t)(6 * p->npoint));
  binfile_write(f, &p->have_devp, sizeof p->have_devp, 1);
  binfile_write(f, &p->umat_calls, sizeof p->umat_calls, 1);
  return !f->ok;
}

int fe_state_load(FeProblem *p, Vec U, BinFile *f) {
  PetscInt     nloc = -1, mine, npoint = -1, nsv = -1, has = 0;
  PetscScalar *u;
  if (VecGetLocalSize(U, &mine)) return 1;
  binfile_read(f, &nloc, sizeof nloc, 1);
  if (nloc != mine) return 1; /* another mesh or partition */
  if (VecGetArray(U, &u)) return 1;
  binfile_read(f, u, sizeof(PetscScalar), (size_t)nloc);
  if (VecRestoreArray(U, &u)) return 1;
  binfile_read(f, &npoint, sizeof npoint, 1);
  binfile_read(f, &nsv, sizeof nsv, 1);
  if (npoint != p->npoint || nsv != p->nsv) return 1;
  binfile_read(f, p->state, sizeof(PetscReal), (size_t)(npoint * nsv));
  binfile_read(f, &has, sizeof has, 1);
  if (has) {
    if (!p->devp_prev && PetscCalloc1(6 * p->npoint + 1, &p->devp_prev)) return 1;
    binfile_read(f, p->devp_prev, sizeof(PetscReal), (size_t)(6 * p->npoint));
  }
  binfile_read(f, &p->have_devp, sizeof p->have_devp, 1);
  binfile_read(f, &p->umat_calls, sizeof p->umat_calls, 1);
  if (f->ok) PetscArraycpy(p->trial, p->state, p->npoint * p->nsv);
  return !f->ok;
}

/* ---- volume statistics (fe_problem.h) ---- */

static int cmp_real(const void *a, const void *b) {
  PetscReal x = *(const PetscReal *)a, y = *(const PetscReal *)b;
  return (x > y) - (x < y);
}

PetscErrorCode fe_problem_stats(FeProblem *p, PetscInt axis, FeStats *s, PetscBool use_trial, PetscBool quantiles) {
  MPI_Comm        comm = PetscObjectComm((PetscObject)p->dm);
  PetscReal       loc[14] = {0}, glob[14];
  const PetscReal *src = use_trial ? p->trial : p->state;
  PetscMPIInt     size, rank;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(s, sizeof *s));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscReal *vals;
  PetscCall(PetscMalloc1(2 * p->npoint + 1, &vals));
  for (PetscInt c = p->cStart; c < p->cEnd; c++) {
    for (PetscInt q = 0; q < p->nq; q++) {
      const PetscReal *st = &src[SV(p, c, q) * p->nsv], *old = &p->state[SV(p, c, q) * p->nsv];
      PetscReal        w  = p->wdetJ[SV(p, c, q)];
      loc[0] += w;
      for (PetscInt vI = 0; vI < 6; vI++) loc[1 + vI] += w * st[ST_STRAN + vI], loc[7 + vI] += w * st[ST_STRESS + vI];
      if (p->mat.nstatv >= CAMCLAY9_NSTATV_MIN) {
        PetscReal d2 = 0;
        for (PetscInt vI = 0; vI < 6; vI++)
          d2 += PetscSqr(st[ST_STATEV + CAMCLAY9_SV_EVP + vI] - old[ST_STATEV + CAMCLAY9_SV_EVP + vI]);
        loc[13] += w * PetscSqrtReal(d2);
        vals[SV(p, c, q)]             = st[ST_STATEV + CAMCLAY9_SV_EVP_HARD + axis]; /* axial vp strain */
        vals[p->npoint + SV(p, c, q)] = st[ST_STATEV + CAMCLAY9_SV_EVP_SOFT + axis];
      }
    }
  }
  PetscCall(MPIU_Allreduce(loc, glob, 14, MPIU_REAL, MPIU_SUM, comm));
  s->volume = glob[0];
  for (PetscInt vI = 0; vI < 6; vI++) s->strain_mean[vI] = glob[1 + vI] / glob[0], s->stress_mean[vI] = glob[7 + vI] / glob[0];
  s->evp_rate = p->dt > 0 ? glob[13] / glob[0] / p->dt : 0;
  PetscReal spread = 0;
  for (PetscInt k = 0; k < p->npoint; k++)
    for (PetscInt vI = 0; vI < 6; vI++) spread = PetscMax(spread, PetscAbsReal(src[k * p->nsv + ST_STRAN + vI] - s->strain_mean[vI]));
  PetscCall(MPIU_Allreduce(&spread, &s->strain_spread, 1, MPIU_REAL, MPIU_MAX, comm));
  if (quantiles && p->mat.nstatv >= CAMCLAY9_NSTATV_MIN) {
    /* Gather both frames' values on rank 0 for the quantiles. */
    PetscMPIInt n = (PetscMPIInt)p->npoint, *counts = NULL, *displs = NULL, total = 0;
    if (!rank) PetscCall(PetscMalloc2(size, &counts, size, &displs));
    PetscCallMPI(MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, 0, comm));
    if (!rank)
      for (PetscMPIInt r = 0; r < size; r++) displs[r] = total, total += counts[r];
    PetscReal *all = NULL;
    if (!rank) PetscCall(PetscMalloc1(total + 1, &all));
    for (PetscInt f = 0; f < 2; f++) {
      PetscCallMPI(MPI_Gatherv(vals + f * p->npoint, n, MPIU_REAL, all, counts, displs, MPIU_REAL, 0, comm));
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
