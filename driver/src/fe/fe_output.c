#include "fe_output.h"
#include "fe_estimate.h"
#include "../io/log_events.h"

#include <petsclayouthdf5.h>
#include <petscviewerhdf5.h>

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Cell fields: name, number of components, where they come from in a point's state (fe_problem.h: stress, strain,
 * then the UMAT's STATEV, read by quantity through material_point.h), and whether the Voigt values are strains
 * (engineering shear, halved in the tensor). */
typedef enum { FROM_STRESS, FROM_STRAN, FROM_STATEV, FROM_PHI, FROM_ETA, FROM_ETA_MAX } FieldSource;
typedef struct {
  const char *name;
  PetscInt    nc;
  FieldSource from;
  MaterialQuantity q; /* FROM_STATEV */
  PetscBool   strain;
} CellField;
static const CellField cell_fields[] = {
  {"stress", 6, FROM_STRESS, 0, PETSC_FALSE},
  {"strain", 6, FROM_STRAN, 0, PETSC_TRUE},
  {"evp_hard", 6, FROM_STATEV, MATERIAL_EVP_HARD, PETSC_TRUE},
  {"evp_soft", 6, FROM_STATEV, MATERIAL_EVP_SOFT, PETSC_TRUE},
  {"evp", 6, FROM_STATEV, MATERIAL_EVP, PETSC_TRUE},
  {"pc_hard", 1, FROM_STATEV, MATERIAL_PC_HARD, PETSC_FALSE},
  {"pc_soft", 1, FROM_STATEV, MATERIAL_PC_SOFT, PETSC_FALSE},
  {"phi", 1, FROM_PHI, 0, PETSC_FALSE},
  {"error_indicator", 1, FROM_ETA, 0, PETSC_FALSE},     /* fe_estimate.h: at this output */
  {"error_indicator_max", 1, FROM_ETA_MAX, 0, PETSC_FALSE}, /* ... its largest over the report times so far */
};
enum { NCELLFIELDS = sizeof cell_fields / sizeof cell_fields[0] };
/* The row-major place of each Voigt component 11 22 33 12 13 23 in a 3x3 tensor (and of its mirror). */
static const PetscInt voigt_row[6] = {0, 4, 8, 1, 2, 5}, voigt_mirror[6] = {0, 4, 8, 3, 6, 7};

static PetscBool field_present(const FeProblem *p, const CellField *cf) {
  return (PetscBool)(cf->from != FROM_STATEV || material_quantity_size(&p->pts.mat, cf->q) == cf->nc);
}

/* Component j of the field at point k of local cell c. */
static PetscReal field_value(const FeProblem *p, const CellField *cf, PetscInt c, PetscInt k, PetscInt j) {
  const PetscReal *st = &p->pts.state[k * p->pts.nsv];
  switch (cf->from) {
  case FROM_STRESS: return st[ST_STRESS + j];
  case FROM_STRAN: return st[ST_STRAN + j];
  case FROM_PHI: return p->pts.phi[c];
  case FROM_ETA: return p->est.eta[c];
  case FROM_ETA_MAX: return p->est.eta_max[c];
  default: return material_quantity(&p->pts.mat, st + ST_STATEV, cf->q, (int)j);
  }
}

/* What the nine components of a tensor are, per kinematics (in 2D the zz slot is the out-of-plane or hoop
 * component, and xz, yz are zero). */
static const char *tensor_components(const FeProblem *p) {
  switch (p->space.kin) {
  case KIN_PLANE_STRAIN: return "full 3x3 tensors row by row: xx xy 0 yx yy 0 0 0 zz (zz out of plane); strains as tensors (eps_xy = gamma_xy / 2)";
  case KIN_AXISYMMETRIC: return "full 3x3 tensors row by row: rr rz 0 zr zz 0 0 0 tt (tt: hoop); strains as tensors (eps_rz = gamma_rz / 2)";
  default: return "full 3x3 tensors row by row: 11 12 13 21 22 23 31 32 33; strains as tensors (eps_12 = gamma_12 / 2)";
  }
}

static PetscErrorCode file_path(const FeOutput *o, const char *base, PetscBool final, char *path, size_t n) {
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, n, "%s/%s%s", o->dir, base, final ? "" : ".part"));
  PetscFunctionReturn(0);
}

