#include "contact_mortar.h"

#include <math.h>
#include <petscsf.h>

#define MV 3 /* vertices of a facet, at most */
#define MN 6 /* P2 nodes of a facet, at most */

/* The facets of the potential contact surface on this rank and what their integrals need. */
struct ContactMortar {
  DM         dm;
  PetscInt   nf, nv, nn, nq;  /* facets here; vertices, P2 nodes and Gauss points per facet */
  PetscInt  *mult;            /* nf x nv: global multiplier index of each vertex (< 0: none) */
  PetscInt  *lmult;           /* nf x nv: its place in the local copy of the multipliers (< 0: none) */
  PetscInt  *rows, *dofs;     /* nf x nn x dim: global rows (< 0: fixed) and local-vector indices */
  PetscInt  *ab;              /* nf x nn x 2: the facet vertices of each node (a = b: a vertex) */
  PetscReal *R;               /* nf x nn x dim x dim: the nodal frame of each node (fe_constraint.h), u = R u_rows */
  PetscReal *Xv;              /* nf x nv x dim: reference coordinates of the vertices */
  PetscReal *L, *qw, *dA;     /* nq x nv barycentric coordinates, nq reference weights; nf x nq: weight x measure (x 2 pi r, thickness) */
  PetscReal *nq_, *gq;        /* nf x nq x dim: the normal at the last gaps; nf x nq: the gap */
  PetscReal  ur;              /* the indenter's position at the last gaps (Uloc: the displacement) */
  Vec        gn, wv, act;     /* multiplier layout: (dim + 1) x: int psi g, int psi n; int psi; active flags */
  Vec        lamloc, Uloc;
  VecScatter scat;
};

/* The P2 shape function of node (a, b) at barycentric coordinates L: L_a (2 L_a - 1) at a vertex, 4 L_a L_b on
   an edge (the standard Lagrange basis of the facet). */
static inline PetscReal shape2(const PetscReal L[], const PetscInt ab[]) {
  return ab[0] == ab[1] ? L[ab[0]] * (2 * L[ab[0]] - 1) : 4 * L[ab[0]] * L[ab[1]];
}

/* The displacement of node j of facet k in global axes from a local vector's values: u = R u_rows, the rows'
   components in the node's frame (fe_constraint.h; the identity off the inclined mirror planes), a constrained
   component zero there. */
static inline void node_disp(const struct ContactMortar *m, PetscInt dim, PetscInt k, PetscInt j, const PetscScalar ua[], double u[]) {
  const PetscReal *R = &m->R[(k * m->nn + j) * dim * dim];
  const PetscInt  *o = &m->dofs[(k * m->nn + j) * dim];
  for (PetscInt d = 0; d < dim; d++) {
    u[d] = 0;
    for (PetscInt e = 0; e < dim; e++) u[d] += R[d * dim + e] * PetscRealPart(ua[o[e]]);
  }
}

/* Rows of a facet's block (nn x dim rows, ncol columns, row-major) from global axes into the nodes' frames, R^T v
   per node: the forces on, and the derivatives by, the rows' components (the element loop's T^T, fe_constraint.h). */
static void rows_to_frames(const struct ContactMortar *m, PetscInt dim, PetscInt k, PetscInt ncol, PetscScalar v[]) {
  for (PetscInt j = 0; j < m->nn; j++) {
    const PetscReal *R = &m->R[(k * m->nn + j) * dim * dim];
    for (PetscInt c = 0; c < ncol; c++) {
      PetscScalar t[3] = {0, 0, 0};
      for (PetscInt e = 0; e < dim; e++)
        for (PetscInt d = 0; d < dim; d++) t[e] += R[d * dim + e] * v[(j * dim + d) * ncol + c];
      for (PetscInt e = 0; e < dim; e++) v[(j * dim + e) * ncol + c] = t[e];
    }
  }
}

