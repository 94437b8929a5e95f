/* The element loops of the FE problem: the residual with the UMAT at every quadrature point (which also caches
 * its tangents), the Jacobian assembled from the cached tangents (MatSetValues or COO), and the same Jacobian
 * applied to a vector without assembling it (the matrix-free operator of the contact solver). The kernels at a
 * point are fe_kernel.h's. */
#include "fe_kernel.h"
#include "fe_problem.h"
#include "../io/log_events.h"

#include <string.h>
#include <time.h>

static inline KernelPoint kernel_point(const FeProblem *p, PetscInt k) {
  const FeSpace *s  = &p->space;
  KernelPoint    kp = {s->dim, s->ns, &s->grad[k * s->ns * s->dim], s->shape_r ? &s->shape_r[k * s->ns] : NULL};
  return kp;
}

/* The call of point k (local cell c, quadrature point q) at total strain eps, from its committed state. */
static void call_from_state(const FeProblem *p, PetscInt c, PetscInt q, const PetscReal eps[6], UmatCall *call) {
  const PetscReal *st = &p->pts.state[SV(p, c, q) * p->pts.nsv];
  memcpy(call->stress, st + ST_STRESS, sizeof call->stress);
  memcpy(call->statev, st + ST_STATEV, sizeof(double) * (size_t)p->pts.mat.nstatv);
  memcpy(call->stran, st + ST_STRAN, sizeof call->stran);
  for (PetscInt vI = 0; vI < p->pts.mat.ntens; vI++) call->dstran[vI] = eps[vI] - st[ST_STRAN + vI];
  call->time[0] = call->time[1] = p->time - p->dt;
  call->dtime                   = p->dt;
  call->noel                    = (int)c + 1;
  call->npt                     = (int)q + 1;
  call->kstep = call->kinc = 1;
  call->sse = call->spd = call->scd = 0;
}

/* Its results: the trial state at eps, and the tangent cache. */
static void call_to_trial(FeProblem *p, PetscInt c, PetscInt q, const PetscReal eps[6], const UmatCall *call) {
  const PetscInt k  = SV(p, c, q);
  PetscReal     *tr = &p->pts.trial[k * p->pts.nsv];
  memcpy(tr + ST_STRESS, call->stress, sizeof call->stress);
  memcpy(tr + ST_STRAN, eps, 6 * sizeof(PetscReal));
  memcpy(tr + ST_STATEV, call->statev, sizeof(double) * (size_t)p->pts.mat.nstatv);
  memcpy(&p->pts.ddsdde[k * 36], call->ddsdde, sizeof(double) * (size_t)(p->pts.mat.ntens * p->pts.mat.ntens));
}

/* The update of point (c, q) at total strain eps: gather its state, the material-point adapter with the cell's phi
 * and the evaluation's step control, scatter to the trial state; the first call that asks for a shorter step is
 * kept for a replay scene. Returns the stress at eps and the call's PNEWDT. */
static void point_update(FeProblem *p, PetscInt c, PetscInt q, const PetscReal eps[6], PetscReal stress[6], PetscReal *pnewdt) {
  const PetscReal   phi = p->pts.phi[c - p->space.cStart];
  UmatCall          call;
  MaterialPointDiag diag;
  call_from_state(p, c, q, eps, &call);
  material_point_update(&p->pts.mat, phi, p->umat, &call, &diag);
  p->diag.umat_calls++;
  if (diag.rejected) {
    const PetscReal *st = &p->pts.state[SV(p, c, q) * p->pts.nsv];
    material_failed_call_keep(&p->diag.failed, &p->pts.mat, phi, p->umat, st + ST_STRESS, st + ST_STATEV, &call);
  }
  call_to_trial(p, c, q, eps, &call);
  memcpy(stress, call.stress, sizeof call.stress);
  *pnewdt = diag.pnewdt;
}

