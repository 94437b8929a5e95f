#include "contact.h"

#include <math.h>
#include <petscsf.h>

/* Add the weights int N_i dGamma of the vertices of one boundary facet (P1: exact, and equal to the
 * nodal quadrature of eq. 18 for 3D and plane strain; axisymmetric: int N_i 2 pi r ds, exact on the
 * straight edge, so that a node on the axis keeps a positive weight). */
static void facet_weights(const FeProblem *p, PetscInt nv, const PetscReal *xv, PetscReal *wv) {
  if (p->dim == 3) { /* triangle: area / 3 each */
    PetscReal a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) a[k] = xv[3 + k] - xv[k], b[k] = xv[6 + k] - xv[k];
    c[0] = a[1] * b[2] - a[2] * b[1], c[1] = a[2] * b[0] - a[0] * b[2], c[2] = a[0] * b[1] - a[1] * b[0];
    PetscReal area = 0.5 * PetscSqrtReal(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    for (int v = 0; v < nv; v++) wv[v] = area / 3;
    return;
  }
  PetscReal L = PetscSqrtReal(PetscSqr(xv[2] - xv[0]) + PetscSqr(xv[3] - xv[1]));
  if (p->kin == KIN_AXISYMMETRIC) {
    PetscReal ra = xv[0], rb = xv[2];
    wv[0] = 2 * PETSC_PI * L * (2 * ra + rb) / 6, wv[1] = 2 * PETSC_PI * L * (ra + 2 * rb) / 6;
  } else wv[0] = wv[1] = 0.5 * L * p->thickness;
}

