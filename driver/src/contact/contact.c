#include "contact.h"
#include "contact_estimate.h"
#include "contact_mortar.h"

#include <math.h>
#include <petscsf.h>

/* eq. 18's weights w_i = int N_i dGamma (the same as nodal quadrature of N_i^2 for P1 in 3D and plane strain;
   axisymmetric: int N_i 2 pi r ds, exact, so that a node on the axis keeps a weight): the nodal forces of a unit
   traction along the indentation axis on the group. */
static PetscErrorCode contact_weights(FeProblem *p, const char *group, Vec *wvec, PetscInt *ustart) {
  const FeSpace *sp = fe_problem_space(p);
  char load[80];
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(load, sizeof load, "%s.%c", group, 'x' + (int)sp->dim - 1));
  PetscCall(fe_problem_unit_load(p, load, wvec));
  PetscCall(VecGetOwnershipRange(*wvec, ustart, NULL));
  PetscFunctionReturn(0);
}

/* nfacet (allocated over the chart): 2D: the group's edges at each vertex; 3D: its faces at each edge; totals over the ranks. */
static PetscErrorCode contact_facet_counts(DM dm, DMLabel label, PetscReal **nfacet_out) {
  PetscInt   pStart, pEnd, fStart, fEnd;
  PetscReal *nfacet;
  PetscSF    sf;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  PetscCall(PetscCalloc1(pEnd - pStart, &nfacet));
  for (PetscInt f = fStart; f < fEnd; f++) { /* the group's facets on this rank, for the rim */
    PetscInt val, nc;
    const PetscInt *cone;
    PetscCall(DMLabelGetValue(label, f, &val));
    if (val < 0) continue;
    PetscCall(DMPlexGetConeSize(dm, f, &nc));
    PetscCall(DMPlexGetCone(dm, f, &cone)); /* 2D: the edge's vertices; 3D: the face's edges */
    for (PetscInt k = 0; k < nc; k++) nfacet[cone[k] - pStart] += 1;
  }
  /* the totals over the ranks, on every rank */
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFReduceBegin(sf, MPIU_REAL, nfacet, nfacet, MPI_SUM));
  PetscCall(PetscSFReduceEnd(sf, MPIU_REAL, nfacet, nfacet, MPI_SUM));
  PetscCall(PetscSFBcastBegin(sf, MPIU_REAL, nfacet, nfacet, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_REAL, nfacet, nfacet, MPI_REPLACE));
  *nfacet_out = nfacet;
  PetscFunctionReturn(0);
}

/* Whether vertex v (global rows row, of which negative ones are fixed) is on the rim of the contact surface: an end
   of the contact edges (2D), on an edge with one contact face (3D); a node with a fixed component (a mirror plane,
   the axis) is a rim of the model, not of the surface. */
static PetscErrorCode contact_vertex_rim(DM dm, PetscInt dim, PetscInt v, const PetscInt row[], const PetscReal nfacet[], PetscInt pStart,
                                         PetscBool *rim) {
  PetscBool fixed = PETSC_FALSE;
  PetscFunctionBeginUser;
  for (PetscInt d = 0; d < dim; d++) fixed = fixed || row[d] < 0;
  if (dim == 2) *rim = nfacet[v - pStart] == 1;
  else {
    const PetscInt *supp;
    PetscInt        ns;
    PetscCall(DMPlexGetSupportSize(dm, v, &ns));
    PetscCall(DMPlexGetSupport(dm, v, &supp));
    for (PetscInt k = 0; k < ns; k++) *rim = *rim || nfacet[supp[k] - pStart] == 1;
  }
  *rim = *rim && !fixed;
  PetscFunctionReturn(0);
}

/* The contact nodes: owned vertices with a weight (coordinates, weights, global rows, rim); two passes, count then
   fill; wsum: this rank's sum of the weights. P2 (ct->mortar, mark given): the marked vertices (the contact facets'),
   with their plex points; their weights come later (contact_mortar_setup). */
