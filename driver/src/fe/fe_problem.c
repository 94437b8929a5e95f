#include "fe_problem.h"
#include "fe_estimate.h"
#include "../io/log_events.h"


#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <time.h>

/* The area of a boundary face and the direction n of its load: the outward normal (a pressure, t = -p n), or for a
 * traction along axis (>= 0) -e_axis (the force is +t, written as -(-e_axis)). */
static PetscErrorCode face_load_direction(FeProblem *p, PetscInt face, PetscInt axis, PetscReal *area, PetscReal n[3]) {
  DM              dm = p->space.dm;
  const PetscInt *support;
  PetscReal       fc[3], cc[3], vol, out = 0;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetSupport(dm, face, &support));
  PetscCall(DMPlexComputeCellGeometryFVM(dm, face, area, fc, n));
  PetscCall(DMPlexComputeCellGeometryFVM(dm, support[0], &vol, cc, NULL));
  for (PetscInt d = 0; d < p->space.dim; d++) out += (fc[d] - cc[d]) * n[d];
  if (out < 0)
    for (PetscInt d = 0; d < p->space.dim; d++) n[d] = -n[d];
  if (axis >= 0) /* a unit traction along the axis: the force is +t, written here as -(-e_axis) */
    for (PetscInt d = 0; d < p->space.dim; d++) n[d] = d == axis ? -1.0 : 0.0;
  PetscFunctionReturn(0);
}

/* An edge: nodal forces of t = -p n by 3-point Gauss on s in [0, 1] (exact here), with the weight of the
 * kinematics: the thickness (plane strain) or 2 pi r (axisymmetric); added to the local array a. */
static PetscErrorCode edge_load(FeProblem *p, PetscSection s, PetscInt face, PetscReal area, const PetscReal n[], PetscScalar *a) {
  DM              dm = p->space.dm;
  Vec             coords;
  PetscSection    cs;
  PetscScalar    *xe = NULL;
  PetscInt        nx, offa, offb, offm = -1, ndof;
  const PetscInt *cone;
  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMPlexVecGetClosure(dm, cs, coords, face, &nx, &xe));
  PetscCall(DMPlexGetCone(dm, face, &cone));
  PetscCall(PetscSectionGetOffset(s, cone[0], &offa));
  PetscCall(PetscSectionGetOffset(s, cone[1], &offb));
  PetscCall(PetscSectionGetDof(s, face, &ndof));
  if (ndof) PetscCall(PetscSectionGetOffset(s, face, &offm));
  static const PetscReal gs[3] = {0.1127016653792583, 0.5, 0.8872983346207417}, gw[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  for (int g = 0; g < 3; g++) {
    PetscReal sg = gs[g], r = (1 - sg) * PetscRealPart(xe[0]) + sg * PetscRealPart(xe[2]);
    PetscReal w = gw[g] * area * fe_space_weight(&p->space, r); /* 2D: 2 pi r or the thickness */
    PetscReal Na = p->space.order == 1 ? 1 - sg : (1 - sg) * (1 - 2 * sg), Nb = p->space.order == 1 ? sg : sg * (2 * sg - 1);
    PetscReal Nm = p->space.order == 1 ? 0 : 4 * sg * (1 - sg);
    for (PetscInt d = 0; d < 2; d++) {
      a[offa + d] -= w * Na * n[d];
      a[offb + d] -= w * Nb * n[d];
      if (offm >= 0) a[offm + d] -= w * Nm * n[d];
    }
  }
  PetscCall(DMPlexVecRestoreClosure(dm, cs, coords, face, &nx, &xe));
  PetscFunctionReturn(0);
}

/* A flat triangle: P1 gives A/3 to each vertex, P2 A/3 to each edge node and 0 to the corners; added to a. */
static PetscErrorCode triangle_load(FeProblem *p, PetscSection s, PetscInt face, PetscReal area, const PetscReal n[], PetscScalar *a) {
  DM        dm      = p->space.dm;
  PetscInt *closure = NULL, nclosure;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetTransitiveClosure(dm, face, PETSC_TRUE, &nclosure, &closure));
  for (PetscInt j = 0; j < nclosure; j++) {
    PetscInt pt = closure[2 * j], depth, ndof, off;
    PetscCall(DMPlexGetPointDepth(dm, pt, &depth));
    PetscCall(PetscSectionGetDof(s, pt, &ndof));
    if (!ndof) continue;
    PetscReal share = p->space.order == 1 ? (depth == 0 ? area / 3 : 0) : (depth == 1 ? area / 3 : 0);
    PetscCall(PetscSectionGetOffset(s, pt, &off));
    for (PetscInt d = 0; d < p->space.dim; d++) a[off + d] -= share * n[d];
  }
  PetscCall(DMPlexRestoreTransitiveClosure(dm, face, PETSC_TRUE, &nclosure, &closure));
  PetscFunctionReturn(0);
}