PetscErrorCode contact_create(FeProblem *p, const char *group, const IndenterShape *shape, Contact *ct) {
  DM           dm = p->dm;
  DMLabel      label;
  PetscInt     pStart, pEnd, vStart, vEnd, fStart, fEnd;
  PetscReal   *wpt;
  MPI_Comm     comm = PetscObjectComm((PetscObject)dm);
  PetscSection cs, ls, gs;
  Vec          coords;
  const PetscScalar *ca;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(ct, sizeof *ct));
  ct->shape = *shape;
  ct->dim   = p->dim;
  PetscCheck(p->order == 1, comm, PETSC_ERR_SUP, "contact: only P1 elements (mesh.order: 1); nodal quadrature of P2 faces puts no weight on the vertices");
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCheck(label, comm, PETSC_ERR_ARG_WRONG, "contact: the mesh has no physical group '%s'", group);
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscReal *nfacet; /* 2D: contact edges at each vertex; 3D: contact faces at each edge */
  PetscCall(PetscCalloc1(pEnd - pStart, &wpt));
  PetscCall(PetscCalloc1(pEnd - pStart, &nfacet));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &ca));
  for (PetscInt f = fStart; f < fEnd; f++) { /* the group's facets on this rank: each lives on one rank */
    PetscInt val, ncl, *cl = NULL, nv = 0, verts[3];
    PetscReal xv[9], wv[3];
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val < 0) continue;
    PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
    for (PetscInt k = 0; k < ncl; k++) {
      PetscInt q = cl[2 * k], off;
      if (q < vStart || q >= vEnd || nv == 3) continue;
      PetscCall(PetscSectionGetOffset(cs, q, &off));
      for (PetscInt d = 0; d < p->dim; d++) xv[nv * p->dim + d] = PetscRealPart(ca[off + d]);
      verts[nv++] = q;
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
    PetscCheck(nv == p->dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "contact facet with %d vertices", (int)nv);
    facet_weights(p, nv, xv, wv);
    for (PetscInt v = 0; v < nv; v++) wpt[verts[v] - pStart] += wv[v];
    if (p->dim == 2) for (PetscInt v = 0; v < nv; v++) nfacet[verts[v] - pStart] += 1;
    else {
      const PetscInt *cone;
      PetscInt        nc;
      PetscCall(DMPlexGetConeSize(dm, f, &nc));
      PetscCall(DMPlexGetCone(dm, f, &cone));
      for (PetscInt k = 0; k < nc; k++) nfacet[cone[k] - pStart] += 1;
    }
  }
  { /* shared vertices: sum the weights on the owning rank */
    PetscSF sf;
    PetscCall(DMGetPointSF(dm, &sf));
    PetscCall(PetscSFReduceBegin(sf, MPIU_REAL, wpt, wpt, MPI_SUM));
    PetscCall(PetscSFReduceEnd(sf, MPIU_REAL, wpt, wpt, MPI_SUM));
    PetscCall(PetscSFReduceBegin(sf, MPIU_REAL, nfacet, nfacet, MPI_SUM)); /* and every rank its points' totals */
    PetscCall(PetscSFReduceEnd(sf, MPIU_REAL, nfacet, nfacet, MPI_SUM));
    PetscCall(PetscSFBcastBegin(sf, MPIU_REAL, nfacet, nfacet, MPI_REPLACE));
    PetscCall(PetscSFBcastEnd(sf, MPIU_REAL, nfacet, nfacet, MPI_REPLACE));
  }
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  PetscInt n = 0;
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt goff;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (wpt[v - pStart] > 0 && goff >= 0) n++;
  }
  ct->n = n;
  PetscCall(PetscMalloc5(n * p->dim, &ct->X, n, &ct->w, n * p->dim, &ct->row, n, &ct->g, n * p->dim, &ct->nrm));
  PetscCall(PetscCalloc2(n, &ct->active, n, &ct->rim));
  n = 0;
  PetscReal wsum = 0;
  for (PetscInt v = vStart; v < vEnd; v++) {
    PetscInt goff, off, nidx, *idx = NULL;
    PetscCall(PetscSectionGetOffset(gs, v, &goff));
    if (!(wpt[v - pStart] > 0 && goff >= 0)) continue;
    PetscCall(PetscSectionGetOffset(cs, v, &off));
    for (PetscInt d = 0; d < p->dim; d++) ct->X[n * p->dim + d] = PetscRealPart(ca[off + d]);
    /* global rows of the vertex's components; constrained ones come back negative */
    PetscCall(DMPlexGetClosureIndices(dm, ls, gs, v, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    PetscCheck(nidx == p->dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "vertex with %d dofs", (int)nidx);
    for (PetscInt d = 0; d < p->dim; d++) ct->row[n * p->dim + d] = idx[d];
    PetscCall(DMPlexRestoreClosureIndices(dm, ls, gs, v, PETSC_TRUE, &nidx, &idx, NULL, NULL));
    ct->w[n] = wpt[v - pStart];
    wsum += ct->w[n];
    /* on the rim: an end of the contact edges (2D), on an edge with one contact face (3D); a node with a
       fixed component (a mirror plane, the axis) is a rim of the model, not of the surface */
    PetscBool fixed = PETSC_FALSE;
    for (PetscInt d = 0; d < p->dim; d++) fixed = fixed || ct->row[n * p->dim + d] < 0;
    if (p->dim == 2) ct->rim[n] = nfacet[v - pStart] == 1;
    else {
      const PetscInt *supp;
      PetscInt        ns;
      PetscCall(DMPlexGetSupportSize(dm, v, &ns));
      PetscCall(DMPlexGetSupport(dm, v, &supp));
      for (PetscInt k = 0; k < ns; k++) ct->rim[n] = ct->rim[n] || nfacet[supp[k] - pStart] == 1;
    }
    ct->rim[n] = ct->rim[n] && !fixed;
    n++;
  }
  PetscCall(VecRestoreArrayRead(coords, &ca));
  PetscCall(PetscFree(wpt));
  PetscCall(PetscFree(nfacet));
  PetscCall(MPIU_Allreduce(&ct->n, &ct->N, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&wsum, &ct->weight_sum, 1, MPIU_REAL, MPI_SUM, comm));
  PetscCallMPI(MPI_Scan(&ct->n, &ct->rstart, 1, MPIU_INT, MPI_SUM, comm));
  ct->rstart -= ct->n;
  PetscCheck(ct->N > 0, comm, PETSC_ERR_ARG_WRONG, "contact: the group '%s' has no boundary faces", group);

  /* The blocks of eq. 15 with their nonzero pattern fixed once (preallocated exactly). */
  PetscMPIInt rank;
  PetscInt    nu, ustart, nr;
  Vec         tmp;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  nr = rank == 0 ? 1 : 0;
  PetscCall(DMGetGlobalVector(dm, &tmp));
  PetscCall(VecGetLocalSize(tmp, &nu));
  PetscCall(VecGetOwnershipRange(tmp, &ustart, NULL));
  PetscCall(DMRestoreGlobalVector(dm, &tmp));
  PetscInt *dnz;
  PetscCall(PetscCalloc1(PetscMax(nu, 1), &dnz));
  for (PetscInt i = 0; i < ct->n; i++)
    for (PetscInt d = 0; d < p->dim; d++)
      if (ct->row[i * p->dim + d] >= 0) dnz[ct->row[i * p->dim + d] - ustart] = 1;
  PetscCall(MatCreateAIJ(comm, nu, ct->n, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz, 0, NULL, &ct->Bt));
  PetscCall(PetscFree(dnz));
  PetscCall(MatCreateAIJ(comm, ct->n, nu, PETSC_DETERMINE, PETSC_DETERMINE, p->dim, NULL, 0, NULL, &ct->B));
  PetscCall(MatCreateAIJ(comm, nr, ct->n, 1, ct->N, ct->n, NULL, ct->N - ct->n, NULL, &ct->Ct));
  PetscCall(MatCreateAIJ(comm, ct->n, nr, ct->N, 1, 1, NULL, 1, NULL, &ct->C));
  PetscCall(MatCreateAIJ(comm, ct->n, ct->n, ct->N, ct->N, 1, NULL, 0, NULL, &ct->D));
  PetscCall(MatCreateAIJ(comm, nr, nr, 1, 1, 1, NULL, 0, NULL, &ct->Kr));
  Mat all[6] = {ct->Bt, ct->B, ct->Ct, ct->C, ct->D, ct->Kr};
  for (int k = 0; k < 6; k++) PetscCall(MatSetOption(all[k], MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_destroy(Contact *ct) {
  PetscFunctionBeginUser;
  PetscCall(PetscFree5(ct->X, ct->w, ct->row, ct->g, ct->nrm));
  PetscCall(PetscFree2(ct->active, ct->rim));
  Mat *all[6] = {&ct->Bt, &ct->B, &ct->Ct, &ct->C, &ct->D, &ct->Kr};
  for (int k = 0; k < 6; k++) PetscCall(MatDestroy(all[k]));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_update_gaps(Contact *ct, Vec U, PetscReal ur) {
  const PetscScalar *ua;
  PetscInt           ustart;
  const PetscInt     dim = ct->dim;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(U, &ustart, NULL));
  PetscCall(VecGetArrayRead(U, &ua));
  for (PetscInt i = 0; i < ct->n; i++) {
    double x[3];
    for (PetscInt d = 0; d < dim; d++) {
      PetscInt r = ct->row[i * dim + d];
      x[d]       = ct->X[i * dim + d] + (r >= 0 ? PetscRealPart(ua[r - ustart]) : 0.0); /* fixed components are zero */
    }
    double nv[3];
    ct->g[i] = indenter_gap(&ct->shape, &ct->X[i * dim], x, ur, nv);
    for (PetscInt d = 0; d < dim; d++) ct->nrm[i * dim + d] = nv[d];
  }
  PetscCall(VecRestoreArrayRead(U, &ua));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_update_active(Contact *ct, Vec lam, PetscReal lambda_ref, PetscInt *changes, PetscInt *nactive) {
  const PetscScalar *la;
  const PetscReal    eps = 1e-12 * lambda_ref; /* a node touching with no pressure (roundoff) is released */
  PetscInt           loc[2] = {0, 0}, all[2];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++) { /* eq. 14 with g >= 0 open: active where lambda - c g > 0 */
    PetscBool a = PetscRealPart(la[i]) - ct->c * ct->g[i] > eps ? PETSC_TRUE : PETSC_FALSE;
    loc[0] += a != ct->active[i];
    loc[1] += a;
    ct->active[i] = a;
  }
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscCall(MPIU_Allreduce(loc, all, 2, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)lam)));
  *changes = all[0], *nactive = all[1];
  PetscFunctionReturn(0);
}

/* n_i . d: d = -e_dim */
#define NDOTD(ct, i) (-(ct)->nrm[(i) * (ct)->dim + (ct)->dim - 1])

PetscErrorCode contact_residual(Contact *ct, Vec lam, PetscReal ur, PetscBool depth_control, PetscReal target,
                                Vec Ru, PetscReal *Rr, PetscReal *ncp_norm) {
  const PetscScalar *la;
  PetscReal          loc[2] = {0, 0}, all[2];
  const PetscInt     dim    = ct->dim;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscReal l = PetscRealPart(la[i]);
    for (PetscInt d = 0; d < dim; d++) /* R_u -= lambda w n (eq. 10's last term, nodal quadrature) */
      if (ct->row[i * dim + d] >= 0) PetscCall(VecSetValue(Ru, ct->row[i * dim + d], -l * ct->w[i] * ct->nrm[i * dim + d], ADD_VALUES));
    loc[0] += l * ct->w[i] * NDOTD(ct, i);                           /* eq. 19: P = 1^T M lambda */
    loc[1] += PetscSqr(ct->w[i] * (l - PetscMax(0, l - ct->c * ct->g[i]))); /* eq. 13, g >= 0 open */
  }
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscCall(VecAssemblyBegin(Ru));
  PetscCall(VecAssemblyEnd(Ru));
  PetscCall(MPIU_Allreduce(loc, all, 2, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)lam)));
  *Rr       = depth_control ? ur - target : all[0] - target;
  *ncp_norm = PetscSqrtReal(all[1]);
  PetscFunctionReturn(0);
}