/* A vector of nloc blocks of bs on this rank, not tied to a DM: PETSc writes it as an (N, bs) dataset. */
static PetscErrorCode block_vec(MPI_Comm comm, PetscInt nloc, PetscInt bs, const char *name, Vec *v) {
  PetscFunctionBeginUser;
  PetscCall(VecCreate(comm, v));
  PetscCall(VecSetSizes(*v, nloc * bs, PETSC_DECIDE));
  PetscCall(VecSetBlockSize(*v, bs));
  PetscCall(VecSetType(*v, VECSTANDARD));
  PetscCall(PetscObjectSetName((PetscObject)*v, name));
  PetscFunctionReturn(0);
}

static PetscErrorCode view_in(PetscViewer viewer, const char *group, PetscObject obj) {
  PetscClassId id;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetClassId(obj, &id));
  PetscCall(PetscViewerHDF5PushGroup(viewer, group));
  if (id == VEC_CLASSID) PetscCall(VecView((Vec)obj, viewer));
  else PetscCall(ISView((IS)obj, viewer));
  PetscCall(PetscViewerHDF5PopGroup(viewer));
  PetscFunctionReturn(0);
}

/* The two vertices of each edge of a simplex in VTK's order of the mid-side nodes (VTK_QUADRATIC_TETRA,
   VTK_QUADRATIC_TRIANGLE; XDMF's Tetrahedron_10 and Triangle_6). */
static const PetscInt tet_edges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}}, tri_edges[3][2] = {{0, 1}, {1, 2}, {2, 0}};

/* The vertices of cell c, positively oriented (as VTK expects: the first two swapped when not). */
static PetscErrorCode cell_vertices(FeProblem *p, PetscInt c, const PetscScalar *x, PetscSection cs, PetscInt lv[4]) {
  PetscInt *cl = NULL, ncl, m = 0, vStart, vEnd, off[4], nvc = p->space.dim + 1;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(p->space.dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetTransitiveClosure(p->space.dm, c, PETSC_TRUE, &ncl, &cl));
  for (PetscInt j = 0; j < 2 * ncl; j += 2)
    if (cl[j] >= vStart && cl[j] < vEnd && m < nvc) lv[m++] = cl[j];
  PetscCall(DMPlexRestoreTransitiveClosure(p->space.dm, c, PETSC_TRUE, &ncl, &cl));
  PetscCheck(m == nvc, PETSC_COMM_SELF, PETSC_ERR_SUP, "fe_output: cell %d is not a simplex", (int)c);
  for (PetscInt j = 0; j < m; j++) PetscCall(PetscSectionGetOffset(cs, lv[j], &off[j]));
  PetscReal a[3][3] = {{0}}, det;
  for (PetscInt j = 1; j < m; j++)
    for (PetscInt d = 0; d < p->space.dim; d++) a[j - 1][d] = PetscRealPart(x[off[j] + d] - x[off[0] + d]);
  det = p->space.dim == 3 ? a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                        a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
                    : a[0][0] * a[1][1] - a[0][1] * a[1][0];
  if (det < 0) {
    PetscInt t = lv[0];
    lv[0] = lv[1], lv[1] = t;
  }
  PetscFunctionReturn(0);
}