/* Consistent nodal forces of a unit pressure on the boundary faces of a group: t = -p n (n outward).
 * Faces of simplices are flat: in 3D closed forms on triangles; in 2D Gauss quadrature on the edges
 * (the axisymmetric weight 2 pi r varies along an edge). */
PetscErrorCode fe_problem_unit_load(FeProblem *p, const char *load, Vec *f) {
  DM           dm = p->space.dm;
  DMLabel      label;
  char         group[64];
  PetscInt     axis = -1; /* a pressure (t = -p n); or 'GROUP.x', '.y', '.z': a traction along that axis */
  PetscCall(PetscStrncpy(group, load, sizeof group));
  {
    size_t len = strlen(group);
    if (len > 2 && group[len - 2] == '.' && strchr("xyz", group[len - 1])) {
      axis             = group[len - 1] - 'x';
      group[len - 2]   = '\0';
    }
  }
  PetscSection s;
  Vec          floc;
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCheck(label, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG,
             "pressure: the mesh has no physical group '%s'", group);
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(DMGetLocalVector(dm, &floc));
  PetscCall(VecZeroEntries(floc));
  PetscCall(VecGetArray(floc, &a));
  PetscInt fStart, fEnd;
  PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
  IS              pointIS;
  const PetscInt *points;
  PetscInt        npoints;
  PetscCall(fe_label_points(label, &pointIS));
  PetscCall(ISGetLocalSize(pointIS, &npoints));
  PetscCall(ISGetIndices(pointIS, &points));
  for (PetscInt k = 0; k < npoints; k++) {
    PetscInt  face = points[k], nsupport;
    PetscReal area, n[3];
    if (face < fStart || face >= fEnd) continue; /* vertices and edges of the group */
    PetscCall(DMPlexGetSupportSize(dm, face, &nsupport));
    if (nsupport != 1) continue;                 /* an interior face: no load */
    PetscCall(face_load_direction(p, face, axis, &area, n));
    if (p->space.dim == 2) PetscCall(edge_load(p, s, face, area, n, a));
    else PetscCall(triangle_load(p, s, face, area, n, a));
  }
  PetscCall(ISRestoreIndices(pointIS, &points));
  PetscCall(ISDestroy(&pointIS));
  PetscCall(fe_constraint_to_frame(&p->space.con, a, NULL));
  PetscCall(VecRestoreArray(floc, &a));
  PetscCall(DMCreateGlobalVector(dm, f));
  PetscCall(VecZeroEntries(*f));
  PetscCall(DMLocalToGlobal(dm, floc, ADD_VALUES, *f));
  PetscCall(DMRestoreLocalVector(dm, &floc));
  PetscFunctionReturn(0);
}

/* The element kernels (fe_kernel.h) take the closure node-major, basis b = scalar basis b / dim, component
 * b % dim: check that PETSc's vector Lagrange space is so (its tabulation at the first point). */
static PetscErrorCode check_vector_layout(const FeProblem *p) {
  const PetscInt   nb = p->space.nb, nc = p->space.dim;
  const PetscReal *T  = p->space.tab->T[0];
  PetscFunctionBeginUser;
  for (PetscInt b = 0; b < nb; b++)
    for (PetscInt cc = 0; cc < nc; cc++) {
      PetscReal v = T[b * nc + cc], s = T[(b - b % nc) * nc];
      PetscCheck(cc == b % nc ? PetscAbsReal(v - s) <= 1e-12 : v == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                 "the vector Lagrange basis is not node-major (basis %d, component %d)", (int)b, (int)cc);
    }
  PetscFunctionReturn(0);
}

/* Physical gradients of the scalar basis at quadrature point q (ns x dim) from the reference derivatives and the
 * inverse Jacobian: g[a][d] = sum_e dphi_a/dxi_e dxi_e/dx_d. */