static PetscErrorCode contact_nodes(FeProblem *p, Vec wvec, PetscInt ustart, const PetscInt mark[], const PetscReal nfacet[], Contact *ct,
                                    PetscReal *wsum) {
  const FeSpace *sp = fe_problem_space(p);
  DM                 dm = sp->dm;
  PetscInt           pStart, pEnd, vStart, vEnd;
  PetscSection       cs, ls, gs;
  Vec                coords;
  const PetscScalar *ca, *wa;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(VecGetArrayRead(coords, &ca));
  if (wvec) PetscCall(VecGetArrayRead(wvec, &wa));
  PetscCall(DMGetLocalSection(dm, &ls));
  PetscCall(DMGetGlobalSection(dm, &gs));
  *wsum = 0;
  for (int pass = 0; pass < 2; pass++) {
    PetscInt n = 0;
    for (PetscInt v = vStart; v < vEnd; v++) {
      PetscInt goff, off, loff, nidx, *idx = NULL, row[3];
      if (mark && !mark[v - pStart]) continue;
      PetscCall(PetscSectionGetOffset(gs, v, &goff));
      if (goff < 0) continue; /* owned by another rank */
      /* global rows of the vertex's components; constrained ones come back negative */
      PetscCall(DMPlexGetClosureIndices(dm, ls, gs, v, PETSC_TRUE, &nidx, &idx, NULL, NULL));
      PetscCheck(nidx == sp->dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "vertex with %d dofs", (int)nidx);
      for (PetscInt d = 0; d < sp->dim; d++) row[d] = idx[d];
      PetscCall(DMPlexRestoreClosureIndices(dm, ls, gs, v, PETSC_TRUE, &nidx, &idx, NULL, NULL));
      const PetscInt ra = row[sp->dim - 1]; /* the axial row carries the weight (free on a contact node) */
      if (ra < 0 || (wvec && !(PetscRealPart(wa[ra - ustart]) > 0))) continue;
      if (pass == 1) {
        PetscCall(PetscSectionGetOffset(cs, v, &off));
        for (PetscInt d = 0; d < sp->dim; d++) ct->X[n * sp->dim + d] = PetscRealPart(ca[off + d]), ct->row[n * sp->dim + d] = row[d];
        ct->w[n] = wvec ? PetscRealPart(wa[ra - ustart]) : 0;
        PetscCall(PetscSectionGetOffset(ls, v, &loff)); /* a node on an inclined mirror plane has a frame of its own */
        PetscCall(fe_constraint_node_frame(&sp->con, loff, &ct->R[n * sp->dim * sp->dim]));
        *wsum += ct->w[n];
        ct->vtx[n] = v;
        PetscCall(contact_vertex_rim(dm, sp->dim, v, row, nfacet, pStart, &ct->rim[n]));
      }
      n++;
    }
    if (pass == 0) {
      ct->n = n;
      PetscCall(PetscMalloc6(n * sp->dim, &ct->X, n, &ct->w, n, &ct->vtx, n * sp->dim, &ct->row, n, &ct->g, n * sp->dim, &ct->nrm));
      PetscCall(PetscCalloc2(n, &ct->active, n, &ct->rim));
      PetscCall(PetscMalloc1(n * sp->dim * sp->dim, &ct->R));
    }
  }
  PetscCall(VecRestoreArrayRead(coords, &ca));
  if (wvec) PetscCall(VecRestoreArrayRead(wvec, &wa));
  PetscFunctionReturn(0);
}