/* Cell connectivity in natural node numbers: the vertices, then (P2) the mid-side nodes of the edges. */
static PetscErrorCode write_cells(FeProblem *p, FeOutput *o) {
  const PetscInt  nvc = p->space.dim + 1;
  const PetscInt *nat;
  PetscInt       *leaf, *root;
  PetscSection    cs;
  Vec             X;
  const PetscScalar *x;
  IS              is;
  PetscFunctionBeginUser;
  PetscCall(fe_natural_indices(p->space.dm, &nat));
  PetscCall(DMGetCoordinateSection(p->space.dm, &cs));
  PetscCall(DMGetCoordinatesLocal(p->space.dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscMalloc1(o->cells.n * o->npc + 1, &leaf));
  PetscCall(PetscMalloc1(o->cells.nroot * o->npc + 1, &root));
  for (PetscInt k = 0; k < o->cells.n; k++) {
    PetscInt lv[4], *row = &leaf[k * o->npc];
    PetscCall(cell_vertices(p, o->cells.points[k], x, cs, lv));
    for (PetscInt j = 0; j < nvc; j++) row[j] = o->nodes.offset[0] + nat[lv[j]];
    for (PetscInt e = 0; e < o->npc - nvc; e++) {
      const PetscInt *ev = p->space.dim == 3 ? tet_edges[e] : tri_edges[e], pair[2] = {lv[ev[0]], lv[ev[1]]}, *join;
      PetscInt        nj;
      PetscCall(DMPlexGetJoin(p->space.dm, 2, pair, &nj, &join));
      PetscCheck(nj == 1, PETSC_COMM_SELF, PETSC_ERR_PLIB, "fe_output: no edge between two vertices of a cell");
      row[nvc + e] = o->nodes.offset[1] + nat[join[0]];
      PetscCall(DMPlexRestoreJoin(p->space.dm, 2, pair, &nj, &join));
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(fe_natural_gather_int(&o->cells, o->npc, leaf, root));
  PetscCall(PetscFree(leaf));
  PetscCall(ISCreateGeneral(o->comm, o->cells.nroot * o->npc, root, PETSC_OWN_POINTER, &is));
  PetscCall(ISSetBlockSize(is, o->npc));
  PetscCall(PetscObjectSetName((PetscObject)is, "cells"));
  PetscCall(view_in(o->viewer, "/mesh", (PetscObject)is));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

/* Node coordinates: the vertices', and (P2) the edges' midpoints. */
static PetscErrorCode write_mesh(FeProblem *p, FeOutput *o) {
  PetscSection       cs;
  Vec                X, C;
  const PetscScalar *x;
  PetscScalar       *c;
  PetscInt           vStart, vEnd;
  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateSection(p->space.dm, &cs));
  PetscCall(DMGetCoordinatesLocal(p->space.dm, &X));
  PetscCall(DMPlexGetDepthStratum(p->space.dm, 0, &vStart, &vEnd));
  PetscCall(PetscMalloc1(o->nodes.n * p->space.dim + 1, &c));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < o->nodes.n; k++) {
    PetscInt        pt = o->nodes.points[k], ncone = 1, off;
    const PetscInt *cone = &pt;
    if (pt < vStart || pt >= vEnd) { /* an edge: its midpoint */
      PetscCall(DMPlexGetConeSize(p->space.dm, pt, &ncone));
      PetscCall(DMPlexGetCone(p->space.dm, pt, &cone));
    }
    for (PetscInt d = 0; d < p->space.dim; d++) c[k * p->space.dim + d] = 0;
    for (PetscInt j = 0; j < ncone; j++) {
      PetscCall(PetscSectionGetOffset(cs, cone[j], &off));
      for (PetscInt d = 0; d < p->space.dim; d++) c[k * p->space.dim + d] += x[off + d] / ncone;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(fe_natural_gather(&o->nodes, p->space.dim, c, "coordinates", &C));
  PetscCall(PetscFree(c));
  PetscCall(view_in(o->viewer, "/mesh", (PetscObject)C));
  PetscCall(VecDestroy(&C));
  PetscCall(write_cells(p, o));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "tensor_components", PETSC_STRING, tensor_components(p)));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "cell_values", PETSC_STRING,
                                          "averages over the quadrature points of a cell, weighted by the volume"));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "displacement_values", PETSC_STRING,
                                          p->space.order > 1 ? "at the nodes of the quadratic cells: vertices, then edge midpoints"
                                                       : "at the vertices (P1)"));
  PetscFunctionReturn(0);
}

/* The existing file of a restart must hold this mesh. */
static PetscErrorCode check_mesh(FeProblem *p, FeOutput *o, const char *path) {
  PetscInt bs = 0, n = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PushGroup(o->viewer, "/mesh"));
  PetscCall(PetscViewerHDF5ReadSizes(o->viewer, "cells", &bs, &n));
  PetscCall(PetscViewerHDF5PopGroup(o->viewer));
  PetscCheck(n == o->cells.N * o->npc, PetscObjectComm((PetscObject)p->space.dm), PETSC_ERR_FILE_UNEXPECTED,
             "%s: /mesh/cells has %d entries, but this mesh has %d cells of %d nodes: the file is not this run's output",
             path, (int)n, (int)o->cells.N, (int)o->npc);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o) {
  MPI_Comm       comm = PetscObjectComm((PetscObject)p->space.dm);
  char           path[700];
  PetscMPIInt    rank;
  const PetscInt node_depths[2] = {0, 1};
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof *o));
  PetscCall(PetscSNPrintf(o->dir, sizeof o->dir, "%s", outdir));
  o->comm     = comm;
  o->promoted = append;
  o->npc      = p->space.order > 1 ? (p->space.dim == 3 ? 10 : 6) : p->space.dim + 1;
  PetscCall(fe_natural_create(p->space.dm, p->space.order > 1 ? 2 : 1, node_depths, PETSC_FALSE, &o->nodes));
  PetscCall(fe_natural_create(p->space.dm, 1, &p->space.dim, PETSC_FALSE, &o->cells));
  PetscCall(file_path(o, "fields.h5", o->promoted, path, sizeof path));
  if (append) {
    int missing = 0;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (!rank) missing = access(path, R_OK | W_OK) != 0;
    PetscCallMPI(MPI_Bcast(&missing, 1, MPI_INT, 0, comm));
    PetscCheck(!missing, comm, PETSC_ERR_FILE_OPEN,
               "%s: cannot append the fields of the restarted run: no such writable file (the checkpointed run's output)", path);
  }
  PetscCall(PetscViewerHDF5Open(comm, path, append ? FILE_MODE_APPEND : FILE_MODE_WRITE, &o->viewer));
  if (append) PetscCall(check_mesh(p, o, path));
  else PetscCall(write_mesh(p, o));
  PetscFunctionReturn(0);
}