static void basis_gradients(const FeProblem *p, PetscInt q, const PetscReal *invJ, PetscReal *g) {
  const PetscInt   nb = p->space.nb, nc = p->space.dim, dim = p->space.dim;
  const PetscReal *D  = &p->space.tab->T[1][q * nb * nc * dim];
  for (PetscInt a = 0; a < p->space.ns; a++)
    for (PetscInt d = 0; d < dim; d++) {
      PetscReal s = 0;
      for (PetscInt e = 0; e < dim; e++) s += D[(a * nc * nc) * dim + e] * invJ[e * dim + d];
      g[a * dim + d] = s;
    }
}

/* The closure dofs of each cell in the local vector and its rows in the global one, once: the residual gathers and
 * scatters with them. */
static PetscErrorCode cell_dofs_setup(FeProblem *p) {
  PetscSection ls, gs;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalSection(p->space.dm, &ls));
  PetscCall(DMGetGlobalSection(p->space.dm, &gs));
  PetscCall(PetscMalloc2((p->space.cEnd - p->space.cStart) * p->space.nb, &p->space.cell_dofs, (p->space.cEnd - p->space.cStart) * p->space.nb, &p->space.cell_rows));
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    PetscInt n, *idx = NULL;
    PetscCall(DMPlexGetClosureIndices(p->space.dm, ls, ls, c, PETSC_TRUE, &n, &idx, NULL, NULL));
    PetscCheck(n == p->space.nb, PETSC_COMM_SELF, PETSC_ERR_PLIB, "closure of cell %d has %d dofs, expected %d", (int)c, (int)n, (int)p->space.nb);
    for (PetscInt b = 0; b < n; b++) p->space.cell_dofs[(c - p->space.cStart) * p->space.nb + b] = idx[b] < 0 ? -(idx[b] + 1) : idx[b];
    PetscCall(DMPlexRestoreClosureIndices(p->space.dm, ls, ls, c, PETSC_TRUE, &n, &idx, NULL, NULL));
    PetscCall(DMPlexGetClosureIndices(p->space.dm, ls, gs, c, PETSC_TRUE, &n, &idx, NULL, NULL));
    for (PetscInt b = 0; b < n; b++) p->space.cell_rows[(c - p->space.cStart) * p->space.nb + b] = idx[b];
    PetscCall(DMPlexRestoreClosureIndices(p->space.dm, ls, gs, c, PETSC_TRUE, &n, &idx, NULL, NULL));
  }
  PetscFunctionReturn(0);
}

/* Per quadrature point, once: the basis gradients (and N/r, axisymmetric), the volume weight (plane strain per its
 * thickness; axisymmetric 2 pi r, x1 = r) and the radius; an inverted cell or a point at r <= 0 (axisymmetric) is
 * refused on every rank. */
static PetscErrorCode point_geometry_setup(FeProblem *p) {
  PetscReal v0[3 * 64], J[9 * 64], invJ[9 * 64], detJ[64], rmin = PETSC_MAX_REAL;
  PetscFunctionBeginUser;
  PetscCheck(p->space.nq <= 64, PETSC_COMM_SELF, PETSC_ERR_SUP, "too many quadrature points");
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    PetscCall(DMPlexComputeCellGeometryFEM(p->space.dm, c, p->space.quad, v0, J, invJ, detJ));
    for (PetscInt q = 0; q < p->space.nq; q++) {
      PetscCheck(detJ[q] > 0, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG, "cell %d is inverted (det J = %g)", (int)c, (double)detJ[q]);
      PetscReal r = v0[q * p->space.dim], scale = fe_space_weight(&p->space, r);
      rmin = PetscMin(rmin, r);
      p->space.radius[SV(p, c, q)] = r;
      basis_gradients(p, q, &invJ[q * p->space.dim * p->space.dim], &p->space.grad[SV(p, c, q) * p->space.ns * p->space.dim]);
      if (p->space.kin == KIN_AXISYMMETRIC)
        for (PetscInt a = 0; a < p->space.ns; a++) p->space.shape_r[SV(p, c, q) * p->space.ns + a] = p->space.tab->T[0][(q * p->space.nb + a * p->space.dim) * p->space.dim] / r;
      p->space.wdetJ[SV(p, c, q)] = p->space.qweights[q] * detJ[q] * scale;
    }
  }
  if (p->space.kin == KIN_AXISYMMETRIC) { /* on every rank, so that all stop together */
    PetscCall(MPIU_Allreduce(MPI_IN_PLACE, &rmin, 1, MPIU_REAL, MPIU_MIN, PetscObjectComm((PetscObject)p->space.dm)));
    PetscCheck(rmin > 0, PetscObjectComm((PetscObject)p->space.dm), PETSC_ERR_ARG_WRONG,
               "axisymmetric: a quadrature point has r = x = %g <= 0: the mesh must lie in x >= 0 (x is the radius)", (double)rmin);
  }
  PetscFunctionReturn(0);
}

