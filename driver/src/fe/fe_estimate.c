/* The Zienkiewicz-Zhu indicator and the size field made from it (fe_estimate.h; docs/adapt.md). */
#include "fe_estimate.h"

#include <math.h>
#include <petscsf.h>

#define NV 7 /* values per vertex: a stress (6) and a weight */

/* The vertex DM: the mesh with NV values per vertex and none elsewhere, so that the sums over the cells that
   share a vertex cross the ranks by PETSc's own star forest (DMLocalToGlobal). */
static PetscErrorCode vertex_dm(FeProblem *p) {
  PetscSection s;
  PetscInt     pStart, pEnd, vStart, vEnd;
  PetscFunctionBeginUser;
  if (p->est.dmv) PetscFunctionReturn(0);
  PetscCall(DMClone(p->space.dm, &p->est.dmv));
  PetscCall(PetscSectionCreate(PetscObjectComm((PetscObject)p->space.dm), &s));
  PetscCall(DMPlexGetChart(p->space.dm, &pStart, &pEnd));
  PetscCall(DMPlexGetDepthStratum(p->space.dm, 0, &vStart, &vEnd));
  PetscCall(PetscSectionSetChart(s, pStart, pEnd));
  for (PetscInt v = vStart; v < vEnd; v++) PetscCall(PetscSectionSetDof(s, v, NV));
  PetscCall(PetscSectionSetUp(s));
  PetscCall(DMSetLocalSection(p->est.dmv, s));
  PetscCall(PetscSectionDestroy(&s));
  PetscFunctionReturn(0);
}

/* The local offsets of the vertices of cell c in the vertex DM's local vector, in closure order (the order of the
   coordinates' closure), and their number. */
static PetscErrorCode cell_vertex_offsets(FeProblem *p, PetscInt c, PetscInt off[4], PetscInt *nv) {
  PetscSection s;
  PetscInt     n, *pts = NULL, vStart, vEnd;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(p->est.dmv, &s));
  PetscCall(DMPlexGetDepthStratum(p->space.dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetTransitiveClosure(p->space.dm, c, PETSC_TRUE, &n, &pts));
  *nv = 0;
  for (PetscInt i = 0; i < n; i++)
    if (pts[2 * i] >= vStart && pts[2 * i] < vEnd && *nv < 4) PetscCall(PetscSectionGetOffset(s, pts[2 * i], &off[(*nv)++]));
  PetscCall(DMPlexRestoreTransitiveClosure(p->space.dm, c, PETSC_TRUE, &n, &pts));
  PetscFunctionReturn(0);
}

/* Solve the small system A x = b (n <= 4, row-major) by Gaussian elimination with partial pivoting; returns 0 if
   A is singular. */
static int solve_small(PetscInt n, PetscReal *A, PetscReal *b) {
  for (PetscInt k = 0; k < n; k++) {
    PetscInt piv = k;
    for (PetscInt i = k + 1; i < n; i++)
      if (PetscAbsReal(A[i * n + k]) > PetscAbsReal(A[piv * n + k])) piv = i;
    if (A[piv * n + k] == 0) return 0;
    for (PetscInt j = 0; j < n; j++) { PetscReal t = A[k * n + j]; A[k * n + j] = A[piv * n + j], A[piv * n + j] = t; }
    PetscReal t = b[k]; b[k] = b[piv], b[piv] = t;
    for (PetscInt i = k + 1; i < n; i++) {
      PetscReal f = A[i * n + k] / A[k * n + k];
      for (PetscInt j = k; j < n; j++) A[i * n + j] -= f * A[k * n + j];
      b[i] -= f * b[k];
    }
  }
  for (PetscInt k = n - 1; k >= 0; k--) {
    for (PetscInt j = k + 1; j < n; j++) b[k] -= A[k * n + j] * b[j];
    b[k] /= A[k * n + k];
  }
  return 1;
}

/* The geometry of cell c: its vertices' coordinates (closure order), its quadrature points' coordinates and
   its volume (the reference weights times det J, without the kinematics' weight). */
typedef struct {
  PetscInt  nv, dim;
  PetscReal xv[4][3], xq[64][3], vol;
} CellGeom;