PetscErrorCode contact_facets(DM dm, DMLabel label, PetscInt *nf, PetscInt **list) {
  PetscInt fStart, fEnd, n = 0;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  for (int pass = 0; pass < 2; pass++) {
    n = 0;
    for (PetscInt f = fStart; f < fEnd; f++) {
      PetscInt val, ns;
      PetscCall(DMLabelGetValue(label, f, &val));
      if (val < 0) continue;
      PetscCall(DMPlexGetSupportSize(dm, f, &ns));
      if (ns != 1) continue;
      if (pass) (*list)[n] = f;
      n++;
    }
    if (!pass) PetscCall(PetscMalloc1(PetscMax(n, 1), list));
  }
  *nf = n;
  PetscFunctionReturn(0);
}

PetscErrorCode contact_facet_rule(PetscInt dim, PetscInt degree, PetscInt *nq, PetscReal **L, PetscReal **w) {
  PetscQuadrature  quad;
  const PetscReal *qx, *qw;
  PetscFunctionBeginUser;
  PetscCall(PetscDTSimplexQuadrature(dim - 1, degree, PETSCDTSIMPLEXQUAD_DEFAULT, &quad));
  PetscCall(PetscQuadratureGetData(quad, NULL, NULL, nq, &qx, &qw));
  PetscCall(PetscMalloc2(*nq * dim, L, *nq, w));
  for (PetscInt q = 0; q < *nq; q++) { /* barycentric coordinates of the reference simplex's points (vertices at -1, 1) */
    PetscReal s = 0;
    for (PetscInt a = 1; a < dim; a++) s += (*L)[q * dim + a] = (qx[q * (dim - 1) + a - 1] + 1) / 2;
    (*L)[q * dim] = 1 - s, (*w)[q] = qw[q];
  }
  PetscCall(PetscQuadratureDestroy(&quad));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_mark(FeProblem *p, DMLabel label, Contact *ct, PetscInt **mark) {
  const FeSpace *sp = fe_problem_space(p);
  DM       dm = sp->dm;
  PetscInt pStart, pEnd, vStart, vEnd, nf, *facets;
  PetscSF  sf;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&ct->mortar));
  ct->mortar->dm = dm;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(PetscCalloc1(pEnd - pStart, mark));
  PetscCall(contact_facets(dm, label, &nf, &facets));
  for (PetscInt k = 0; k < nf; k++) { /* the facets' vertices, marked here ... */
    PetscInt *cl = NULL, ncl;
    PetscCall(DMPlexGetTransitiveClosure(dm, facets[k], PETSC_TRUE, &ncl, &cl));
    for (PetscInt j = 0; j < ncl; j++)
      if (cl[2 * j] >= vStart && cl[2 * j] < vEnd) (*mark)[cl[2 * j] - pStart] = 1;
    PetscCall(DMPlexRestoreTransitiveClosure(dm, facets[k], PETSC_TRUE, &ncl, &cl));
  }
  PetscCall(PetscFree(facets));
  PetscCall(DMGetPointSF(dm, &sf)); /* ... and on their owners */
  PetscCall(PetscSFReduceBegin(sf, MPIU_INT, *mark, *mark, MPI_MAX));
  PetscCall(PetscSFReduceEnd(sf, MPIU_INT, *mark, *mark, MPI_MAX));
  PetscFunctionReturn(0);
}

/* Per facet: its vertices (multiplier indices, coordinates), its P2 nodes (rows, local dofs, the vertex pair of
   each) and the measure at each Gauss point; mpt: the multiplier index of every plex point (< 0: none). */