/* The Lagrange space of the given order on the mesh, with the smallest symmetric rule exact for B^T D B (degree
 * 2(k-1)): 1 point for P1, 4 for P2. */
static PetscErrorCode space_setup(FeProblem *p, const FeFixed *fixed, PetscInt nfixed) {
  PetscQuadrature q;
  PetscFunctionBeginUser;
  PetscCall(PetscFECreateLagrange(PetscObjectComm((PetscObject)p->space.dm), p->space.dim, p->space.dim, PETSC_TRUE, p->space.order, 2 * (p->space.order - 1), &p->space.fe));
  PetscCall(PetscObjectSetName((PetscObject)p->space.fe, "displacement"));
  PetscCall(PetscDTSimplexQuadrature(p->space.dim, PetscMax(2 * (p->space.order - 1), 1), PETSCDTSIMPLEXQUAD_MINSYM, &q));
  PetscCall(PetscFESetQuadrature(p->space.fe, q));
  PetscCall(PetscQuadratureDestroy(&q));
  PetscCall(DMSetField(p->space.dm, 0, NULL, (PetscObject)p->space.fe));
  PetscCall(DMCreateDS(p->space.dm));
  PetscCall(fe_constraint_setup(&p->space.con, p->space.dm, p->space.fe, fixed, nfixed)); /* the section with its constrained components */
  PetscCall(PetscFEGetQuadrature(p->space.fe, &p->space.quad));
  PetscCall(PetscQuadratureGetData(p->space.quad, NULL, NULL, &p->space.nq, NULL, &p->space.qweights));
  PetscCall(PetscFEGetCellTabulation(p->space.fe, 1, &p->space.tab));
  p->space.nb = p->space.tab->Nb;
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_setup(FeProblem *p, DM dm, Kinematics kin, PetscReal thickness, PetscInt order,
                                const UmatMaterial *mat, const FeFixed *fixed,
                                PetscInt nfixed, const char pressure_groups[][64], PetscInt npressure) {
  PetscFunctionBeginUser;
  p->space.dm        = dm;
  p->space.order     = order;
  p->pts.mat       = *mat;
  p->space.kin       = kin;
  p->space.thickness = thickness;
  PetscCall(DMGetDimension(dm, &p->space.dim));
  PetscCheck(p->space.dim == (kin == KIN_3D ? 3 : 2), PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG,
             "the mesh is %dD but the kinematics (%s) need a %dD mesh", (int)p->space.dim,
             kin == KIN_3D ? "3d" : kin == KIN_PLANE_STRAIN ? "plane_strain" : "axisymmetric", kin == KIN_3D ? 3 : 2);
  PetscCheck(mat->ntens == (kin == KIN_3D ? 6 : 4), PetscObjectComm((PetscObject)dm), PETSC_ERR_PLIB, "NTENS");
  PetscCall(space_setup(p, fixed, nfixed));
  PetscCall(DMPlexGetHeightStratum(dm, 0, &p->space.cStart, &p->space.cEnd));
  p->space.npoint = (p->space.cEnd - p->space.cStart) * p->space.nq;
  p->pts.nsv    = ST_STATEV + mat->nstatv;
  PetscCall(PetscCalloc3(p->space.npoint * p->pts.nsv, &p->pts.state, p->space.npoint * p->pts.nsv, &p->pts.trial, p->space.npoint * 36, &p->pts.ddsdde));
  PetscCall(PetscMalloc1(p->space.cEnd - p->space.cStart, &p->pts.phi));
  p->space.ns = p->space.nb / p->space.dim;
  PetscCall(check_vector_layout(p));
  PetscCall(PetscMalloc4(p->space.npoint * p->space.ns * p->space.dim, &p->space.grad, kin == KIN_AXISYMMETRIC ? p->space.npoint * p->space.ns : 0, &p->space.shape_r, p->space.npoint, &p->space.wdetJ,
                         p->space.npoint, &p->space.radius));
  PetscCall(cell_dofs_setup(p));
  PetscCall(point_geometry_setup(p));
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) p->pts.phi[c - p->space.cStart] = material_phi(mat);
  p->loads.npressure = npressure;
  for (PetscInt g = 0; g < npressure; g++) {
    PetscCall(PetscStrncpy(p->loads.pressure_group[g], pressure_groups[g], 64));
    PetscCall(fe_problem_unit_load(p, pressure_groups[g], &p->loads.unit_force[g]));
    p->loads.pressure[g] = 0;
  }
  PetscCall(DMCreateGlobalVector(dm, &p->loads.fext));
  PetscCall(VecZeroEntries(p->loads.fext));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_destroy(FeProblem *p) {
  PetscFunctionBeginUser;
  for (PetscInt g = 0; g < p->loads.npressure; g++) PetscCall(VecDestroy(&p->loads.unit_force[g]));
  PetscCall(VecDestroy(&p->loads.fext));
  PetscCall(VecDestroy(&p->pts.ddsdde_u));
  PetscCall(PetscFree3(p->pts.state, p->pts.trial, p->pts.ddsdde));
  PetscCall(PetscFree(p->pts.phi));
  PetscCall(PetscFree4(p->space.grad, p->space.shape_r, p->space.wdetJ, p->space.radius));
  PetscCall(PetscFree2(p->space.cell_dofs, p->space.cell_rows));
  PetscCall(fe_constraint_destroy(&p->space.con));
  PetscCall(PetscFree(p->pts.devp_prev));
  PetscCall(PetscFree(p->coo_v));
  PetscCall(VecDestroy(&p->pts.ddsdde_u));
  PetscCall(PetscFEDestroy(&p->space.fe));
  PetscCall(fe_estimate_destroy(p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_set_initial_stress(FeProblem *p, const PetscReal stress0[6]) {
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < p->space.npoint; k++) {
    PetscReal *st = &p->pts.state[k * p->pts.nsv];
    PetscCall(PetscArrayzero(st, p->pts.nsv));
    PetscCall(PetscArraycpy(st + ST_STRESS, stress0, 6));
  }
  PetscCall(PetscArraycpy(p->pts.trial, p->pts.state, p->space.npoint * p->pts.nsv));
  PetscFunctionReturn(0);
}

/* splitmix64: a counter-based generator, so phi depends on (seed, cell centroid) only. */
static uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

static int cmp_sample(const void *a, const void *b) { /* order samples by their coordinates */
  const PetscReal *x = (const PetscReal *)a, *y = (const PetscReal *)b;
  for (int d = 0; d < 4; d++)
    if (x[d] != y[d]) return x[d] < y[d] ? -1 : 1;
  return 0;
}

PetscErrorCode fe_problem_set_phi(FeProblem *p, PetscReal mean, PetscReal std, PetscReal lo, PetscReal hi,
                                  PetscInt seed, PetscReal correlation) {
  MPI_Comm   comm = PetscObjectComm((PetscObject)p->space.dm);
  PetscInt   nloc = p->space.cEnd - p->space.cStart;
  PetscReal *z, *xc;
  PetscFunctionBeginUser;
  PetscCall(PetscMalloc2(nloc, &z, 3 * nloc, &xc));
  for (PetscInt c = p->space.cStart; c < p->space.cEnd; c++) {
    PetscReal vol, x[3] = {0, 0, 0}, v = mean;
    PetscCall(DMPlexComputeCellGeometryFVM(p->space.dm, c, &vol, x, NULL));
    for (PetscInt d = 0; d < 3; d++) xc[3 * (c - p->space.cStart) + d] = x[d];
    uint64_t key = mix64((uint64_t)seed);
    for (PetscInt d = 0; d < p->space.dim; d++) key = mix64(key ^ (uint64_t)(int64_t)llround(x[d] * 1e6));
    for (int draw = 0; draw < 1000; draw++) { /* Box-Muller; uncorrelated: redrawn until within [lo, hi] */
      uint64_t  a = mix64(key + 2 * (uint64_t)draw), b = mix64(key + 2 * (uint64_t)draw + 1);
      PetscReal u1 = ((a >> 11) + 0.5) / 9007199254740992.0, u2 = ((b >> 11) + 0.5) / 9007199254740992.0;
      z[c - p->space.cStart] = sqrt(-2 * log(u1)) * cos(2 * M_PI * u2);
      v                = mean + std * z[c - p->space.cStart];
      if (correlation > 0 || std == 0 || (v >= lo && v <= hi)) break;
    }
    p->pts.phi[c - p->space.cStart] = PetscMin(PetscMax(v, lo), hi);
  }
  if (correlation > 0 && std > 0) {
    /* A correlated field: white noise smoothed by a Gaussian kernel of length l and scaled back to
     * unit variance, g_i = sum_j w_ij z_j / sqrt(sum_j w_ij^2), w_ij = exp(-|x_i - x_j|^2 / (2 l^2)),
     * over the cells of all ranks in a fixed (coordinate) order, so the field does not depend on the
     * partition; phi = mean + std g, clipped to [lo, hi]. */
    PetscMPIInt size, n4 = (PetscMPIInt)(4 * nloc), *counts, *displs, total = 0;
    PetscReal  *mine, *all;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCall(PetscMalloc3(size, &counts, size, &displs, 4 * nloc + 1, &mine));
    for (PetscInt i = 0; i < nloc; i++) {
      for (int d = 0; d < 3; d++) mine[4 * i + d] = xc[3 * i + d];
      mine[4 * i + 3] = z[i];
    }
    PetscCallMPI(MPI_Allgather(&n4, 1, MPI_INT, counts, 1, MPI_INT, comm));
    for (PetscMPIInt r = 0; r < size; r++) displs[r] = total, total += counts[r];
    PetscCall(PetscMalloc1(total + 1, &all));
    PetscCallMPI(MPI_Allgatherv(mine, n4, MPIU_REAL, all, counts, displs, MPIU_REAL, comm));
    qsort(all, (size_t)(total / 4), 4 * sizeof(PetscReal), cmp_sample);
    for (PetscInt i = 0; i < nloc; i++) {
      PetscReal num = 0, den = 0;
      for (PetscMPIInt j = 0; j < total / 4; j++) {
        PetscReal d2 = 0;
        for (int d = 0; d < 3; d++) d2 += PetscSqr(xc[3 * i + d] - all[4 * j + d]);
        PetscReal w = exp(-d2 / (2 * correlation * correlation));
        num += w * all[4 * j + 3];
        den += w * w;
      }
      p->pts.phi[i] = PetscMin(PetscMax(mean + std * num / PetscSqrtReal(den), lo), hi);
    }
    PetscCall(PetscFree(all));
    PetscCall(PetscFree3(counts, displs, mine));
  }
  PetscCall(PetscFree2(z, xc));
  PetscFunctionReturn(0);
}

PetscReal fe_problem_stiffness_scale(const FeProblem *p) {
  PetscReal E = 0;
  for (PetscInt k = 0; k < p->space.npoint; k++) E = PetscMax(E, p->pts.ddsdde[k * 36]);
  return E;
}

PetscErrorCode fe_problem_set_pressures(FeProblem *p, PetscInt n, const PetscReal pressure[]) {
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < n; k++) p->loads.pressure[k] = pressure[k];
  PetscCall(fe_problem_update_loads(p));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_update_loads(FeProblem *p) {
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(p->loads.fext));
  for (PetscInt g = 0; g < p->loads.npressure; g++) PetscCall(VecAXPY(p->loads.fext, p->loads.pressure[g], p->loads.unit_force[g]));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_problem_commit(FeProblem *p) {
  PetscFunctionBeginUser;
  PetscCall(PetscArraycpy(p->pts.state, p->pts.trial, p->space.npoint * p->pts.nsv));
  PetscFunctionReturn(0);
}

/* The supports' force on the body: at a fixed component F_int = F_ext + F_support, and no external load acts
   there (pressures on fixed components are carried by the support directly), so F_support = F_int, summed
   over the cells of all ranks (each cell is on one rank). Collective; called for a converged state only. */
PetscErrorCode fe_problem_reactions(FeProblem *p) {
  PetscFunctionBeginUser;
  PetscCall(MPIU_Allreduce(p->diag.reaction_local, p->diag.reaction, 3, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)p->space.dm)));
  PetscFunctionReturn(0);
}