static PetscErrorCode cell_geometry(FeProblem *p, PetscInt c, CellGeom *g) {
  PetscReal    v0[3 * 64], J[9 * 64], invJ[9 * 64], detJ[64];
  Vec          X;
  DM           cdm;
  PetscScalar *xc = NULL;
  PetscInt     n, dim = p->space.dim;
  PetscFunctionBeginUser;
  PetscCall(DMPlexComputeCellGeometryFEM(p->space.dm, c, p->space.quad, v0, J, invJ, detJ));
  g->dim = dim, g->vol = 0;
  for (PetscInt q = 0; q < p->space.nq; q++) {
    for (PetscInt i = 0; i < dim; i++) g->xq[q][i] = v0[q * dim + i];
    g->vol += p->space.qweights[q] * detJ[q];
  }
  PetscCall(DMGetCoordinatesLocal(p->space.dm, &X));
  PetscCall(DMGetCoordinateDM(p->space.dm, &cdm));
  PetscCall(DMPlexVecGetClosure(cdm, NULL, X, c, &n, &xc));
  g->nv = PetscMin(n / dim, 4);
  for (PetscInt v = 0; v < g->nv; v++)
    for (PetscInt i = 0; i < dim; i++) g->xv[v][i] = PetscRealPart(xc[v * dim + i]);
  PetscCall(DMPlexVecRestoreClosure(cdm, NULL, X, c, &n, &xc));
  PetscFunctionReturn(0);
}

/* The recovered fields (fe_estimate.h): the stress, and the viscoplastic strain (Voigt, engineering shears). */
typedef enum { SRC_STRESS, SRC_EVP } Source;

/* Component j of the field at quadrature point q of local cell c. */
static PetscReal point_value(const FeProblem *p, PetscInt c, PetscInt q, PetscInt j, Source src) {
  const PetscReal *st = &p->pts.state[SV(p, c + p->space.cStart, q) * p->pts.nsv];
  return src == SRC_STRESS ? st[ST_STRESS + j] : material_quantity(&p->pts.mat, st + ST_STATEV, MATERIAL_EVP, (int)j);
}

/* The cell's field as a linear function a0 + a . (x - x_q0), fitted by least squares through its quadrature
   points (exact through the d + 1 points of the P2 rule; the constant mean with one point, P1); evaluated at
   the point x into s[6]. */
static void cell_field_at(FeProblem *p, PetscInt c, const CellGeom *g, const PetscReal *x, Source src, PetscReal s[6]) {
  const PetscInt dim = g->dim, nq = p->space.nq, m = dim + 1;
  for (PetscInt j = 0; j < 6; j++) {
    PetscReal A[16] = {0}, b[4] = {0}, mean = 0, wsum = 0;
    for (PetscInt q = 0; q < nq; q++) {
      const PetscReal w = p->space.qweights[q], v = point_value(p, c, q, j, src);
      PetscReal       row[4] = {1, 0, 0, 0};
      for (PetscInt i = 0; i < dim; i++) row[1 + i] = g->xq[q][i] - g->xq[0][i];
      for (PetscInt r = 0; r < m; r++) {
        for (PetscInt k = 0; k < m; k++) A[r * m + k] += w * row[r] * row[k];
        b[r] += w * row[r] * v;
      }
      mean += w * v, wsum += w;
    }
    if (nq < m || !solve_small(m, A, b)) { s[j] = mean / wsum; continue; }
    s[j] = b[0];
    for (PetscInt i = 0; i < dim; i++) s[j] += b[1 + i] * (x[i] - g->xq[0][i]);
  }
}

/* The barycentric coordinates of x in the simplex of the vertices xv. */
static void barycentric(const CellGeom *g, const PetscReal *x, PetscReal lam[4]) {
  const PetscInt d = g->dim;
  PetscReal      A[9], b[3];
  for (PetscInt i = 0; i < d; i++) {
    for (PetscInt k = 0; k < d; k++) A[i * d + k] = g->xv[k + 1][i] - g->xv[0][i];
    b[i] = x[i] - g->xv[0][i];
  }
  if (!solve_small(d, A, b)) b[0] = b[1] = b[2] = 0;
  lam[0] = 1;
  for (PetscInt k = 0; k < d; k++) lam[k + 1] = b[k], lam[0] -= b[k];
}

/* The tensor's own norm squared (fe_estimate.h): a stress's shear components count twice, a strain's engineering
   shears (twice the tensor's) half. */