/* The blocks of eq. 15 with their nonzero pattern fixed once (preallocated exactly); nu: the local displacement rows. */
static PetscErrorCode contact_matrices(FeProblem *p, PetscInt nu, PetscInt ustart, Contact *ct) {
  const FeSpace *sp = fe_problem_space(p);
  MPI_Comm    comm = PetscObjectComm((PetscObject)sp->dm);
  PetscMPIInt rank;
  PetscInt    nr, *dnz;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  nr = rank == 0 ? 1 : 0;
  if (!ct->mortar) { /* P1: one node per multiplier (P2: Bt and B from contact_mortar_setup) */
    PetscCall(PetscCalloc1(PetscMax(nu, 1), &dnz));
    for (PetscInt i = 0; i < ct->n; i++)
      for (PetscInt d = 0; d < sp->dim; d++)
        if (ct->row[i * sp->dim + d] >= 0) dnz[ct->row[i * sp->dim + d] - ustart] = 1;
    PetscCall(MatCreateAIJ(comm, nu, ct->n, PETSC_DETERMINE, PETSC_DETERMINE, 0, dnz, 0, NULL, &ct->Bt));
    PetscCall(PetscFree(dnz));
    PetscCall(MatCreateAIJ(comm, ct->n, nu, PETSC_DETERMINE, PETSC_DETERMINE, sp->dim, NULL, 0, NULL, &ct->B));
  }
  PetscCall(MatCreateAIJ(comm, nr, ct->n, 1, ct->N, ct->n, NULL, ct->N - ct->n, NULL, &ct->Ct));
  PetscCall(MatCreateAIJ(comm, ct->n, nr, ct->N, 1, 1, NULL, 1, NULL, &ct->C));
  PetscCall(MatCreateAIJ(comm, ct->n, ct->n, ct->N, ct->N, 1, NULL, 0, NULL, &ct->D));
  PetscCall(MatCreateAIJ(comm, nr, nr, 1, 1, 1, NULL, 0, NULL, &ct->Kr));
  Mat all[6] = {ct->Bt, ct->B, ct->Ct, ct->C, ct->D, ct->Kr};
  for (int k = 0; k < 6; k++) PetscCall(MatSetOption(all[k], MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_create(FeProblem *p, const char *group, const IndenterShape *shape, Contact *ct) {
  const FeSpace *sp = fe_problem_space(p);
  DM         dm = sp->dm;
  DMLabel    label;
  PetscInt   ustart, nu;
  MPI_Comm   comm = PetscObjectComm((PetscObject)dm);
  Vec        wvec;
  PetscReal *nfacet, wsum; /* nfacet: 2D: contact edges at each vertex; 3D: contact faces at each edge */
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(ct, sizeof *ct));
  ct->shape = *shape;
  ct->dim   = sp->dim;
  PetscCheck(sp->order == 1 || sp->order == 2, comm, PETSC_ERR_SUP, "contact: P1 or P2 elements only (mesh.order 1 or 2)");
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCheck(label, comm, PETSC_ERR_ARG_WRONG, "contact: the mesh has no physical group '%s'", group);
  PetscCall(contact_weights(p, group, &wvec, &ustart));
  PetscCall(contact_facet_counts(dm, label, &nfacet));
  if (sp->order == 1) PetscCall(contact_nodes(p, wvec, ustart, NULL, nfacet, ct, &wsum));
  else { /* P2: the facets' vertices, their weights below */
    PetscInt *mark;
    PetscCall(contact_mortar_mark(p, label, ct, &mark));
    PetscCall(contact_nodes(p, NULL, 0, mark, nfacet, ct, &wsum));
    PetscCall(PetscFree(mark));
  }
  PetscCall(PetscFree(nfacet));
  /* the numbering of the contact nodes over the ranks */
  PetscCall(MPIU_Allreduce(&ct->n, &ct->N, 1, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Scan(&ct->n, &ct->rstart, 1, MPIU_INT, MPI_SUM, comm));
  ct->rstart -= ct->n;
  PetscCheck(ct->N > 0, comm, PETSC_ERR_ARG_WRONG, "key 'indenter.contact': the physical group '%s' has no boundary %s (the potential contact surface must be boundary %s of the mesh)", group, sp->dim == 3 ? "faces" : "edges", sp->dim == 3 ? "faces" : "edges");
  if (ct->mortar) PetscCall(contact_mortar_setup(p, label, ct, &wsum));
  PetscCall(contact_estimate_setup(p, label, ct));
  PetscCall(MPIU_Allreduce(&wsum, &ct->weight_sum, 1, MPIU_REAL, MPI_SUM, comm));
  PetscCall(VecGetLocalSize(wvec, &nu)); /* the displacement layout */
  PetscCall(VecDestroy(&wvec));
  PetscCall(contact_matrices(p, nu, ustart, ct));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_destroy(Contact *ct) {
  PetscFunctionBeginUser;
  PetscCall(PetscFree6(ct->X, ct->w, ct->vtx, ct->row, ct->g, ct->nrm));
  PetscCall(PetscFree2(ct->active, ct->rim));
  PetscCall(contact_mortar_destroy(ct));
  PetscCall(contact_estimate_destroy(ct));
  PetscCall(PetscFree(ct->R));
  Mat *all[6] = {&ct->Bt, &ct->B, &ct->Ct, &ct->C, &ct->D, &ct->Kr};
  for (int k = 0; k < 6; k++) PetscCall(MatDestroy(all[k]));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_update_gaps(Contact *ct, Vec U, PetscReal ur) {
  const PetscScalar *ua;
  PetscInt           ustart;
  const PetscInt     dim = ct->dim;
  PetscFunctionBeginUser;
  if (ct->mortar) { /* P2: weighted gaps at the facets' Gauss points */
    PetscCall(contact_mortar_gaps(ct, U, ur));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetOwnershipRange(U, &ustart, NULL));
  PetscCall(VecGetArrayRead(U, &ua));
  for (PetscInt i = 0; i < ct->n; i++) {
    double x[3], u[3];
    for (PetscInt d = 0; d < dim; d++) {
      PetscInt r = ct->row[i * dim + d];
      u[d]       = r >= 0 ? PetscRealPart(ua[r - ustart]) : 0.0; /* fixed components are zero */
    }
    for (PetscInt d = 0; d < dim; d++) { /* the node's rows in its frame: to global axes */
      x[d] = ct->X[i * dim + d];
      for (PetscInt j = 0; j < dim; j++) x[d] += ct->R[(i * dim + d) * dim + j] * u[j];
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


void contact_frame_normal(const Contact *ct, PetscInt i, PetscReal nf[]) {
  const PetscInt dim = ct->dim;
  for (PetscInt j = 0; j < dim; j++) {
    nf[j] = 0;
    for (PetscInt d = 0; d < dim; d++) nf[j] += ct->R[(i * dim + d) * dim + j] * ct->nrm[i * dim + d];
  }
}

PetscErrorCode contact_residual(Contact *ct, Vec lam, PetscReal ur, PetscBool depth_control, PetscReal target,
                                Vec Ru, PetscReal *Rr, PetscReal *ncp_norm) {
  const PetscScalar *la;
  PetscScalar       *ra;
  PetscReal          loc[2] = {0, 0}, all[2];
  PetscInt           rstart;
  const PetscInt     dim = ct->dim;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(Ru, &rstart, NULL));
  PetscCall(VecGetArray(Ru, &ra)); /* a contact node's rows are owned where the node is */
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscReal l = PetscRealPart(la[i]), nf[3];
    if (!ct->mortar) { /* R_u -= lambda w n (eq. 10's last term, nodal quadrature; P2: contact_mortar_forces) */
      contact_frame_normal(ct, i, nf);
      for (PetscInt d = 0; d < dim; d++)
        if (ct->row[i * dim + d] >= 0) ra[ct->row[i * dim + d] - rstart] -= l * ct->w[i] * nf[d];
    }
    loc[0] += l * ct->w[i] * contact_ndotd(ct, i);                           /* eq. 19: P = 1^T M lambda */
    loc[1] += PetscSqr(ct->w[i] * (l - PetscMax(0, l - ct->c * ct->g[i]))); /* eq. 13, g >= 0 open */
  }
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscCall(VecRestoreArray(Ru, &ra));
  if (ct->mortar) PetscCall(contact_mortar_forces(ct, lam, Ru)); /* P2: int lambda_h N n dA */
  PetscCall(MPIU_Allreduce(loc, all, 2, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)lam)));
  *Rr       = depth_control ? ct->kn * (ur - target) : all[0] - target;
  *ncp_norm = PetscSqrtReal(all[1]);
  PetscFunctionReturn(0);
}

PetscErrorCode contact_constraint_residual(Contact *ct, Vec lam, Vec Rlam) {
  const PetscScalar *la;
  PetscScalar       *ra;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  PetscCall(VecGetArray(Rlam, &ra));
  for (PetscInt i = 0; i < ct->n; i++) ra[i] = ct->active[i] ? -ct->c * ct->w[i] * ct->g[i] : ct->w[i] * la[i]; /* eq. 12; eq. 15's I rows */
  PetscCall(VecRestoreArray(Rlam, &ra));
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_jacobian(Contact *ct, PetscBool depth_control, PetscBool shift) {
  const PetscInt dim = ct->dim;
  PetscMPIInt    rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)ct->D), &rank));
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscInt  li = ct->rstart + i, zero = 0;
    PetscReal wn[3], c = ct->w[i] * contact_ndotd(ct, i), z = 0.0;
    contact_frame_normal(ct, i, wn);
    for (PetscInt d = 0; d < dim; d++) wn[d] *= -ct->w[i];
    for (PetscInt d = 0; d < dim && !ct->mortar; d++) { /* dR_u/dlambda = -w n, all nodes (exact) */
      PetscInt r = ct->row[i * dim + d];
      if (r < 0) continue;
      PetscCall(MatSetValue(ct->Bt, r, li, wn[d], INSERT_VALUES));
      PetscCall(MatSetValue(ct->B, li, r, ct->active[i] ? ct->c * wn[d] : 0.0, INSERT_VALUES)); /* d(-c w g)/du */
    }
    PetscCall(MatSetValue(ct->Ct, 0, li, depth_control ? 0.0 : c, INSERT_VALUES));            /* eq. 19 */
    PetscCall(MatSetValue(ct->C, li, zero, ct->active[i] ? ct->c * c : 0.0, INSERT_VALUES)); /* d(-c w g)/du_r */
    PetscCall(MatSetValue(ct->D, li, li, ct->active[i] ? z : ct->w[i], INSERT_VALUES));      /* w x identity rows */
  }
  if (ct->mortar) PetscCall(contact_mortar_coupling(ct)); /* P2: Bt and B from the facet integrals */
  ct->kr = depth_control || shift ? ct->kn : 0.0, ct->depth_control = depth_control;
  if (!rank) PetscCall(MatSetValue(ct->Kr, 0, 0, ct->kr, INSERT_VALUES));
  Mat all[6] = {ct->Bt, ct->B, ct->Ct, ct->C, ct->D, ct->Kr};
  for (int k = ct->mortar ? 2 : 0; k < 6; k++) PetscCall(MatAssemblyBegin(all[k], MAT_FINAL_ASSEMBLY));
  for (int k = ct->mortar ? 2 : 0; k < 6; k++) PetscCall(MatAssemblyEnd(all[k], MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_summary(Contact *ct, Vec lam, PetscReal *force, PetscReal *penetration, PetscReal *min_lambda) {
  const PetscScalar *la;
  PetscReal          loc[3] = {0, 0, PETSC_MAX_REAL}, all[3];
  MPI_Comm           comm   = PetscObjectComm((PetscObject)lam);
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++) {
    loc[0] += PetscRealPart(la[i]) * ct->w[i] * contact_ndotd(ct, i);
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

PetscErrorCode contact_node_stiffness(Contact *ct, Mat K) {
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
  ct->kn = all;
  PetscFunctionReturn(0);
}

PetscErrorCode contact_on_rim(Contact *ct, PetscInt *count) {
  PetscInt loc = 0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ct->n; i++) loc += ct->active[i] && ct->rim[i];
  PetscCall(MPIU_Allreduce(&loc, count, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)ct->D)));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_first_touch(Contact *ct, PetscBool pointwise, PetscReal *dmin) {
  PetscReal loc = PETSC_MAX_REAL;
  PetscFunctionBeginUser;
  if (ct->mortar && pointwise) PetscCall(contact_mortar_first_touch(ct, &loc));
  else
    for (PetscInt i = 0; i < ct->n; i++) {
      PetscReal nd = contact_ndotd(ct, i);
      if (nd > 1e-3) loc = PetscMin(loc, ct->g[i] / nd);
    }
  PetscCall(MPIU_Allreduce(&loc, dmin, 1, MPIU_REAL, MPI_MIN, PetscObjectComm((PetscObject)ct->D)));
  PetscFunctionReturn(0);
}

/* The angle about the indenter's axis through `tip` that the potential contact surface spans, in degrees: the
   circle less its largest gap free of nodes, the nodes' azimuths taken in bins of a tenth of a degree (nodes within
   1e-9 of the surface's reach from the axis have none). 2D: 0 with every node on one side of the axis, 180 with
   nodes on both. A model that is one of `copies` mirror images of the body spans at most 360 / copies (3D; 2D: 0). */
PetscErrorCode contact_azimuth_span(Contact *ct, const double tip[], PetscReal *span) {
  enum { NBIN = 3600 };
  const PetscInt nl = ct->dim - 1;
  PetscInt      *bin, *all, gap = 0, run = 0, first = -1;
  PetscReal      reach = 0, loc;
  MPI_Comm       comm = PetscObjectComm((PetscObject)ct->D);
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < ct->n; i++) {
    PetscReal r = 0;
    for (PetscInt k = 0; k < nl; k++) r += PetscSqr(ct->X[i * ct->dim + k] - tip[k]);
    reach = PetscMax(reach, PetscSqrtReal(r));
  }
  loc = reach;
  PetscCall(MPIU_Allreduce(&loc, &reach, 1, MPIU_REAL, MPI_MAX, comm));
  PetscCall(PetscCalloc2(NBIN, &bin, NBIN, &all));
  for (PetscInt i = 0; i < ct->n; i++) {
    const PetscReal *x = &ct->X[i * ct->dim], dx = x[0] - tip[0], dy = nl > 1 ? x[1] - tip[1] : 0;
    if (PetscSqrtReal(dx * dx + dy * dy) <= 1e-9 * reach) continue;
    PetscReal az = atan2(dy, dx) * 180 / PETSC_PI; /* (-180, 180] */
    bin[((PetscInt)PetscFloorReal((az + 180) * NBIN / 360)) % NBIN] = 1;
  }
  PetscCall(MPIU_Allreduce(bin, all, NBIN, MPIU_INT, MPI_MAX, comm));
  for (PetscInt b = 0; b < 2 * NBIN; b++) { /* twice round: the largest empty run of bins on the circle */
    if (all[b % NBIN]) {
      if (first < 0) first = b;
      run = 0;
    } else if (first >= 0) {
      run++;
      gap = PetscMax(gap, run);
    }
  }
  PetscCall(PetscFree2(bin, all));
  if (first < 0) *span = 0; /* every node on the axis */
  else if (nl == 1) *span = gap >= NBIN / 2 ? 0 : 180;
  else *span = 360.0 * (NBIN - PetscMin(gap, NBIN)) / NBIN;
  PetscFunctionReturn(0);
}