/* The displacement at the owned nodes, boundary values in, in global axes, padded to 3 components. */
static PetscErrorCode displacement_vec(FeProblem *p, Vec U, FeOutput *o, const char *name, Vec *D) {
  Vec          Uloc;
  PetscSection s;
  PetscScalar *u, *d;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->space.dm, &Uloc));
  PetscCall(VecZeroEntries(Uloc));
  PetscCall(DMGlobalToLocal(p->space.dm, U, INSERT_VALUES, Uloc));
  PetscCall(DMGetLocalSection(p->space.dm, &s));
  PetscCall(VecGetArray(Uloc, &u));
  PetscCall(fe_constraint_to_global(&p->space.con, u)); /* the fixed components' zeros; nodal frames to global axes */
  PetscCall(PetscMalloc1(3 * o->nodes.n + 1, &d));
  for (PetscInt k = 0; k < o->nodes.n; k++) {
    PetscInt off, ndof;
    PetscCall(PetscSectionGetOffset(s, o->nodes.points[k], &off));
    PetscCall(PetscSectionGetDof(s, o->nodes.points[k], &ndof));
    PetscCheck(ndof == p->space.dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "fe_output: %d dofs at a node", (int)ndof);
    for (PetscInt c = 0; c < 3; c++) d[3 * k + c] = c < p->space.dim ? u[off + c] : 0;
  }
  PetscCall(VecRestoreArray(Uloc, &u));
  PetscCall(DMRestoreLocalVector(p->space.dm, &Uloc));
  PetscCall(fe_natural_gather(&o->nodes, 3, d, name, D));
  PetscCall(PetscFree(d));
  PetscFunctionReturn(0);
}

/* A cell field: per owned cell, the average over its quadrature points (weights w detJ); a tensor as its nine
 * components. In 2D the 13 and 23 slots of stress and strain are not the UMAT's (NTENS = 4) and are written as the
 * zeros they are. */
static PetscErrorCode cell_vec(FeProblem *p, const CellField *cf, FeOutput *o, const char *name, Vec *F) {
  const PetscInt bs = cf->nc == 6 ? 9 : 1;
  PetscScalar   *a;
  PetscFunctionBeginUser;
  PetscCall(PetscCalloc1(o->cells.n * bs + 1, &a));
  for (PetscInt k = 0; k < o->cells.n; k++) {
    const PetscInt c = o->cells.points[k] - p->space.cStart;
    for (PetscInt j = 0; j < cf->nc; j++) {
      PetscReal sum = 0, vol = 0, v;
      for (PetscInt q = 0; q < p->space.nq; q++) {
        const PetscInt  pt = c * p->space.nq + q;
        const PetscReal w  = p->space.wdetJ[pt];
        sum += w * field_value(p, cf, c, pt, j);
        vol += w;
      }
      v = p->space.dim == 2 && (cf->from == FROM_STRESS || cf->from == FROM_STRAN) && j >= 4 ? 0 : sum / vol;
      if (bs == 1) a[k] = v;
      else {
        if (j >= 3 && cf->strain) v /= 2; /* engineering shear to the tensor's */
        a[k * 9 + voigt_row[j]] = a[k * 9 + voigt_mirror[j]] = v;
      }
    }
  }
  PetscCall(fe_natural_gather(&o->cells, bs, a, name, F));
  PetscCall(PetscFree(a));
  PetscFunctionReturn(0);
}

