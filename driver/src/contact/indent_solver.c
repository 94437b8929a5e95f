#include "indent_solver.h"
#include "../io/log_events.h"
#include "../io/options.h"

#include <string.h>
#include <time.h>

/* The factorisation (direct) or multigrid hierarchy (fieldsplit) is kept across solves: refactor_its > 0. */
static inline PetscBool kept(const IndentSolver *s) { return s->refactor_its > 0 ? PETSC_TRUE : PETSC_FALSE; }

static double wall(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The nest of eq. 15 with the displacement block K: [K 0 Bt; 0 Kr Ct; B C D] (Bt carries every multiplier: the
 * exact derivative of R_u). */
static PetscErrorCode nest_of(Contact *ct, Mat K, Mat *A) {
  Mat blocks[9] = {K, NULL, ct->Bt, NULL, ct->Kr, ct->Ct, ct->B, ct->C, ct->D};
  PetscFunctionBeginUser;
  PetscCall(MatCreateNest(PetscObjectComm((PetscObject)K), 3, NULL, 3, NULL, blocks, A));
  PetscFunctionReturn(0);
}

/* The direct path's package (-indent_pc_factor_mat_solver_type overrides it). A 2D model on one rank: UMFPACK with
 * METIS' ordering, whose triangular solves, the main cost of the 2D contact solve, take about 0.7 of MUMPS' time there
 * (MUMPS as Debian builds it orders by PORD only; docs/contact.md, "The linear solver"). 3D or several ranks: MUMPS
 * (in 3D its solves are the faster; UMFPACK is serial). Both pivot, as the zero diagonal of the multiplier rows and of
 * the indenter row under force control asks; MUMPS' ICNTL(14) leaves room for those delayed pivots. */
static PetscErrorCode direct_package(MPI_Comm comm, PetscInt dim, PC pc) {
  PetscMPIInt size;
  PetscBool   umfpack = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (dim == 2 && size == 1) {
    PetscBool built; /* PETSc configured with UMFPACK; umfpack: and it factors this matrix type */
    PetscCall(MatSolverTypeGet(MATSOLVERUMFPACK, MATSEQAIJ, MAT_FACTOR_LU, &built, &umfpack, NULL));
  }
  PetscCall(PCFactorSetMatSolverType(pc, umfpack ? MATSOLVERUMFPACK : MATSOLVERMUMPS));
  PetscCall(options_default("-indent_mat_umfpack_ordering", "METIS"));
  PetscCall(options_default("-indent_mat_mumps_icntl_14", "100"));
  PetscFunctionReturn(0);
}

PetscErrorCode indent_solver_create(Contact *ct, Mat K, Mat Kmf, PetscErrorCode (*assemble)(void *), PetscErrorCode (*coarse)(void *, Mat *, MatNullSpace *),
                                   void *actx, const IndentOptions *o, IndentSolver *s) {
  MPI_Comm  comm = PetscObjectComm((PetscObject)K);
  PetscInt  m, M, nr, nu;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(s, sizeof *s));
  s->K = K, s->assemble = assemble, s->actx = actx;
  PetscCall(MatGetSize(K, &nu, NULL));
  /* auto: the field split in 3D above fieldsplit_above displacement unknowns, where the direct path's memory outgrows
     its speed (docs/contact.md, "The field split"); in 2D the direct path wins at every size measured */
  s->fieldsplit = o->solver == 1 || (o->solver == 2 && ct->dim == 3 && nu > o->fieldsplit_above);
  s->refactor_its = o->refactor_its, s->rtol_tight = o->rtol_tight, s->refactor = PETSC_TRUE;
  s->check = o->check_solve;
  /* the operator: with a kept factorisation or preconditioner the matrix-free tangent (K is assembled only to be
     factored or to set the multigrid up), otherwise K itself */
  PetscCall(nest_of(ct, kept(s) ? Kmf : K, &s->A));
  if (kept(s)) PetscCall(nest_of(ct, K, &s->Apc));
  else {
    PetscCall(PetscObjectReference((PetscObject)s->A));
    s->Apc = s->A;
  }
  {
    IS rows[3];
    PetscCall(MatNestGetISs(s->A, rows, NULL));
    for (int k = 0; k < 3; k++) {
      PetscCall(PetscObjectReference((PetscObject)rows[k]));
      s->is[k] = rows[k];
    }
    PetscCall(ISConcatenate(comm, 2, &s->is[1], &s->isrl));
  }
  PetscCall(MatGetLocalSize(s->A, &m, NULL));
  PetscCall(MatGetSize(s->A, &M, NULL));
  PetscCall(VecCreateMPI(comm, m, M, &s->X));
  PetscCall(VecDuplicate(s->X, &s->F));
  PetscCall(KSPCreate(comm, &s->ksp));
  PetscCall(KSPSetOptionsPrefix(s->ksp, "indent_"));
  PC pc;
  PetscCall(KSPGetPC(s->ksp, &pc));
  if (!s->fieldsplit) {
    if (kept(s)) { /* GMRES on the nest, right-preconditioned by the kept factorisation (flexible GMRES: it keeps the
                      preconditioned directions, so the solution costs no further triangular solve) */
      PetscCall(KSPSetType(s->ksp, KSPFGMRES));
      PetscCall(KSPSetTolerances(s->ksp, 1e-2, 1e-300, PETSC_DEFAULT, 30));
      PetscCall(KSPGMRESSetRestart(s->ksp, 30));
    } else PetscCall(KSPSetType(s->ksp, KSPPREONLY));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(direct_package(comm, ct->dim, pc));
  } else {
    PetscCall(ISGetLocalSize(s->is[1], &nr));
    PetscCall(KSPSetType(s->ksp, KSPFGMRES));
    PetscCall(KSPSetTolerances(s->ksp, 1e-10, 1e-300, PETSC_DEFAULT, 500));
    PetscCall(KSPGMRESSetRestart(s->ksp, 100));
    PetscCall(PCSetType(pc, PCFIELDSPLIT));
    PetscCall(PCFieldSplitSetIS(pc, "u", s->is[0]));
    PetscCall(PCFieldSplitSetIS(pc, "contact", s->isrl));
    PetscCall(PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR));
    /* the lower factorisation: one multigrid cycle per outer iteration where the full one takes two (GAMG on the P2
       block, 8 steps of the sector at 24 k unknowns: 660 outer iterations against 647, 15.1 s CPU against 22.2,
       measured by hand) */
    PetscCall(PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_LOWER));
    /* the Schur complement's preconditioner: A11 - A10 diag(K)^-1 A01, an arrow matrix (the indenter
       row and column, a diagonal), assembled in indent_solver_solve */
    PetscInt *dnz, *onz, nl = nr + ct->n;
    PetscCall(PetscCalloc2(PetscMax(nl, 1), &dnz, PetscMax(nl, 1), &onz));
    for (PetscInt i = 0; i < nl; i++) dnz[i] = 2, onz[i] = 1;
    if (nr) dnz[0] = 1 + ct->n, onz[0] = ct->N - ct->n;
    PetscCall(MatCreateAIJ(comm, nl, nl, ct->N + 1, ct->N + 1, 0, dnz, 0, onz, &s->Sp));
    PetscCall(PetscFree2(dnz, onz));
    PetscCall(PCFieldSplitSetSchurPre(pc, PC_FIELDSPLIT_SCHUR_PRE_USER, s->Sp));
    /* inner solves preonly, the outer flexible GMRES the only iteration: nested Krylov solves to 1e-12 cost 2.4 to
       3.4 times as much CPU (docs/contact.md, "The field split") */
    PetscCall(options_default("-indent_fieldsplit_u_ksp_type", "preonly"));
    if (o->pmg && coarse) PetscCall(coarse(actx, &s->P, &s->rbmc)); /* the u block's PC: pmg_configure, at the first solve */
    else PetscCall(options_default("-indent_fieldsplit_u_pc_type", "gamg"));
    PetscCall(options_default("-indent_fieldsplit_contact_ksp_type", "preonly"));
    PetscCall(options_default("-indent_fieldsplit_contact_pc_type", "lu"));
    PetscCall(options_default("-indent_fieldsplit_contact_pc_factor_mat_solver_type", "mumps"));
    /* MUMPS' workspace estimate does not foresee the delayed pivots of the zero diagonal: relax it */
    PetscCall(options_default("-indent_fieldsplit_contact_mat_mumps_icntl_14", "200"));
  }
  PetscCall(KSPSetFromOptions(s->ksp));
  PetscCall(KSPGetTolerances(s->ksp, &s->rtol, NULL, NULL, NULL));
  PetscFunctionReturn(0);
}

