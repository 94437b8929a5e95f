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