static PetscErrorCode facet_data(FeProblem *p, struct ContactMortar *m, PetscInt k, PetscInt f, const PetscInt mpt[], const PetscScalar ca[],
                                 PetscSection cs) {
  const FeSpace *sp = fe_problem_space(p);
  DM           dm = sp->dm;
  PetscSection ls, gs;
  PetscInt    *cl = NULL, ncl, *gi = NULL, *li = NULL, ng, nl, nv = 0, nn = 0, vtx[MV];
  const PetscInt dim = sp->dim;
  PetscReal    meas, c[3], nrm[3];
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  PetscCall(DMPlexGetClosureIndices(dm, ls, gs, f, PETSC_TRUE, &ng, &gi, NULL, NULL));
  PetscCall(DMPlexGetClosureIndices(dm, ls, ls, f, PETSC_TRUE, &nl, &li, NULL, NULL));
  PetscCheck(ng == m->nn * dim && nl == ng, PETSC_COMM_SELF, PETSC_ERR_SUP, "contact: a P2 facet with %d dofs, expected %d", (int)ng, (int)(m->nn * dim));
  for (PetscInt j = 0; j < ncl; j++) { /* the vertices first, in closure order */
    PetscInt pt = cl[2 * j], depth;
    PetscCall(DMPlexGetPointDepth(dm, pt, &depth));
    if (depth == 0) vtx[nv++] = pt;
  }
  for (PetscInt a = 0; a < nv; a++) {
    PetscInt off;
    m->mult[k * m->nv + a] = mpt[vtx[a]];
    PetscCall(PetscSectionGetOffset(cs, vtx[a], &off));
    for (PetscInt d = 0; d < dim; d++) m->Xv[(k * m->nv + a) * dim + d] = PetscRealPart(ca[off + d]);
  }
  for (PetscInt j = 0; j < ncl; j++) { /* the nodes, in the order of the closure's dofs */
    PetscInt pt = cl[2 * j], ndof, depth, *ab = &m->ab[(k * m->nn + nn) * 2];
    PetscCall(PetscSectionGetDof(ls, pt, &ndof));
    if (!ndof) continue;
    PetscCheck(ndof == dim, PETSC_COMM_SELF, PETSC_ERR_SUP, "contact: a point with %d dofs on a P2 facet", (int)ndof);
    PetscCall(DMPlexGetPointDepth(dm, pt, &depth));
    if (depth == 0) {
      for (PetscInt a = 0; a < nv; a++)
        if (vtx[a] == pt) ab[0] = ab[1] = a;
    } else { /* an edge: its node between its two vertices */
      const PetscInt *cone;
      PetscCall(DMPlexGetCone(dm, pt, &cone));
      for (PetscInt a = 0; a < nv; a++) {
        if (vtx[a] == cone[0]) ab[0] = a;
        if (vtx[a] == cone[1]) ab[1] = a;
      }
    }
    for (PetscInt d = 0; d < dim; d++) {
      m->rows[(k * m->nn + nn) * dim + d] = gi[nn * dim + d];
      m->dofs[(k * m->nn + nn) * dim + d] = li[nn * dim + d] < 0 ? -(li[nn * dim + d] + 1) : li[nn * dim + d];
    }
    /* vertex or edge node: on an inclined mirror plane its rows are the components in a frame of its own */
    PetscCall(fe_constraint_node_frame(&sp->con, m->dofs[(k * m->nn + nn) * dim], &m->R[(k * m->nn + nn) * dim * dim]));
    nn++;
  }
  PetscCall(DMPlexRestoreClosureIndices(dm, ls, ls, f, PETSC_TRUE, &nl, &li, NULL, NULL));
  PetscCall(DMPlexRestoreClosureIndices(dm, ls, gs, f, PETSC_TRUE, &ng, &gi, NULL, NULL));
  PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  PetscCall(DMPlexComputeCellGeometryFVM(dm, f, &meas, c, nrm));
  for (PetscInt q = 0; q < m->nq; q++) { /* reference simplex of measure 2 (PetscDT); 2 pi r at the point's reference radius */
    PetscReal r = 0;
    for (PetscInt a = 0; a < nv; a++) r += m->L[q * nv + a] * m->Xv[(k * nv + a) * dim];
    m->dA[k * m->nq + q] = m->qw[q] * meas / 2 * fe_space_weight(sp, r);
  }
  PetscFunctionReturn(0);
}

/* The multiplier index of every plex point: owned vertices numbered here, ghosts from their owners. */
static PetscErrorCode multiplier_points(Contact *ct, PetscInt **mpt) {
  DM       dm = ct->mortar->dm;
  PetscInt pStart, pEnd;
  PetscSF  sf;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscMalloc1(pEnd - pStart, mpt));
  for (PetscInt q = 0; q < pEnd - pStart; q++) (*mpt)[q] = -1;
  for (PetscInt i = 0; i < ct->n; i++) (*mpt)[ct->vtx[i] - pStart] = ct->rstart + i;
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFBcastBegin(sf, MPIU_INT, *mpt, *mpt, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_INT, *mpt, *mpt, MPI_REPLACE));
  PetscFunctionReturn(0);
}