/* The path and, on the direct one, its package, for the log: "direct (umfpack)", "fieldsplit". */
PetscErrorCode indent_solver_name(IndentSolver *s, char *name, size_t len) {
  PC            pc;
  MatSolverType type = NULL;
  PetscFunctionBeginUser;
  if (s->fieldsplit) {
    PetscCall(PetscSNPrintf(name, len, "fieldsplit"));
    PetscFunctionReturn(0);
  }
  PetscCall(KSPGetPC(s->ksp, &pc));
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  PetscCall(PetscSNPrintf(name, len, "direct (%s)", type ? type : "?"));
  PetscFunctionReturn(0);
}

PetscErrorCode indent_solver_destroy(IndentSolver *s) {
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&s->ksp));
  PetscCall(MatDestroy(&s->A));
  PetscCall(MatDestroy(&s->Apc));
  PetscCall(MatDestroy(&s->Aaij));
  PetscCall(MatDestroy(&s->Sp));
  PetscCall(MatDestroy(&s->P));
  PetscCall(MatDestroy(&s->Kc));
  PetscCall(MatNullSpaceDestroy(&s->rbmc));
  for (int k = 0; k < 3; k++) PetscCall(ISDestroy(&s->is[k]));
  PetscCall(ISDestroy(&s->isrl));
  PetscCall(VecDestroy(&s->X));
  PetscCall(VecDestroy(&s->F));
  PetscFunctionReturn(0);
}