/* /time as a growing dataset (PETSc's timestepping): entry k is written, and the dataset cut to k + 1. */
static PetscErrorCode write_time(FeOutput *o, PetscInt k, PetscReal t) {
  Vec         T;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)o->viewer), &rank));
  PetscCall(block_vec(PetscObjectComm((PetscObject)o->viewer), rank ? 0 : 1, 1, "time", &T));
  if (!rank) PetscCall(VecSetValue(T, 0, t, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(T));
  PetscCall(VecAssemblyEnd(T));
  PetscCall(PetscViewerHDF5PushTimestepping(o->viewer));
  PetscCall(PetscViewerHDF5SetTimestep(o->viewer, k));
  PetscCall(view_in(o->viewer, "/", (PetscObject)T));
  PetscCall(PetscViewerHDF5PopTimestepping(o->viewer));
  PetscCall(VecDestroy(&T));
  PetscFunctionReturn(0);
}

/* ------------------------------------------------------------------------------------------ XDMF */
static void data_item(FILE *fp, const char *h5, const char *type, int prec, PetscInt n, PetscInt nc, const char *h5path) {
  fprintf(fp, "          <DataItem DataType=\"%s\" Precision=\"%d\" Format=\"HDF\" Dimensions=\"%d", type, prec, (int)n);
  if (nc > 1) fprintf(fp, " %d", (int)nc);
  fprintf(fp, "\">%s:%s</DataItem>\n", h5, h5path);
}

static void xmf_grid(FILE *fp, const FeProblem *p, const FeOutput *o, const char *h5, PetscInt k) {
  char        ds[96];
  const char *topology = p->space.order > 1 ? (p->space.dim == 3 ? "Tetrahedron_10" : "Triangle_6") : (p->space.dim == 3 ? "Tetrahedron" : "Triangle");
  fprintf(fp, "    <Grid Name=\"output %d\" GridType=\"Uniform\">\n      <Time Value=\"%.17g\"/>\n", (int)k, (double)o->times[k]);
  fprintf(fp, "      <Topology TopologyType=\"%s\" NumberOfElements=\"%d\">\n", topology, (int)o->cells.N);
  data_item(fp, h5, "Int", (int)sizeof(PetscInt), o->cells.N, o->npc, "/mesh/cells");
  fprintf(fp, "      </Topology>\n      <Geometry GeometryType=\"%s\">\n", p->space.dim == 3 ? "XYZ" : "XY");
  data_item(fp, h5, "Float", 8, o->nodes.N, p->space.dim, "/mesh/coordinates");
  fprintf(fp, "      </Geometry>\n      <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n");
  snprintf(ds, sizeof ds, "/fields/displacement/%06d", (int)k);
  data_item(fp, h5, "Float", 8, o->nodes.N, 3, ds);
  fprintf(fp, "      </Attribute>\n");
  for (PetscInt f = 0; f < NCELLFIELDS; f++) {
    const CellField *cf = &cell_fields[f];
    if (!field_present(p, cf)) continue;
    fprintf(fp, "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Cell\">\n", cf->name, cf->nc == 6 ? "Tensor" : "Scalar");
    snprintf(ds, sizeof ds, "/fields/%s/%06d", cf->name, (int)k);
    data_item(fp, h5, "Float", 8, o->cells.N, cf->nc == 6 ? 9 : 1, ds);
    fprintf(fp, "      </Attribute>\n");
  }
  fprintf(fp, "    </Grid>\n");
}

/* Rank 0 writes the whole index to a temporary file and renames it over the current one, so a reader
 * never sees half a file. Before the promotion it is fields.xmf.part and names fields.h5.part. */