PetscErrorCode contact_constraint_residual(Contact *ct, Vec lam, Vec Rlam) {
  const PetscScalar *la;
  PetscScalar       *ra;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  PetscCall(VecGetArray(Rlam, &ra));
  for (PetscInt i = 0; i < ct->n; i++) ra[i] = ct->active[i] ? -ct->w[i] * ct->g[i] : la[i]; /* eq. 12; eq. 15's I rows */
  PetscCall(VecRestoreArray(Rlam, &ra));
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_jacobian(Contact *ct, PetscBool depth_control, PetscReal kshift) {
  const PetscInt dim = ct->dim;
  PetscMPIInt    rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)ct->D), &rank));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscInt  li = ct->rstart + i, zero = 0;
    PetscReal wn[3], c = ct->w[i] * NDOTD(ct, i), one = 1.0, z = 0.0;
    for (PetscInt d = 0; d < dim; d++) wn[d] = -ct->w[i] * ct->nrm[i * dim + d];
    for (PetscInt d = 0; d < dim; d++) { /* dR_u/dlambda = -w n, all nodes (exact) */
      PetscInt r = ct->row[i * dim + d];
      if (r < 0) continue;
      PetscCall(MatSetValue(ct->Bt, r, li, wn[d], INSERT_VALUES));
      PetscCall(MatSetValue(ct->B, li, r, ct->active[i] ? wn[d] : 0.0, INSERT_VALUES)); /* d(-w g)/du */
    }
    PetscCall(MatSetValue(ct->Ct, 0, li, depth_control ? 0.0 : c, INSERT_VALUES));    /* eq. 19 */
    PetscCall(MatSetValue(ct->C, li, zero, ct->active[i] ? c : 0.0, INSERT_VALUES));  /* d(-w g)/du_r */
    PetscCall(MatSetValue(ct->D, li, li, ct->active[i] ? z : one, INSERT_VALUES));    /* identity rows */
  }
  ct->kr = depth_control ? 1.0 : kshift, ct->depth_control = depth_control;
  if (!rank) PetscCall(MatSetValue(ct->Kr, 0, 0, ct->kr, INSERT_VALUES));
  Mat all[6] = {ct->Bt, ct->B, ct->Ct, ct->C, ct->D, ct->Kr};
  for (int k = 0; k < 6; k++) PetscCall(MatAssemblyBegin(all[k], MAT_FINAL_ASSEMBLY));
  for (int k = 0; k < 6; k++) PetscCall(MatAssemblyEnd(all[k], MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_summary(Contact *ct, Vec lam, PetscReal *force, PetscReal *penetration, PetscReal *min_lambda) {
  const PetscScalar *la;
  PetscReal          loc[3] = {0, 0, PETSC_MAX_REAL}, all[3];
  MPI_Comm           comm   = PetscObjectComm((PetscObject)lam);
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++) {
    loc[0] += PetscRealPart(la[i]) * ct->w[i] * NDOTD(ct, i);
    loc[1] = PetscMax(loc[1], -ct->g[i]);
    if (ct->active[i]) loc[2] = PetscMin(loc[2], PetscRealPart(la[i]));
  }
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscCall(MPIU_Allreduce(&loc[0], &all[0], 1, MPIU_REAL, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&loc[1], &all[1], 1, MPIU_REAL, MPI_MAX, comm));
  PetscCall(MPIU_Allreduce(&loc[2], &all[2], 1, MPIU_REAL, MPI_MIN, comm));
  *force = all[0], *penetration = all[1], *min_lambda = all[2] == PETSC_MAX_REAL ? 0 : all[2];
  PetscFunctionReturn(0);
}

PetscErrorCode contact_node_stiffness(Contact *ct, Mat K, PetscReal *k) {
  Vec                diag;
  const PetscScalar *da;
  PetscInt           rstart;
  PetscReal          kmax = 0, all;
  PetscFunctionBeginUser;
  PetscCall(MatCreateVecs(K, NULL, &diag));
  PetscCall(MatGetDiagonal(K, diag));
  PetscCall(VecGetOwnershipRange(diag, &rstart, NULL));
  PetscCall(VecGetArrayRead(diag, &da));
  for (PetscInt i = 0; i < ct->n * ct->dim; i++)
    if (ct->row[i] >= 0) kmax = PetscMax(kmax, PetscAbsReal(PetscRealPart(da[ct->row[i] - rstart])));
  PetscCall(VecRestoreArrayRead(diag, &da));
  PetscCall(VecDestroy(&diag));
  PetscCall(MPIU_Allreduce(&kmax, &all, 1, MPIU_REAL, MPI_MAX, PetscObjectComm((PetscObject)K)));
  *k = all;
  PetscFunctionReturn(0);
}

PetscErrorCode contact_on_rim(Contact *ct, PetscInt *count) {
  PetscInt loc = 0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ct->n; i++) loc += ct->active[i] && ct->rim[i];
  PetscCall(MPIU_Allreduce(&loc, count, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ct->D)));
  PetscFunctionReturn(0);
}