/* The Schur preconditioning matrix in the numbering of the (u_r, lambda) split: u_r first (global 0),
 * then the multipliers (global 1 + their index). The multiplier rows are the scaled ones of contact.h:
 * c B and c C on the active set, w_i on the diagonal elsewhere. */
static PetscErrorCode assemble_schur_pre(IndentSolver *s, Contact *ct) {
  Vec                diag;
  const PetscScalar *da;
  PetscInt           rstart;
  PetscMPIInt        rank;
  const PetscInt     dim = ct->dim;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)s->Sp), &rank));
  PetscCall(MatCreateVecs(s->K, NULL, &diag));
  PetscCall(MatGetDiagonal(s->K, diag));
  PetscCall(VecGetOwnershipRange(diag, &rstart, NULL));
  PetscCall(VecGetArrayRead(diag, &da));
  if (!rank) PetscCall(MatSetValue(s->Sp, 0, 0, ct->kr, INSERT_VALUES));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscInt  gi = 1 + ct->rstart + i, zero = 0;
    PetscReal c = ct->w[i] * contact_ndotd(ct, i), sii = ct->w[i], nf[3];
    if (ct->active[i]) {
      sii = 0;
      contact_frame_normal(ct, i, nf); /* the node's rows are in its nodal frame (mirror planes) */
      for (PetscInt d = 0; d < dim; d++) {
        PetscInt r = ct->row[i * dim + d];
        if (r >= 0) sii -= ct->c * PetscSqr(ct->w[i] * nf[d]) / PetscRealPart(da[r - rstart]);
      }
    }
    PetscCall(MatSetValue(s->Sp, zero, gi, ct->depth_control ? 0.0 : c, INSERT_VALUES));
    PetscCall(MatSetValue(s->Sp, gi, zero, ct->active[i] ? ct->c * c : 0.0, INSERT_VALUES));
    PetscCall(MatSetValue(s->Sp, gi, gi, sii, INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(diag, &da));
  PetscCall(VecDestroy(&diag));
  PetscCall(MatAssemblyBegin(s->Sp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(s->Sp, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

/* Copy between a part of the flat vector and its own vector (to_flat: part -> flat). */
static PetscErrorCode part(Vec flat, IS is, Vec v, PetscBool to_flat) {
  Vec sub;
  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(flat, is, &sub));
  if (to_flat) PetscCall(VecCopy(v, sub));
  else PetscCall(VecCopy(sub, v));
  PetscCall(VecRestoreSubVector(flat, is, &sub));
  PetscFunctionReturn(0);
}

/* -indent_check_solve: the kept solve's solution X against a fresh LU solve of the same system (K assembled at the
 * iterate, the nest converted, MUMPS), printed as |X - X_lu| / |X_lu| with the multipliers as lengths (lambda / c),
 * with the solve's Krylov iterations and whether it factored afresh (for tests of the refactorisation rule). */
static PetscErrorCode check_against_fresh_lu(IndentSolver *s, PetscReal c, PetscInt its, PetscBool fresh) {
  Mat       A;
  KSP       ksp;
  PC        pc;
  Vec       Y;
  PetscReal d, n;
  PetscFunctionBeginUser;
  PetscCall(s->assemble(s->actx));
  PetscCall(MatAssemblyBegin(s->Apc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(s->Apc, MAT_FINAL_ASSEMBLY));
  PetscCall(MatConvert(s->Apc, MATAIJ, MAT_INITIAL_MATRIX, &A));
  PetscCall(KSPCreate(PetscObjectComm((PetscObject)A), &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(VecDuplicate(s->X, &Y));
  PetscCall(KSPSolve(ksp, s->F, Y));
  /* in lengths: the multipliers (pressures) over the complementarity constant c (pressure per length) */
  Vec X, lam;
  PetscCall(VecDuplicate(s->X, &X));
  PetscCall(VecCopy(s->X, X));
  Vec *both[] = {&X, &Y};
  for (int k = 0; k < 2; k++) {
    PetscCall(VecGetSubVector(*both[k], s->is[2], &lam));
    PetscCall(VecScale(lam, 1 / c));
    PetscCall(VecRestoreSubVector(*both[k], s->is[2], &lam));
  }
  PetscCall(VecNorm(Y, NORM_2, &n));
  PetscCall(VecAXPY(X, -1.0, Y));
  PetscCall(VecNorm(X, NORM_2, &d));
  PetscCall(VecDestroy(&X));
  s->check_max = PetscMax(s->check_max, d / PetscMax(n, 1e-300));
  PetscCall(PetscPrintf(PetscObjectComm((PetscObject)A), "    solve check: kept factorisation against a fresh LU: |dx - dx_lu| / |dx_lu| = %.3e (lambda / c: all lengths); "
                        "%d Krylov iterations, %s factorisation\n", (double)(d / PetscMax(n, 1e-300)), (int)its, fresh ? "fresh" : "kept"));
  PetscCall(VecDestroy(&Y));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(MatDestroy(&A));
  PetscFunctionReturn(0);
}

/* One Krylov solve of the flat system, its iterations counted. */
static PetscErrorCode run_ksp(IndentSolver *s, KSPConvergedReason *reason, PetscInt *its) {
  PetscFunctionBeginUser;
  PetscCall(KSPSolve(s->ksp, s->F, s->X));
  PetscCall(KSPGetConvergedReason(s->ksp, reason));
  PetscCall(KSPGetIterationNumber(s->ksp, its));
  s->linear_its += *its;
  PetscFunctionReturn(0);
}

/* The kept preconditioner's rule: a solve's iterations beyond a fresh one's are summed, and the preconditioner is
 * rebuilt at the next solve once they exceed refactor_its (its cost counted in Krylov iterations). */
static void count_extra(IndentSolver *s, PetscInt extra) {
  s->extra_its += PetscMax(extra, 0);
  if (s->extra_its > s->refactor_its) s->refactor = PETSC_TRUE; /* never kept: fresh at every solve anyway */
}

/* The direct path: GMRES on the current nest with the kept factorisation (indent_solver.h), refactored first
 * when due, and once more at once when the solve fails on a kept one; refactor_its 0: LU alone, every time.
 * Due: when the Krylov iterations beyond the first, summed over the solves since the factorisation, exceed
 * refactor_its, the cost of a factorisation counted in Krylov iterations (a fresh one solves in one). */
static PetscErrorCode solve_kept(IndentSolver *s, PetscReal c, KSPConvergedReason *reason) {
  PetscInt its = 0;
  PetscFunctionBeginUser;
  PetscBool fresh = PETSC_FALSE;
  for (int attempt = 0; attempt < 2; attempt++) {
    fresh = s->refactor || !s->Aaij || !kept(s);
    if (fresh) { /* K at this iterate, and the nest's values into the same AIJ matrix: the pattern is fixed, so MUMPS
                    keeps its analysis */
      PetscCall(s->assemble(s->actx));
      PetscCall(MatAssemblyBegin(s->Apc, MAT_FINAL_ASSEMBLY));
      PetscCall(MatAssemblyEnd(s->Apc, MAT_FINAL_ASSEMBLY));
      PetscCall(MatConvert(s->Apc, MATAIJ, s->Aaij ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, &s->Aaij));
      s->setups++, s->refactor = PETSC_FALSE, s->extra_its = 0;
    }
    PetscCall(KSPSetOperators(s->ksp, kept(s) ? s->A : s->Aaij, s->Aaij));
    PetscCall(KSPSetReusePreconditioner(s->ksp, fresh ? PETSC_FALSE : PETSC_TRUE));
    PetscCall(run_ksp(s, reason, &its));
    if (*reason > 0 || fresh) break;
    s->refactor = PETSC_TRUE; /* the kept factorisation no longer serves: a fresh one, now */
  }
  if (s->check && kept(s)) PetscCall(check_against_fresh_lu(s, c, its, fresh));
  count_extra(s, its - 1);
  PetscFunctionReturn(0);
}

/* The displacement block's p-multigrid (fe_pmg.h), set on its KSP once the field split has made it: two levels,
 * Chebyshev-Jacobi (2 iterations, eigenvalues estimated) on the P2 block and one GAMG cycle on the coarse P^T K P
 * with the coarse rigid-body modes; its options take the prefix indent_fieldsplit_u_ (-indent_fieldsplit_u_mg_levels_*,
 * -indent_fieldsplit_u_mg_coarse_*). */
static PetscErrorCode pmg_configure(IndentSolver *s) {
  PC       pc, pcu, spc;
  KSP     *sub, smooth, coarse;
  PetscInt nsub;
  PetscFunctionBeginUser;
  PetscCall(KSPSetUp(s->ksp)); /* the field split's sub-KSPs exist from here on */
  PetscCall(KSPGetPC(s->ksp, &pc));
  PetscCall(PCFieldSplitGetSubKSP(pc, &nsub, &sub));
  PetscCall(KSPGetPC(sub[0], &pcu));
  PetscCall(PetscFree(sub));
  PetscCall(PCSetType(pcu, PCMG));
  PetscCall(PCMGSetLevels(pcu, 2, NULL));
  PetscCall(PCMGSetGalerkin(pcu, PC_MG_GALERKIN_NONE)); /* P^T K P made here, to carry the coarse near null space */
  PetscCall(PCMGSetInterpolation(pcu, 1, s->P));
  PetscCall(PCMGGetSmoother(pcu, 1, &smooth));
  PetscCall(KSPSetType(smooth, KSPCHEBYSHEV));
  PetscCall(KSPChebyshevEstEigSet(smooth, 0, 0.1, 0, 1.1));
  PetscCall(KSPSetTolerances(smooth, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 2));
  PetscCall(KSPGetPC(smooth, &spc));
  PetscCall(PCSetType(spc, PCJACOBI));
  PetscCall(PCMGGetCoarseSolve(pcu, &coarse));
  PetscCall(KSPSetType(coarse, KSPPREONLY));
  PetscCall(KSPGetPC(coarse, &spc));
  PetscCall(PCSetType(spc, PCGAMG));
  PetscCall(KSPSetOperators(coarse, s->Kc, s->Kc));
  PetscCall(PCSetFromOptions(pcu));
  PetscCall(KSPSetFromOptions(smooth));
  PetscCall(KSPSetFromOptions(coarse));
  PetscFunctionReturn(0);
}

/* The coarse matrix P^T K P of the p-multigrid for the K just assembled, with its near null space. */
static PetscErrorCode pmg_coarse_matrix(IndentSolver *s) {
  PetscFunctionBeginUser;
  PetscCall(MatPtAP(s->K, s->P, s->Kc ? MAT_REUSE_MATRIX : MAT_INITIAL_MATRIX, PETSC_DEFAULT, &s->Kc));
  PetscCall(MatSetNearNullSpace(s->Kc, s->rbmc));
  PetscFunctionReturn(0);
}

/* The field split with a kept multigrid hierarchy (indent_solver.h): K is assembled (and on P2 its coarse P^T K P
 * formed), and the multigrid set up afresh, only when due; otherwise K keeps its state and PCSetUp leaves the
 * displacement block's multigrid as it is, while the contact block's
 * matrices (the active set's rows) and its Schur approximation are current at every solve. Due: at the first solve,
 * after a refresh, when a solve fails on a kept one (then at once), and when the Krylov iterations beyond those of
 * the first solve on the set-up (of the same tolerance), summed over the solves since, exceed refactor_its.
 * refactor_its 0: set up at every Newton iteration. */
static PetscErrorCode solve_split(IndentSolver *s, Contact *ct, PetscBool tight, KSPConvergedReason *reason) {
  PetscInt its = 0, t = tight ? 1 : 0;
  PetscFunctionBeginUser;
  for (int attempt = 0; attempt < 2; attempt++) {
    PetscBool fresh = s->refactor || !kept(s); /* refactor: set at the start, after a refresh or a failed solve */
    if (fresh) {
      PetscCall(s->assemble(s->actx));
      if (s->P) PetscCall(pmg_coarse_matrix(s));
      s->setups++, s->refactor = PETSC_FALSE, s->extra_its = 0, s->base_its[0] = s->base_its[1] = -1;
    }
    PetscCall(assemble_schur_pre(s, ct));
    PetscCall(MatAssemblyBegin(s->Apc, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(s->Apc, MAT_FINAL_ASSEMBLY));
    PetscCall(KSPSetOperators(s->ksp, s->A, s->Apc));
    if (s->P && s->setups == 1 && fresh) PetscCall(pmg_configure(s));
    if (s->setups > 1 || !fresh) { /* the nest's assembly touches K's state: keep the multigrid by the PC's reuse flag */
      PC       pc;
      KSP     *sub;
      PetscInt nsub;
      PetscCall(KSPGetPC(s->ksp, &pc));
      PetscCall(PCFieldSplitGetSubKSP(pc, &nsub, &sub));
      PetscCall(KSPSetReusePreconditioner(sub[0], fresh ? PETSC_FALSE : PETSC_TRUE));
      PetscCall(PetscFree(sub));
    }
    PetscCall(run_ksp(s, reason, &its));
    if (*reason > 0 || fresh) break;
    s->refactor = PETSC_TRUE; /* the kept hierarchy no longer serves: a fresh one, now */
  }
  if (s->base_its[t] < 0) s->base_its[t] = its;
  count_extra(s, its - s->base_its[t]);
  PetscFunctionReturn(0);
}

PetscErrorCode indent_solver_solve(IndentSolver *s, Contact *ct, Vec Ru, PetscReal Rr, Vec Rlam, PetscBool tight, PetscReal eta, Vec du,
                                   PetscReal *dur, Vec dlam, PetscBool *ok) {
  double             t0 = wall();
  KSPConvergedReason reason;
  Vec                sub;
  PetscScalar       *a;
  PetscInt           n;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(driver_event(EV_CONTACT_SOLVE), 0, 0, 0, 0));
  PetscCall(part(s->F, s->is[0], Ru, PETSC_TRUE));
  PetscCall(part(s->F, s->is[2], Rlam, PETSC_TRUE));
  PetscCall(VecGetSubVector(s->F, s->is[1], &sub));
  PetscCall(VecGetLocalSize(sub, &n));
  PetscCall(VecGetArray(sub, &a));
  if (n) a[0] = Rr;
  PetscCall(VecRestoreArray(sub, &a));
  PetscCall(VecRestoreSubVector(s->F, s->is[1], &sub));
  PetscCall(MatAssemblyBegin(s->A, MAT_FINAL_ASSEMBLY)); /* the nest takes note of its changed blocks */
  PetscCall(MatAssemblyEnd(s->A, MAT_FINAL_ASSEMBLY));
  if (eta > 0) tight = PETSC_FALSE; /* a forcing term's solve counts with the loose ones (solve_split's base_its) */
  PetscCall(KSPSetTolerances(s->ksp, eta > 0 ? eta : tight ? PetscMin(s->rtol, s->rtol_tight) : s->rtol, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT));
  if (!s->fieldsplit) PetscCall(solve_kept(s, ct->c, &reason));
  else PetscCall(solve_split(s, ct, tight, &reason));
  *ok = reason > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscCall(VecScale(s->X, -1.0));
  PetscCall(part(s->X, s->is[0], du, PETSC_FALSE));
  PetscCall(part(s->X, s->is[2], dlam, PETSC_FALSE));
  PetscCall(VecGetSubVector(s->X, s->is[1], &sub));
  PetscCall(VecGetLocalSize(sub, &n));
  PetscReal v = 0;
  PetscCall(VecGetArray(sub, &a));
  if (n) v = PetscRealPart(a[0]);
  PetscCall(VecRestoreArray(sub, &a));
  PetscCall(VecRestoreSubVector(s->X, s->is[1], &sub));
  PetscCallMPI(MPI_Bcast(&v, 1, MPIU_REAL, 0, PetscObjectComm((PetscObject)s->X)));
  *dur = v;
  s->seconds += wall() - t0;
  PetscCall(PetscLogEventEnd(driver_event(EV_CONTACT_SOLVE), 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

/* The indenter's entry of a flat vector (on rank 0), set or read. */
static PetscErrorCode indenter_entry(IndentSolver *s, Vec flat, PetscReal *v, PetscBool set) {
  Vec          sub;
  PetscScalar *a;
  PetscInt     n;
  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(flat, s->is[1], &sub));
  PetscCall(VecGetLocalSize(sub, &n));
  PetscCall(VecGetArray(sub, &a));
  if (n && set) a[0] = *v;
  PetscReal got = n ? PetscRealPart(a[0]) : 0;
  PetscCall(VecRestoreArray(sub, &a));
  PetscCall(VecRestoreSubVector(flat, s->is[1], &sub));
  if (!set) {
    PetscCallMPI(MPI_Bcast(&got, 1, MPIU_REAL, 0, PetscObjectComm((PetscObject)flat)));
    *v = got;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode indent_solver_apply(IndentSolver *s, Vec du, PetscReal dur, Vec dlam, Vec ju, PetscReal *jr, Vec jlam) {
  PetscFunctionBeginUser;
  PetscCall(part(s->X, s->is[0], du, PETSC_TRUE));
  PetscCall(part(s->X, s->is[2], dlam, PETSC_TRUE));
  PetscCall(indenter_entry(s, s->X, &dur, PETSC_TRUE));
  PetscCall(MatAssemblyBegin(s->A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(s->A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatMult(s->A, s->X, s->F));
  PetscCall(part(s->F, s->is[0], ju, PETSC_FALSE));
  PetscCall(part(s->F, s->is[2], jlam, PETSC_FALSE));
  PetscCall(indenter_entry(s, s->F, jr, PETSC_FALSE));
  PetscFunctionReturn(0);
}