/* The element loop: residual (F = F_int - F_ext) and, with the same UMAT calls, the tangent cache. */
PetscErrorCode fe_residual(SNES snes, Vec U, Vec F, void *ctx) {
  FeProblem   *p  = (FeProblem *)ctx;
  DM           dm = p->space.dm;
  Vec          Uloc, Floc;
  PetscScalar  ue[90], re[90], *ua, *fa;
  PetscReal    min_pnewdt = PETSC_MAX_REAL, reaction[3] = {0, 0, 0};
  clock_t      t0         = clock();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(driver_event(EV_RESIDUAL), 0, 0, 0, 0));
  PetscCheck(p->space.nq <= 64 && p->space.nb <= 90, PETSC_COMM_SELF, PETSC_ERR_SUP, "element too large");
  PetscCall(DMGetLocalVector(dm, &Uloc));
  PetscCall(DMGetLocalVector(dm, &Floc));
  PetscCall(DMGlobalToLocal(dm, U, INSERT_VALUES, Uloc));
  PetscCall(VecZeroEntries(Floc));
  p->diag.failed.have = false;
  PetscCall(VecGetArray(Uloc, &ua));
  PetscCall(VecGetArray(Floc, &fa));
  PetscCall(fe_constraint_to_global(&p->space.con, ua)); /* the fixed components (zero values); nodal frames to global axes */
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    const PetscInt *dofs = &p->space.cell_dofs[(c - p->space.cStart) * p->space.nb];
    for (PetscInt b = 0; b < p->space.nb; b++) ue[b] = ua[dofs[b]], re[b] = 0;
    for (PetscInt q = 0; q < p->space.nq; q++) {
      const KernelPoint kp = kernel_point(p, SV(p, c, q));
      PetscReal         eps[6], sig[6], pnewdt;
      kernel_strain(&kp, ue, eps);
      point_update(p, c, q, eps, sig, &pnewdt);
      min_pnewdt = PetscMin(min_pnewdt, pnewdt);
      kernel_force(&kp, sig, p->space.wdetJ[SV(p, c, q)], re);
    }
    for (PetscInt b = 0; b < p->space.nb; b++) fa[dofs[b]] += re[b];
  }
  PetscCall(fe_constraint_to_frame(&p->space.con, fa, reaction)); /* internal force on the fixed components; into the frames */
  PetscCall(VecRestoreArray(Uloc, &ua));
  PetscCall(VecRestoreArray(Floc, &fa));
  PetscCall(VecZeroEntries(F));
  PetscCall(DMLocalToGlobal(dm, Floc, ADD_VALUES, F));
  PetscCall(VecAXPY(F, -1.0, p->loads.fext));
  PetscCall(DMRestoreLocalVector(dm, &Uloc));
  PetscCall(DMRestoreLocalVector(dm, &Floc));
  PetscCall(MPIU_Allreduce(&min_pnewdt, &p->diag.min_pnewdt, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)dm)));
  for (PetscInt d = 0; d < 3; d++) p->diag.reaction_local[d] = reaction[d];
  p->pts.ddsdde_valid = 1;
  if (!p->pts.ddsdde_u) PetscCall(VecDuplicate(U, &p->pts.ddsdde_u));
  PetscCall(VecCopy(U, p->pts.ddsdde_u));
  p->diag.assembly_seconds += (double)(clock() - t0) / CLOCKS_PER_SEC;
  PetscCall(PetscLogEventEnd(driver_event(EV_RESIDUAL), 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_evaluated_at(FeProblem *p, Vec U, PetscBool *same) {
  PetscFunctionBeginUser;
  *same = PETSC_FALSE;
  if (p->pts.ddsdde_valid) PetscCall(VecEqual(U, p->pts.ddsdde_u, same));
  PetscFunctionReturn(0);
}

/* The cached tangents must belong to U: evaluate the residual there first if they do not. */
static PetscErrorCode tangents_at(FeProblem *p, Vec U) {
  PetscBool same;
  PetscFunctionBeginUser;
  PetscCall(fe_problem_evaluated_at(p, U, &same));
  if (!same) {
    Vec F;
    p->diag.tangent_recomputes++;
    PetscCall(VecDuplicate(U, &F));
    PetscCall(fe_residual(NULL, U, F, p));
    PetscCall(VecDestroy(&F));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_jacobian(SNES snes, Vec U, Mat Jac, Mat P, void *ctx) {
  FeProblem   *p  = (FeProblem *)ctx;
  PetscScalar *Ke = NULL;
  clock_t      t0 = clock();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(driver_event(EV_JACOBIAN), 0, 0, 0, 0));
  PetscCall(tangents_at(p, U));
  const PetscBool coo = p->coo_mat == P; /* the values go to the COO array, all set at once at the end */
  if (!coo) PetscCall(MatZeroEntries(P));
  if (!coo) PetscCall(PetscMalloc1(p->space.nb * p->space.nb, &Ke));
  const PetscInt n = p->pts.mat.ntens, nb = p->space.nb;
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    PetscScalar *K = coo ? &p->coo_v[(c - p->space.cStart) * nb * nb] : Ke;
    PetscCall(PetscArrayzero(K, nb * nb));
    for (PetscInt q = 0; q < p->space.nq; q++) {
      const KernelPoint kp = kernel_point(p, SV(p, c, q));
      kernel_tangent(&kp, n, &p->pts.ddsdde[SV(p, c, q) * 36], p->space.wdetJ[SV(p, c, q)], K);
    }
    PetscCall(fe_constraint_rotate_cell(&p->space.con, &p->space.cell_dofs[(c - p->space.cStart) * nb], nb, K)); /* nodal frames */
    /* constrained dofs have negative rows: MatSetValues skips them */
    const PetscInt *rows = &p->space.cell_rows[(c - p->space.cStart) * nb];
    if (!coo) PetscCall(MatSetValues(P, nb, rows, nb, rows, Ke, ADD_VALUES));
  }
  PetscCall(PetscFree(Ke));
  if (coo) PetscCall(MatSetValuesCOO(P, p->coo_v, INSERT_VALUES));
  else {
    PetscCall(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY));
  }
  if (Jac != P) {
    PetscCall(MatAssemblyBegin(Jac, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(Jac, MAT_FINAL_ASSEMBLY));
  }
  p->diag.assembly_seconds += (double)(clock() - t0) / CLOCKS_PER_SEC;
  PetscCall(PetscLogEventEnd(driver_event(EV_JACOBIAN), 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* COO assembly of the Jacobian into J (MatSetPreallocationCOO/MatSetValuesCOO): every cell's element
   matrix in one array, rows and columns from cell_rows (constrained ones negative, which PETSc ignores), set
   at once; fe_jacobian writes there when it assembles J. */
PetscErrorCode fe_jacobian_coo_setup(FeProblem *p, Mat J) {
  const PetscInt nb = p->space.nb, ncell = p->space.cEnd - p->space.cStart;
  PetscCount     n = (PetscCount)ncell * nb * nb, k = 0;
  PetscInt      *ci, *cj;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(n, &ci, n, &cj));
  for (PetscInt c = 0; c < ncell; c++)
    for (PetscInt a = 0; a < nb; a++)
      for (PetscInt b = 0; b < nb; b++, k++) ci[k] = p->space.cell_rows[c * nb + a], cj[k] = p->space.cell_rows[c * nb + b];
  PetscCall(MatSetPreallocationCOO(J, n, ci, cj));
  PetscCall(PetscFree2(ci, cj));
  PetscCall(PetscFree(p->coo_v));
  PetscCall(PetscMalloc1(n, &p->coo_v));
  p->coo_mat = J;
  PetscFunctionReturn(0);
}

/* Y = K X with the tangents cached by the last residual, cell by cell as the residual goes: the fixed components
 * zero and the framed nodes in global axes on the way in, the forces into the frames on the way out. The same
 * operator as fe_jacobian's matrix (to roundoff). */
static PetscErrorCode tangent_apply(Mat A, Vec X, Vec Y) {
  FeProblem   *p;
  DM           dm;
  Vec          Xloc, Yloc;
  PetscScalar  xe[90], ye[90], *xa, *ya;
  clock_t      t0 = clock();
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &p));
  PetscCall(PetscLogEventBegin(driver_event(EV_TANGENT_APPLY), 0, 0, 0, 0));
  dm = p->space.dm;
  PetscCall(DMGetLocalVector(dm, &Xloc));
  PetscCall(DMGetLocalVector(dm, &Yloc));
  PetscCall(DMGlobalToLocal(dm, X, INSERT_VALUES, Xloc));
  PetscCall(VecZeroEntries(Yloc));
  PetscCall(VecGetArray(Xloc, &xa));
  PetscCall(VecGetArray(Yloc, &ya));
  PetscCall(fe_constraint_to_global(&p->space.con, xa));
  const PetscInt n = p->pts.mat.ntens;
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    const PetscInt *dofs = &p->space.cell_dofs[(c - p->space.cStart) * p->space.nb];
    for (PetscInt b = 0; b < p->space.nb; b++) xe[b] = xa[dofs[b]], ye[b] = 0;
    for (PetscInt q = 0; q < p->space.nq; q++) {
      const PetscInt    k  = SV(p, c, q);
      const KernelPoint kp = kernel_point(p, k);
      PetscReal         eps[6], sig[6];
      kernel_strain(&kp, xe, eps);
      kernel_stress(n, &p->pts.ddsdde[k * 36], eps, sig);
      kernel_force(&kp, sig, p->space.wdetJ[k], ye);
    }
    for (PetscInt b = 0; b < p->space.nb; b++) ya[dofs[b]] += ye[b];
  }
  PetscCall(fe_constraint_to_frame(&p->space.con, ya, NULL));
  PetscCall(VecRestoreArray(Xloc, &xa));
  PetscCall(VecRestoreArray(Yloc, &ya));
  PetscCall(VecZeroEntries(Y));
  PetscCall(DMLocalToGlobal(dm, Yloc, ADD_VALUES, Y));
  PetscCall(DMRestoreLocalVector(dm, &Xloc));
  PetscCall(DMRestoreLocalVector(dm, &Yloc));
  p->diag.assembly_seconds += (double)(clock() - t0) / CLOCKS_PER_SEC;
  PetscCall(PetscLogEventEnd(driver_event(EV_TANGENT_APPLY), 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_tangent_operator(FeProblem *p, Mat like, Mat *A) {
  PetscInt m, n, M, N;
  PetscFunctionBeginUser;
  PetscCall(MatGetLocalSize(like, &m, &n));
  PetscCall(MatGetSize(like, &M, &N));
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)like), m, n, M, N, p, A));
  PetscCall(MatShellSetOperation(*A, MATOP_MULT, (void (*)(void))tangent_apply));
  PetscFunctionReturn(0);
}