static PetscErrorCode xmf_write(FeProblem *p, FeOutput *o) {
  PetscMPIInt rank;
  char        tmp[700], path[700];
  int         err = 0;
  const char *h5  = o->promoted ? "fields.h5" : "fields.h5.part";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)p->space.dm), &rank));
  PetscCall(file_path(o, "fields.xmf", o->promoted, path, sizeof path));
  PetscCall(PetscSNPrintf(tmp, sizeof tmp, "%s/.fields.xmf.tmp", o->dir));
  if (!rank) {
    FILE *fp = fopen(tmp, "w");
    if (fp) {
      fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
      fprintf(fp, "    <Information Name=\"tensor_components\" Value=\"%s\"/>\n", tensor_components(p));
      fprintf(fp, "    <Information Name=\"cell_values\" Value=\"averages over the quadrature points\"/>\n");
      fprintf(fp, "    <Information Name=\"displacement\" Value=\"%s\"/>\n",
              p->space.order > 1 ? "at the nodes of the quadratic cells (vertices, then edge midpoints)" : "vertex values (P1)");
      fprintf(fp, "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
      for (PetscInt k = 0; k < o->nout; k++) xmf_grid(fp, p, o, h5, k);
      fprintf(fp, "    </Grid>\n  </Domain>\n</Xdmf>\n");
      err = ferror(fp) ? EIO : 0;
      if (fclose(fp) && !err) err = errno;
      if (!err && rename(tmp, path)) err = errno;
    } else err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, PetscObjectComm((PetscObject)p->space.dm)));
  PetscCheck(!err, PetscObjectComm((PetscObject)p->space.dm), PETSC_ERR_FILE_WRITE, "fe_output: cannot write %s: %s", path, strerror(err));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_resume(FeOutput *o, PetscInt nout, const PetscReal *times) {
  PetscFunctionBeginUser;
  o->cap = PetscMax(64, 2 * nout);
  PetscCall(PetscMalloc1(o->cap, &o->times));
  PetscCall(PetscArraycpy(o->times, times, nout));
  o->nout = nout;
  /* drop the times written after the checkpoint (the .xmf is rewritten at the next output) */
  if (nout > 0) PetscCall(write_time(o, nout - 1, times[nout - 1]));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, PetscBool report, FeOutput *o) {
  char group[64], name[16];
  Vec  v;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(driver_event(EV_OUTPUT), 0, 0, 0, 0));
  PetscCall(PetscSNPrintf(name, sizeof name, "%06d", (int)o->nout));
  PetscCall(displacement_vec(p, U, o, name, &v));
  PetscCall(view_in(o->viewer, "/fields/displacement", (PetscObject)v));
  PetscCall(VecDestroy(&v));
  PetscCall(fe_estimate_update(p, report));
  for (PetscInt f = 0; f < NCELLFIELDS; f++) {
    const CellField *cf = &cell_fields[f];
    if (!field_present(p, cf)) continue;
    PetscCall(cell_vec(p, cf, o, name, &v));
    PetscCall(PetscSNPrintf(group, sizeof group, "/fields/%s", cf->name));
    PetscCall(view_in(o->viewer, group, (PetscObject)v));
    PetscCall(VecDestroy(&v));
  }
  PetscCall(write_time(o, o->nout, time));
  PetscCall(PetscViewerFlush(o->viewer)); /* on disk before the index names it */
  if (o->nout == o->cap) {
    o->cap = o->cap ? 2 * o->cap : 64;
    PetscCall(PetscRealloc(sizeof(PetscReal) * o->cap, &o->times));
  }
  o->times[o->nout++] = time;
  PetscCall(xmf_write(p, o));
  PetscCall(PetscLogEventEnd(driver_event(EV_OUTPUT), 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_promote(FeProblem *p, FeOutput *o) {
  MPI_Comm    comm = o->comm;
  PetscMPIInt rank;
  int         err  = 0;
  char        from[700], to[700];
  PetscFunctionBeginUser;
  if (o->promoted) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(file_path(o, "fields.h5", PETSC_FALSE, from, sizeof from));
  PetscCall(file_path(o, "fields.h5", PETSC_TRUE, to, sizeof to));
  if (!rank && rename(from, to) && !(errno == ENOENT && access(to, F_OK) == 0)) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_FILE_WRITE, "fe_output: cannot rename %s to %s: %s", from, to, strerror(err));
  o->promoted = PETSC_TRUE;
  if (o->nout > 0) PetscCall(xmf_write(p, o)); /* fields.xmf, naming fields.h5 */
  PetscCall(file_path(o, "fields.xmf", PETSC_FALSE, from, sizeof from));
  if (!rank) remove(from);
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o) {
  PetscFunctionBeginUser;
  if (o->nout > 0) PetscCall(xmf_write(p, o)); /* after a resume without further outputs: its times */
  PetscCall(PetscViewerDestroy(&o->viewer));
  PetscCall(fe_natural_destroy(&o->nodes));
  PetscCall(fe_natural_destroy(&o->cells));
  PetscCall(PetscFree(o->times));
  PetscFunctionReturn(0);
}