/* The local copy of the multipliers of the facets here: a scatter from the global multipliers. */
static PetscErrorCode multiplier_scatter(Contact *ct, MPI_Comm comm) {
  struct ContactMortar *m = ct->mortar;
  PetscInt             *need, nneed = 0;
  IS                    is;
  Vec                   lam;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc1(PetscMax(m->nf * m->nv, 1), &need));
  for (PetscInt k = 0; k < m->nf * m->nv; k++)
    if (m->mult[k] >= 0) need[nneed++] = m->mult[k];
  PetscCall(PetscSortRemoveDupsInt(&nneed, need));
  for (PetscInt k = 0; k < m->nf * m->nv; k++) {
    PetscInt loc = -1;
    if (m->mult[k] >= 0) PetscCall(PetscFindInt(m->mult[k], nneed, need, &loc));
    m->lmult[k] = loc;
  }
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nneed, need, PETSC_OWN_POINTER, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, nneed, &m->lamloc));
  PetscCall(VecCreateMPI(comm, ct->n, ct->N, &lam));
  PetscCall(VecScatterCreate(lam, is, m->lamloc, NULL, &m->scat));
  PetscCall(VecDestroy(&lam));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Bt's nonzero pattern, fixed once through a preallocator: every (node component, facet vertex) pair. */