static PetscReal tensor_norm2(const PetscReal s[6], PetscInt ntens, Source src) {
  PetscReal n = 0;
  for (PetscInt j = 0; j < ntens; j++) n += (j < 3 ? 1 : src == SRC_STRESS ? 2 : 0.5) * s[j] * s[j];
  return n;
}

/* The cells' values at each vertex in L combined over every rank (op: MPI_SUM, or MPI_MAX, which DMLocalToGlobal
   lacks) by the section's star forest, and the result back in every rank's L. */
static PetscErrorCode combine_at_vertices(FeProblem *p, Vec L, MPI_Op op) {
  Vec                G;
  PetscSF            sf;
  const PetscScalar *l;
  PetscScalar       *g;
  PetscFunctionBeginUser;
  PetscCall(DMGetSectionSF(p->est.dmv, &sf));
  PetscCall(DMGetGlobalVector(p->est.dmv, &G));
  PetscCall(VecZeroEntries(G));
  PetscCall(VecGetArrayRead(L, &l));
  PetscCall(VecGetArray(G, &g));
  PetscCall(PetscSFReduceBegin(sf, MPIU_SCALAR, l, g, op));
  PetscCall(PetscSFReduceEnd(sf, MPIU_SCALAR, l, g, op));
  PetscCall(VecRestoreArray(G, &g));
  PetscCall(VecRestoreArrayRead(L, &l));
  PetscCall(DMGlobalToLocal(p->est.dmv, G, INSERT_VALUES, L));
  PetscCall(DMRestoreGlobalVector(p->est.dmv, &G));
  PetscFunctionReturn(0);
}


/* The recovery indicator of one field into eta (per local cell): sigma* from the cells' vertex values, then
   eta_K = (int_K |sigma* - sigma_h|^2)^(1/2) (fe_estimate.h). */
static PetscErrorCode recover(FeProblem *p, Source src, PetscReal *eta) {
  const PetscInt ncell = p->space.cEnd - p->space.cStart, ntens = p->space.dim == 3 ? 6 : 4;
  Vec            L;
  PetscScalar   *a;
  CellGeom       g;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->est.dmv, &L));
  PetscCall(VecZeroEntries(L));
  PetscCall(VecGetArray(L, &a));
  for (PetscInt c = 0; c < ncell; c++) { /* each cell's field at its vertices, weighted by its volume */
    PetscInt  off[4], nv;
    PetscReal s[6];
    PetscCall(cell_geometry(p, c + p->space.cStart, &g));
    PetscCall(cell_vertex_offsets(p, c + p->space.cStart, off, &nv));
    for (PetscInt v = 0; v < nv; v++) {
      cell_field_at(p, c, &g, g.xv[v], src, s);
      for (PetscInt j = 0; j < 6; j++) a[off[v] + j] += g.vol * s[j];
      a[off[v] + 6] += g.vol;
    }
  }
  PetscCall(VecRestoreArray(L, &a));
  PetscCall(combine_at_vertices(p, L, MPI_SUM));
  PetscCall(VecGetArray(L, &a));
  for (PetscInt c = 0; c < ncell; c++) { /* eta_K^2 = int_K |sigma* - sigma_h|^2 */
    PetscInt  off[4], nv;
    PetscReal e2 = 0;
    PetscCall(cell_geometry(p, c + p->space.cStart, &g));
    PetscCall(cell_vertex_offsets(p, c + p->space.cStart, off, &nv));
    for (PetscInt q = 0; q < p->space.nq; q++) {
      PetscReal lam[4], d[6];
      barycentric(&g, g.xq[q], lam);
      for (PetscInt j = 0; j < 6; j++) {
        d[j] = -point_value(p, c, q, j, src);
        for (PetscInt v = 0; v < nv; v++) d[j] += lam[v] * PetscRealPart(a[off[v] + j]) / PetscRealPart(a[off[v] + 6]);
      }
      e2 += p->space.wdetJ[SV(p, c + p->space.cStart, q)] * tensor_norm2(d, ntens, src);
    }
    eta[c] = PetscSqrtReal(e2);
  }
  PetscCall(VecRestoreArray(L, &a));
  PetscCall(DMRestoreLocalVector(p->est.dmv, &L));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_estimate_stress_at(FeProblem *p, PetscInt cell, const PetscReal x[], PetscReal s[6]) {
  CellGeom g;
  PetscFunctionBeginUser;
  PetscCall(cell_geometry(p, cell, &g));
  cell_field_at(p, cell - p->space.cStart, &g, x, SRC_STRESS, s);
  PetscFunctionReturn(0);
}

