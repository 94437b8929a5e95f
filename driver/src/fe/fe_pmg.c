#include "fe_pmg.h"

/* The global rows of point p's own unknowns (one per component; -1 where constrained); false if another rank owns
 * p. The global section numbers a point's unconstrained components consecutively from its offset. */
static PetscErrorCode point_rows(PetscSection ls, PetscSection gs, PetscInt p, PetscInt dim, PetscInt rows[], PetscBool *owned) {
  PetscInt        goff, ndof, cdof, k = 0;
  const PetscInt *cind = NULL;
  PetscFunctionBeginUser;
  PetscCall(PetscSectionGetOffset(gs, p, &goff));
  PetscCall(PetscSectionGetDof(ls, p, &ndof));
  *owned = goff >= 0 && ndof > 0 ? PETSC_TRUE : PETSC_FALSE;
  if (!*owned) PetscFunctionReturn(0);
  PetscCheck(ndof == dim, PETSC_COMM_SELF, PETSC_ERR_SUP, "p-multigrid: point %d has %d unknowns, not one node's %d", (int)p, (int)ndof, (int)dim);
  PetscCall(PetscSectionGetConstraintDof(ls, p, &cdof));
  if (cdof) PetscCall(PetscSectionGetConstraintIndices(ls, p, &cind));
  for (PetscInt d = 0; d < dim; d++) {
    PetscBool fixed = PETSC_FALSE;
    for (PetscInt c = 0; c < cdof; c++) fixed = fixed || cind[c] == d;
    rows[d] = fixed ? -1 : goff + k++;
  }
  PetscFunctionReturn(0);
}

/* The coarse numbering: the owned vertices' unconstrained components, rank by rank; cidx, a local vector of the P2
 * space, holds at each vertex component its coarse index (also at ghost vertices) and -1 elsewhere. */
static PetscErrorCode coarse_numbering(const FeSpace *sp, Vec cidx, PetscInt *nc, PetscInt *Nc) {
  DM           dm = sp->dm;
  PetscSection ls, gs;
  PetscInt     vStart, vEnd, n = 0, start, fstart, rows[3];
  Vec          g;
  PetscScalar *ga;
  PetscBool    owned;
  MPI_Comm     comm = PetscObjectComm((PetscObject)dm);
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscCall(point_rows(ls, gs, v, sp->dim, rows, &owned));
    for (PetscInt d = 0; owned && d < sp->dim; d++) n += rows[d] >= 0;
  }
  PetscCallMPI(MPI_Scan(&n, &start, 1, MPIU_INT, MPI_SUM, comm));
  start -= n, *nc = n;
  PetscCall(MPIU_Allreduce(&n, Nc, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(DMGetGlobalVector(dm, &g));
  PetscCall(VecSet(g, -1.0));
  PetscCall(VecGetOwnershipRange(g, &fstart, NULL));
  PetscCall(VecGetArray(g, &ga));
  for (PetscInt v = vStart, k = start; v < vEnd; v++) {
    PetscCall(point_rows(ls, gs, v, sp->dim, rows, &owned));
    for (PetscInt d = 0; owned && d < sp->dim; d++)
      if (rows[d] >= 0) ga[rows[d] - fstart] = (PetscScalar)k++;
  }
  PetscCall(VecRestoreArray(g, &ga));
  PetscCall(VecSet(cidx, -1.0));
  PetscCall(DMGlobalToLocal(dm, g, INSERT_VALUES, cidx));
  PetscCall(DMRestoreGlobalVector(dm, &g));
  PetscFunctionReturn(0);
}

/* The rows of P: a vertex's unknowns are the coarse ones (the same frame); an edge's midpoint takes the mean of its
 * two vertices' values, u_e = R_e^T (R_a u_a + R_b u_b) / 2. */
static PetscErrorCode prolongation_rows(const FeSpace *sp, const PetscScalar *ca, Mat P) {
  DM             dm = sp->dm;
  PetscSection   ls, gs;
  PetscInt       pStart, pEnd, vStart, vEnd, eStart, eEnd, rows[3];
  const PetscInt dim = sp->dim;
  PetscBool      owned;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 1, &eStart, &eEnd));
  for (PetscInt p = pStart; p < pEnd; p++) {
    PetscInt        loff, ncone = 1, coff[2];
    const PetscInt *cone = &p;
    PetscReal       Re[9], Ra[18]; /* the point's frame; its one or two vertices' */
    PetscCall(point_rows(ls, gs, p, dim, rows, &owned));
    if (!owned) continue;
    PetscCheck((p >= vStart && p < vEnd) || (p >= eStart && p < eEnd), PETSC_COMM_SELF, PETSC_ERR_SUP,
               "p-multigrid: unknowns on point %d, neither a vertex nor an edge (P2 on simplices only)", (int)p);
    PetscCall(PetscSectionGetOffset(ls, p, &loff));
    PetscCall(fe_constraint_node_frame(&sp->con, loff, Re));
    if (p >= eStart) {
      PetscCall(DMPlexGetConeSize(dm, p, &ncone));
      PetscCall(DMPlexGetCone(dm, p, &cone));
      PetscCheck(ncone == 2, PETSC_COMM_SELF, PETSC_ERR_PLIB, "edge %d with %d vertices", (int)p, (int)ncone);
    }
    for (PetscInt a = 0; a < ncone; a++) {
      PetscCall(PetscSectionGetOffset(ls, cone[a], &coff[a]));
      PetscCall(fe_constraint_node_frame(&sp->con, coff[a], &Ra[a * 9]));
    }
    for (PetscInt d = 0; d < dim; d++) {
      if (rows[d] < 0) continue;
      for (PetscInt a = 0; a < ncone; a++) {
        for (PetscInt k = 0; k < dim; k++) {
          const PetscInt col = (PetscInt)PetscRealPart(ca[coff[a] + k]);
          PetscReal      v = 0;
          for (PetscInt i = 0; i < dim; i++) v += Re[i * dim + d] * Ra[a * 9 + i * dim + k];
          if (col >= 0 && PetscAbsReal(v) > 1e-14) PetscCall(MatSetValue(P, rows[d], col, v / ncone, INSERT_VALUES));
        }
      }
    }
  }
  PetscFunctionReturn(0);
}