static PetscErrorCode coupling_pattern(FeProblem *p, Contact *ct) {
  const FeSpace *sp = fe_problem_space(p);
  struct ContactMortar *m = ct->mortar;
  MPI_Comm              comm = PetscObjectComm((PetscObject)sp->dm);
  PetscInt              nu;
  Mat                   pre;
  Vec                   u;
  PetscScalar           zero[MN * 3 * MV] = {0};
  PetscFunctionBeginUser;
  PetscCall(DMGetGlobalVector(sp->dm, &u));
  PetscCall(VecGetLocalSize(u, &nu));
  PetscCall(DMRestoreGlobalVector(sp->dm, &u));
  PetscCall(MatCreate(comm, &pre));
  PetscCall(MatSetType(pre, MATPREALLOCATOR));
  PetscCall(MatSetSizes(pre, nu, ct->n, PETSC_DETERMINE, ct->N));
  PetscCall(MatSetUp(pre));
  for (PetscInt k = 0; k < m->nf; k++)
    PetscCall(MatSetValues(pre, m->nn * sp->dim, &m->rows[k * m->nn * sp->dim], m->nv, &m->mult[k * m->nv], zero, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(pre, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(pre, MAT_FINAL_ASSEMBLY));
  PetscCall(MatCreate(comm, &ct->Bt));
  PetscCall(MatSetType(ct->Bt, MATAIJ));
  PetscCall(MatSetSizes(ct->Bt, nu, ct->n, PETSC_DETERMINE, ct->N));
  PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, ct->Bt));
  PetscCall(MatDestroy(&pre));
  PetscCall(MatTranspose(ct->Bt, MAT_INITIAL_MATRIX, &ct->B));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_setup(FeProblem *p, DMLabel label, Contact *ct, PetscReal *wsum) {
  const FeSpace *sp = fe_problem_space(p);
  struct ContactMortar *m    = ct->mortar;
  MPI_Comm              comm = PetscObjectComm((PetscObject)sp->dm);
  const PetscInt        dim  = sp->dim;
  PetscInt             *facets, *mpt, nqp;
  PetscSection          cs;
  Vec                   coords;
  const PetscScalar    *ca;
  PetscFunctionBeginUser;
  m->nv = dim, m->nn = dim == 2 ? 3 : 6;
  /* Gauss points on the facet: degree 8 (2D) and 6 (3D) integrate psi N (2 pi r) exactly and the smooth gaps
     to well below the discretisation error */
  PetscCall(contact_facet_rule(dim, dim == 2 ? 8 : 6, &nqp, &m->L, &m->qw));
  m->nq = nqp;
  PetscCall(contact_facets(sp->dm, label, &m->nf, &facets));
  PetscInt nf = PetscMax(m->nf, 1);
  PetscCall(PetscMalloc5(nf * m->nv, &m->mult, nf * m->nv, &m->lmult, nf * m->nn * dim, &m->rows, nf * m->nn * dim, &m->dofs, nf * m->nn * 2, &m->ab));
  PetscCall(PetscMalloc4(nf * m->nv * dim, &m->Xv, nf * nqp, &m->dA, nf * nqp * dim, &m->nq_, nf * nqp, &m->gq));
  PetscCall(PetscMalloc1(nf * m->nn * dim * dim, &m->R));
  PetscCall(multiplier_points(ct, &mpt));
  PetscCall(DMGetCoordinateSection(sp->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(sp->dm, &coords));
  PetscCall(VecGetArrayRead(coords, &ca));
  for (PetscInt k = 0; k < m->nf; k++) PetscCall(facet_data(p, m, k, facets[k], mpt, ca, cs));
  PetscCall(VecRestoreArrayRead(coords, &ca));
  PetscCall(PetscFree(mpt));
  PetscCall(PetscFree(facets));
  PetscCall(multiplier_scatter(ct, comm));
  PetscCall(VecCreateMPI(comm, ct->n * (dim + 1), ct->N * (dim + 1), &m->gn));
  PetscCall(VecSetOption(m->gn, VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE)); /* vertices without a multiplier */
  PetscCall(VecCreateMPI(comm, ct->n, ct->N, &m->wv));
  PetscCall(VecDuplicate(m->wv, &m->act));
  PetscCall(DMCreateLocalVector(sp->dm, &m->Uloc));
  /* the weights w_j = int psi_j dA */
  PetscCall(VecZeroEntries(m->wv));
  for (PetscInt k = 0; k < m->nf; k++)
    for (PetscInt q = 0; q < m->nq; q++)
      for (PetscInt a = 0; a < m->nv; a++)
        if (m->mult[k * m->nv + a] >= 0) PetscCall(VecSetValue(m->wv, m->mult[k * m->nv + a], m->L[q * m->nv + a] * m->dA[k * m->nq + q], ADD_VALUES));
  PetscCall(VecAssemblyBegin(m->wv));
  PetscCall(VecAssemblyEnd(m->wv));
  {
    const PetscScalar *wa;
    PetscCall(VecGetArrayRead(m->wv, &wa));
    *wsum = 0;
    for (PetscInt i = 0; i < ct->n; i++) *wsum += ct->w[i] = PetscRealPart(wa[i]);
    PetscCall(VecRestoreArrayRead(m->wv, &wa));
  }
  PetscCall(coupling_pattern(p, ct));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_destroy(Contact *ct) {
  struct ContactMortar *m = ct->mortar;
  PetscFunctionBeginUser;
  if (!m) PetscFunctionReturn(0);
  PetscCall(PetscFree5(m->mult, m->lmult, m->rows, m->dofs, m->ab));
  PetscCall(PetscFree4(m->Xv, m->dA, m->nq_, m->gq));
  PetscCall(PetscFree2(m->L, m->qw));
  PetscCall(PetscFree(m->R));
  PetscCall(VecDestroy(&m->gn));
  PetscCall(VecDestroy(&m->wv));
  PetscCall(VecDestroy(&m->act));
  PetscCall(VecDestroy(&m->lamloc));
  PetscCall(VecDestroy(&m->Uloc));
  PetscCall(VecScatterDestroy(&m->scat));
  PetscCall(PetscFree(ct->mortar));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_gaps(Contact *ct, Vec U, PetscReal ur) {
  struct ContactMortar *m   = ct->mortar;
  const PetscInt        dim = ct->dim, nv = m->nv, nn = m->nn;
  const PetscScalar    *ua, *ga;
  PetscFunctionBeginUser;
  m->ur = ur;
  PetscCall(VecZeroEntries(m->Uloc)); /* fixed components stay zero */
  PetscCall(DMGlobalToLocal(m->dm, U, INSERT_VALUES, m->Uloc));
  PetscCall(VecGetArrayRead(m->Uloc, &ua));
  PetscCall(VecZeroEntries(m->gn));
  for (PetscInt k = 0; k < m->nf; k++) {
    PetscScalar acc[MV * 4] = {0};
    PetscInt    idx[MV * 4];
    for (PetscInt q = 0; q < m->nq; q++) {
      const PetscReal *L = &m->L[q * nv], dA = m->dA[k * m->nq + q];
      double           X[3] = {0, 0, 0}, x[3], nv_[3];
      for (PetscInt a = 0; a < nv; a++)
        for (PetscInt d = 0; d < dim; d++) X[d] += L[a] * m->Xv[(k * nv + a) * dim + d];
      for (PetscInt d = 0; d < dim; d++) x[d] = X[d];
      for (PetscInt j = 0; j < nn; j++) { /* x = X + u_h at the point (P2 interpolation, nodes in global axes) */
        PetscReal N = shape2(L, &m->ab[(k * nn + j) * 2]);
        double    u[3];
        node_disp(m, dim, k, j, ua, u);
        for (PetscInt d = 0; d < dim; d++) x[d] += N * u[d];
      }
      double g = indenter_gap(&ct->shape, X, x, ur, nv_);
      for (PetscInt d = 0; d < dim; d++) m->nq_[(k * m->nq + q) * dim + d] = nv_[d];
      m->gq[k * m->nq + q] = g;
      for (PetscInt a = 0; a < nv; a++) { /* int psi_a g dA, int psi_a n dA */
        acc[a * (dim + 1)] += L[a] * g * dA;
        for (PetscInt d = 0; d < dim; d++) acc[a * (dim + 1) + 1 + d] += L[a] * nv_[d] * dA;
      }
    }
    for (PetscInt a = 0; a < nv; a++)
      for (PetscInt c = 0; c <= dim; c++) idx[a * (dim + 1) + c] = m->mult[k * nv + a] >= 0 ? m->mult[k * nv + a] * (dim + 1) + c : -1;
    PetscCall(VecSetValues(m->gn, nv * (dim + 1), idx, acc, ADD_VALUES));
  }
  PetscCall(VecRestoreArrayRead(m->Uloc, &ua));
  PetscCall(VecAssemblyBegin(m->gn));
  PetscCall(VecAssemblyEnd(m->gn));
  PetscCall(VecGetArrayRead(m->gn, &ga));
  for (PetscInt i = 0; i < ct->n; i++) { /* per multiplier: the mean gap and normal (w g, w n: the integrals) */
    ct->g[i] = PetscRealPart(ga[i * (dim + 1)]) / ct->w[i];
    for (PetscInt d = 0; d < dim; d++) ct->nrm[i * dim + d] = PetscRealPart(ga[i * (dim + 1) + 1 + d]) / ct->w[i];
  }
  PetscCall(VecRestoreArrayRead(m->gn, &ga));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_forces(Contact *ct, Vec lam, Vec Ru) {
  struct ContactMortar *m   = ct->mortar;
  const PetscInt        dim = ct->dim, nv = m->nv, nn = m->nn;
  const PetscScalar    *la;
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(m->scat, lam, m->lamloc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(m->scat, lam, m->lamloc, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(m->lamloc, &la));
  PetscCall(VecSetOption(Ru, VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE)); /* the fixed components' rows (< 0) */
  for (PetscInt k = 0; k < m->nf; k++) {
    PetscScalar f[MN * 3] = {0};
    for (PetscInt q = 0; q < m->nq; q++) {
      const PetscReal *L = &m->L[q * nv], *n = &m->nq_[(k * m->nq + q) * dim];
      PetscReal        lh = 0; /* lambda_h = sum_j psi_j lambda_j at the point */
      for (PetscInt a = 0; a < nv; a++)
        if (m->lmult[k * nv + a] >= 0) lh += L[a] * PetscRealPart(la[m->lmult[k * nv + a]]);
      for (PetscInt j = 0; j < nn; j++) {
        PetscReal c = lh * shape2(L, &m->ab[(k * nn + j) * 2]) * m->dA[k * m->nq + q];
        for (PetscInt d = 0; d < dim; d++) f[j * dim + d] -= c * n[d];
      }
    }
    rows_to_frames(m, dim, k, 1, f); /* a constrained component's row is negative: ignored */
    PetscCall(VecSetValues(Ru, nn * dim, &m->rows[k * nn * dim], f, ADD_VALUES));
  }
  PetscCall(VecRestoreArrayRead(m->lamloc, &la));
  PetscCall(VecAssemblyBegin(Ru));
  PetscCall(VecAssemblyEnd(Ru));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_coupling(Contact *ct) {
  struct ContactMortar *m   = ct->mortar;
  const PetscInt        dim = ct->dim, nv = m->nv, nn = m->nn;
  PetscScalar          *aa;
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(ct->Bt));
  for (PetscInt k = 0; k < m->nf; k++) {
    PetscScalar v[MN * 3 * MV] = {0}; /* row-major: (node component) x (facet vertex) */
    for (PetscInt q = 0; q < m->nq; q++) {
      const PetscReal *L = &m->L[q * nv], *n = &m->nq_[(k * m->nq + q) * dim];
      for (PetscInt j = 0; j < nn; j++) {
        PetscReal c = shape2(L, &m->ab[(k * nn + j) * 2]) * m->dA[k * m->nq + q];
        for (PetscInt d = 0; d < dim; d++)
          for (PetscInt a = 0; a < nv; a++) v[(j * dim + d) * nv + a] -= c * L[a] * n[d];
      }
    }
    rows_to_frames(m, dim, k, nv, v); /* dR_u/dlambda on the rows' components */
    PetscCall(MatSetValues(ct->Bt, nn * dim, &m->rows[k * nn * dim], nv, &m->mult[k * nv], v, ADD_VALUES));
  }
  PetscCall(MatAssemblyBegin(ct->Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(ct->Bt, MAT_FINAL_ASSEMBLY));
  PetscCall(MatTranspose(ct->Bt, MAT_REUSE_MATRIX, &ct->B)); /* d(-c w g)/du = c Bt^T on the active rows, zero elsewhere */
  PetscCall(VecGetArray(m->act, &aa));
  for (PetscInt i = 0; i < ct->n; i++) aa[i] = ct->active[i] ? ct->c : 0.0;
  PetscCall(VecRestoreArray(m->act, &aa));
  PetscCall(MatDiagonalScale(ct->B, m->act, NULL));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_mortar_first_touch(Contact *ct, PetscReal *dmin) {
  struct ContactMortar *m   = ct->mortar;
  const PetscInt        dim = ct->dim;
  const PetscScalar    *ua;
  PetscFunctionBeginUser;
  *dmin = PETSC_MAX_REAL;
  for (PetscInt k = 0; k < m->nf * m->nq; k++) { /* the Gauss points */
    PetscReal nd = -m->nq_[k * dim + dim - 1];   /* n . d, d = -e_z (-e_y in 2D) */
    if (nd > 1e-3) *dmin = PetscMin(*dmin, m->gq[k] / nd);
  }
  PetscCall(VecGetArrayRead(m->Uloc, &ua));
  for (PetscInt k = 0; k < m->nf; k++) /* and the P2 nodes (a tip over a vertex touches there first) */
    for (PetscInt j = 0; j < m->nn; j++) {
      const PetscInt *ab = &m->ab[(k * m->nn + j) * 2];
      double          X[3] = {0, 0, 0}, x[3], n[3], u[3];
      node_disp(m, dim, k, j, ua, u);
      for (PetscInt d = 0; d < dim; d++) {
        X[d] = (m->Xv[(k * m->nv + ab[0]) * dim + d] + m->Xv[(k * m->nv + ab[1]) * dim + d]) / 2;
        x[d] = X[d] + u[d];
      }
      double g = indenter_gap(&ct->shape, X, x, m->ur, n);
      if (-n[dim - 1] > 1e-3) *dmin = PetscMin(*dmin, g / -n[dim - 1]);
    }
  PetscCall(VecRestoreArrayRead(m->Uloc, &ua));
  PetscFunctionReturn(0);
}