void fe_estimate_add_surface(FeProblem *p, PetscInt cell, PetscReal e2) {
  if (p->est.surf) p->est.surf[cell - p->space.cStart] += e2;
}

PetscErrorCode fe_estimate_update(FeProblem *p, PetscBool report) {
  const PetscInt ncell = p->space.cEnd - p->space.cStart;
  PetscReal     *eta_e, norm2[2] = {0, 0};
  PetscFunctionBeginUser;
  PetscCall(vertex_dm(p));
  if (!p->est.eta) PetscCall(PetscCalloc3(ncell + 1, &p->est.eta, ncell + 1, &p->est.eta_max, ncell + 1, &p->est.surf));
  PetscCall(PetscMalloc1(ncell + 1, &eta_e));
  PetscCall(recover(p, SRC_STRESS, p->est.eta));
  PetscCall(PetscArrayzero(p->est.surf, ncell + 1));
  if (p->est.surface) { /* a boundary's traction residual joins the stress's share (fe_estimate.h) */
    PetscCall(p->est.surface(p->est.surface_ctx, p));
    for (PetscInt c = 0; c < ncell; c++) p->est.eta[c] = PetscSqrtReal(p->est.eta[c] * p->est.eta[c] + p->est.surf[c]);
  }
  if (material_quantity_size(&p->pts.mat, MATERIAL_EVP) == 6) PetscCall(recover(p, SRC_EVP, eta_e));
  else PetscCall(PetscArrayzero(eta_e, ncell + 1));
  for (PetscInt c = 0; c < ncell; c++) norm2[0] += p->est.eta[c] * p->est.eta[c], norm2[1] += eta_e[c] * eta_e[c];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, norm2, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)p->space.dm)));
  /* the two fields' shares, each relative to its own norm, in the stress indicator's units (fe_estimate.h) */
  if (norm2[1] > 0)
    for (PetscInt c = 0; c < ncell; c++) {
      const PetscReal s = norm2[0] > 0 ? p->est.eta[c] * p->est.eta[c] / norm2[0] : 0, e = eta_e[c] * eta_e[c] / norm2[1];
      p->est.eta[c] = PetscSqrtReal(norm2[0] > 0 ? norm2[0] : 1) * PetscSqrtReal(s + e);
    }
  if (report) {
    for (PetscInt c = 0; c < ncell; c++) p->est.eta_max[c] = PetscMax(p->est.eta_max[c], p->est.eta[c]);
    p->est.nupdates++;
  }
  PetscCall(PetscFree(eta_e));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_estimate_norm(FeProblem *p, PetscReal *norm) {
  PetscReal s = 0;
  PetscFunctionBeginUser;
  for (PetscInt c = 0; p->est.eta && c < p->space.cEnd - p->space.cStart; c++) s += p->est.eta_max[c] * p->est.eta_max[c];
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &s, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)p->space.dm)));
  *norm = PetscSqrtReal(s);
  PetscFunctionReturn(0);
}

/* The size of a cell of volume vol: the edge of the regular simplex of that volume (gmsh's size is an edge
   length). */
static PetscReal cell_size(PetscInt dim, PetscReal vol) {
  return dim == 2 ? PetscSqrtReal(4 * vol / PetscSqrtReal(3.0)) : PetscCbrtReal(6 * PetscSqrtReal(2.0) * vol);
}