/* The coarse rigid-body modes at the owned vertices, in their frames, then orthonormalised (modified Gram-Schmidt). */
static PetscErrorCode coarse_modes(const FeSpace *sp, const PetscScalar *ca, Mat P, MatNullSpace *rbm) {
  DM                 dm = sp->dm;
  PetscSection       ls, gs, cs;
  Vec                coords, m[6];
  const PetscScalar *xa;
  PetscScalar       *ma[6];
  PetscInt           vStart, vEnd, cstart, rows[3];
  const PetscInt     dim = sp->dim, nm = sp->kin == KIN_AXISYMMETRIC ? 2 : dim == 3 ? 6 : 3;
  PetscBool          owned;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &xa));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  for (PetscInt j = 0; j < nm; j++) {
    PetscCall(MatCreateVecs(P, &m[j], NULL));
    PetscCall(VecGetArray(m[j], &ma[j]));
  }
  PetscCall(VecGetOwnershipRange(m[0], &cstart, NULL));
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt  loff, xoff;
    PetscReal R[9], x[3] = {0, 0, 0};
    PetscCall(point_rows(ls, gs, v, dim, rows, &owned));
    if (!owned) continue;
    PetscCall(PetscSectionGetOffset(ls, v, &loff));
    PetscCall(PetscSectionGetOffset(cs, v, &xoff));
    PetscCall(fe_constraint_node_frame(&sp->con, loff, R));
    for (PetscInt i = 0; i < dim; i++) x[i] = PetscRealPart(xa[xoff + i]);
    for (PetscInt j = 0; j < nm; j++) {
      PetscReal u[3] = {0, 0, 0}; /* the mode in global axes: translations, then rotations about x, y, z (2D: z) */
      if (j < dim) u[j] = 1;
      else if (dim == 2) u[0] = -x[1], u[1] = x[0];
      else if (j == 3) u[1] = -x[2], u[2] = x[1];
      else if (j == 4) u[0] = x[2], u[2] = -x[0];
      else u[0] = -x[1], u[1] = x[0];
      for (PetscInt k = 0; k < dim; k++) {
        const PetscInt col = (PetscInt)PetscRealPart(ca[loff + k]);
        PetscReal      uf = 0;
        for (PetscInt i = 0; i < dim; i++) uf += R[i * dim + k] * u[i];
        if (col >= 0) ma[j][col - cstart] = uf;
      }
    }
  }
  PetscCall(VecRestoreArrayRead(coords, &xa));
  for (PetscInt j = 0; j < nm; j++) PetscCall(VecRestoreArray(m[j], &ma[j]));
  for (PetscInt j = 0; j < nm; j++) {
    for (PetscInt i = 0; i < j; i++) {
      PetscScalar dot;
      PetscCall(VecDot(m[j], m[i], &dot));
      PetscCall(VecAXPY(m[j], -dot, m[i]));
    }
    PetscCall(VecNormalize(m[j], NULL));
  }
  PetscCall(MatNullSpaceCreate(PetscObjectComm((PetscObject)P), PETSC_FALSE, nm, m, rbm));
  for (PetscInt j = 0; j < nm; j++) PetscCall(VecDestroy(&m[j]));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_p1_prolongation(const FeSpace *sp, Mat *P, MatNullSpace *rbm) {
  DM                 dm = sp->dm;
  Vec                cidx;
  const PetscScalar *ca;
  PetscInt           nc, Nc, n, N;
  PetscFunctionBeginUser;
  PetscCheck(sp->order == 2, PetscObjectComm((PetscObject)dm), PETSC_ERR_SUP, "p-multigrid: the space is P%d, not P2", (int)sp->order);
  PetscCall(DMCreateLocalVector(dm, &cidx));
  PetscCall(coarse_numbering(sp, cidx, &nc, &Nc));
  {
    Vec g;
    PetscCall(DMGetGlobalVector(dm, &g));
    PetscCall(VecGetLocalSize(g, &n));
    PetscCall(VecGetSize(g, &N));
    PetscCall(DMRestoreGlobalVector(dm, &g));
  }
  /* a row has at most two nodes' components: dim (a vertex) or 2 dim (a midpoint) */
  PetscCall(MatCreateAIJ(PetscObjectComm((PetscObject)dm), n, nc, N, Nc, 2 * sp->dim, NULL, 2 * sp->dim, NULL, P));
  PetscCall(VecGetArrayRead(cidx, &ca));
  PetscCall(prolongation_rows(sp, ca, *P));
  PetscCall(MatAssemblyBegin(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(*P, MAT_FINAL_ASSEMBLY));
  PetscCall(coarse_modes(sp, ca, *P, rbm));
  PetscCall(VecRestoreArrayRead(cidx, &ca));
  PetscCall(VecDestroy(&cidx));
  PetscFunctionReturn(0);
}