/* The new size of every local cell (fe_estimate.h), and the predicted number of cells of all ranks. */
static PetscErrorCode new_sizes(FeProblem *p, PetscReal target, PetscReal *hnew, PetscReal *predicted) {
  const PetscInt  ncell = p->space.cEnd - p->space.cStart, d = p->space.dim;
  const PetscReal s     = p->space.order + 0.5 * d, e = d / s;
  PetscReal       sum = 0, eta_t;
  MPI_Comm        comm = PetscObjectComm((PetscObject)p->space.dm);
  CellGeom        g;
  PetscFunctionBeginUser;
  for (PetscInt c = 0; c < ncell; c++) sum += PetscPowReal(p->est.eta_max[c], e);
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPIU_SUM, comm));
  eta_t      = PetscPowReal(sum / target, 1 / e);
  *predicted = 0;
  for (PetscInt c = 0; c < ncell; c++) {
    PetscCall(cell_geometry(p, c + p->space.cStart, &g));
    const PetscReal h     = cell_size(d, g.vol), eta = p->est.eta_max[c];
    const PetscReal ratio = eta > 0 ? PetscPowReal(eta_t / eta, 1 / s) : 2;
    hnew[c]               = h * PetscMin(PetscMax(ratio, 0.25), 2.0);
    *predicted += PetscPowReal(h / hnew[c], d);
  }
  PetscCall(MPIU_Allreduce(MPI_IN_PLACE, predicted, 1, MPIU_REAL, MPIU_SUM, comm));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_estimate_write_sizes(FeProblem *p, PetscReal target_cells, const char *path, PetscReal *predicted) {
  const PetscInt ncell = p->space.cEnd - p->space.cStart, d = p->space.dim;
  PetscReal     *hnew;
  Vec            L;
  PetscScalar   *a;
  PetscViewer    vw;
  CellGeom       g;
  PetscFunctionBeginUser;
  PetscCheck(p->est.eta && p->est.nupdates > 0, PetscObjectComm((PetscObject)p->space.dm), PETSC_ERR_ORDER, "no error indicator yet: the run wrote no fields");
  PetscCall(PetscMalloc1(ncell + 1, &hnew));
  PetscCall(new_sizes(p, target_cells, hnew, predicted));
  PetscCall(DMGetLocalVector(p->est.dmv, &L));
  PetscCall(VecZeroEntries(L));
  PetscCall(VecGetArray(L, &a));
  for (PetscInt c = 0; c < ncell; c++) { /* 1/h at the vertices: the largest of the cells' (the smallest size) */
    PetscInt off[4], nv;
    PetscCall(cell_vertex_offsets(p, c + p->space.cStart, off, &nv));
    for (PetscInt v = 0; v < nv; v++) a[off[v]] = PetscMax(PetscRealPart(a[off[v]]), 1 / hnew[c]);
  }
  PetscCall(VecRestoreArray(L, &a));
  PetscCall(combine_at_vertices(p, L, MPI_MAX));
  PetscCall(PetscViewerASCIIOpen(PetscObjectComm((PetscObject)p->space.dm), path, &vw));
  PetscCall(PetscViewerASCIIPrintf(vw, "// The element sizes made from the error indicator (fe_estimate.h): %g cells predicted\nView \"size\" {\n", (double)*predicted));
  PetscCall(PetscViewerASCIIPushSynchronized(vw));
  PetscCall(VecGetArray(L, &a));
  for (PetscInt c = 0; c < ncell; c++) {
    PetscInt off[4], nv;
    PetscCall(cell_geometry(p, c + p->space.cStart, &g));
    PetscCall(cell_vertex_offsets(p, c + p->space.cStart, off, &nv));
    PetscCall(PetscViewerASCIISynchronizedPrintf(vw, "%s(", d == 2 ? "ST" : "SS"));
    for (PetscInt v = 0; v < nv; v++)
      PetscCall(PetscViewerASCIISynchronizedPrintf(vw, "%s%.12g,%.12g,%.12g", v ? "," : "", (double)g.xv[v][0], (double)g.xv[v][1], d == 3 ? (double)g.xv[v][2] : 0.0));
    PetscCall(PetscViewerASCIISynchronizedPrintf(vw, "){"));
    for (PetscInt v = 0; v < nv; v++) PetscCall(PetscViewerASCIISynchronizedPrintf(vw, "%s%.6g", v ? "," : "", 1 / (double)PetscRealPart(a[off[v]])));
    PetscCall(PetscViewerASCIISynchronizedPrintf(vw, "};\n"));
  }
  PetscCall(VecRestoreArray(L, &a));
  PetscCall(PetscViewerFlush(vw));
  PetscCall(PetscViewerASCIIPopSynchronized(vw));
  PetscCall(PetscViewerASCIIPrintf(vw, "};\n"));
  PetscCall(PetscViewerDestroy(&vw));
  PetscCall(DMRestoreLocalVector(p->est.dmv, &L));
  PetscCall(PetscFree(hnew));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_estimate_destroy(FeProblem *p) {
  PetscFunctionBeginUser;
  PetscCall(PetscFree3(p->est.eta, p->est.eta_max, p->est.surf));
  PetscCall(DMDestroy(&p->est.dmv));
  p->est.nupdates = 0;
  PetscFunctionReturn(0);
}
