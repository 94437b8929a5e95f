#include "fe_output.h"
#include "../io/log_events.h"

#include <petsclayouthdf5.h>
#include <petscviewerhdf5.h>

#include "camclay9.h"
#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* Cell fields: name, number of components, and where they come from in a point's state
 * (fe_problem.h: stress, strain, then STATEV with the Cam-Clay IX slots of camclay9.h). */
typedef struct {
  const char *name;
  PetscInt    nc, offset;
} CellField;
static const CellField cell_fields[] = {
  {"stress", 6, ST_STRESS},
  {"strain", 6, ST_STRAN},
  {"evp_hard", 6, ST_STATEV + CAMCLAY9_SV_EVP_HARD},
  {"evp_soft", 6, ST_STATEV + CAMCLAY9_SV_EVP_SOFT},
  {"evp", 6, ST_STATEV + CAMCLAY9_SV_EVP},
  {"pc_hard", 1, ST_STATEV + CAMCLAY9_SV_PC_HARD},
  {"pc_soft", 1, ST_STATEV + CAMCLAY9_SV_PC_SOFT},
  {"phi", 1, -1},
};
enum { NCELLFIELDS = sizeof cell_fields / sizeof cell_fields[0] };

static PetscBool field_present(const FeProblem *p, const CellField *cf) {
  return (PetscBool)!(cf->offset >= ST_STATEV && cf->offset + cf->nc > ST_STATEV + p->mat.nstatv); /* UMAT without these slots */
}

/* What the six components of a tensor are, per kinematics (the UMAT's Voigt order; in 2D the 33 slot is the
 * out-of-plane or hoop component, 13 and 23 are zero). */
static const char *tensor_components(const FeProblem *p) {
  switch (p->kin) {
  case KIN_PLANE_STRAIN: return "xx yy zz(out-of-plane) xy 0 0";
  case KIN_AXISYMMETRIC: return "rr zz tt(hoop) rz 0 0";
  default: return "11 22 33 12 13 23";
  }
}

static PetscErrorCode file_path(const FeOutput *o, const char *base, PetscBool final, char *path, size_t n) {
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(path, n, "%s/%s%s", o->dir, base, final ? "" : ".part"));
  PetscFunctionReturn(0);
}

/* The points of [pStart, pStart + size(num)) that this rank owns (num >= 0), which DMPlex numbers
 * contiguously from the first of them. */
static PetscErrorCode owned_points(IS num, PetscInt pStart, PetscInt *nloc, PetscInt **pts) {
  const PetscInt *g;
  PetscInt        n, m = 0, g0 = -1;
  PetscFunctionBeginUser;
  PetscCall(ISGetLocalSize(num, &n));
  PetscCall(ISGetIndices(num, &g));
  for (PetscInt k = 0; k < n; k++) m += g[k] >= 0;
  PetscCall(PetscMalloc1(m + 1, pts));
  m = 0;
  for (PetscInt k = 0; k < n; k++) {
    if (g[k] < 0) continue;
    if (g0 < 0) g0 = g[k];
    PetscCheck(g[k] == g0 + m, PETSC_COMM_SELF, PETSC_ERR_PLIB, "fe_output: owned points not numbered contiguously");
    (*pts)[m++] = pStart + k;
  }
  PetscCall(ISRestoreIndices(num, &g));
  *nloc = m;
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

/* Cell connectivity in global vertex numbers, each simplex positively oriented (as VTK expects). */
static PetscErrorCode write_cells(FeProblem *p, FeOutput *o) {
  const PetscInt  nvc = p->dim + 1;
  IS              vnum, is;
  const PetscInt *gv;
  PetscInt        vStart, vEnd, *idx, cdim;
  PetscSection    cs;
  Vec             X;
  const PetscScalar *x;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetDepthStratum(p->dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetVertexNumbering(p->dm, &vnum));
  PetscCall(ISGetIndices(vnum, &gv));
  PetscCall(DMGetCoordinateDim(p->dm, &cdim));
  PetscCall(DMGetCoordinateSection(p->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(p->dm, &X));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(PetscMalloc1(o->ncloc * nvc + 1, &idx));
  for (PetscInt k = 0; k < o->ncloc; k++) {
    PetscInt *cl = NULL, ncl, m = 0, lv[4], off[4];
    PetscCall(DMPlexGetTransitiveClosure(p->dm, o->cown[k], PETSC_TRUE, &ncl, &cl));
    for (PetscInt j = 0; j < 2 * ncl; j += 2)
      if (cl[j] >= vStart && cl[j] < vEnd && m < nvc) lv[m++] = cl[j];
    PetscCall(DMPlexRestoreTransitiveClosure(p->dm, o->cown[k], PETSC_TRUE, &ncl, &cl));
    PetscCheck(m == nvc, PETSC_COMM_SELF, PETSC_ERR_SUP, "fe_output: cell %d is not a simplex", (int)o->cown[k]);
    for (PetscInt j = 0; j < m; j++) PetscCall(PetscSectionGetOffset(cs, lv[j], &off[j]));
    PetscReal a[3][3] = {{0}}, det;
    for (PetscInt j = 1; j < m; j++)
      for (PetscInt d = 0; d < p->dim; d++) a[j - 1][d] = PetscRealPart(x[off[j] + d] - x[off[0] + d]);
    det = p->dim == 3 ? a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                          a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
                      : a[0][0] * a[1][1] - a[0][1] * a[1][0];
    if (det < 0) {
      PetscInt t = lv[0];
      lv[0] = lv[1], lv[1] = t;
    }
    for (PetscInt j = 0; j < m; j++) {
      PetscInt g = gv[lv[j] - vStart];
      idx[k * nvc + j] = g < 0 ? -(g + 1) : g;
    }
  }
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(ISRestoreIndices(vnum, &gv));
  PetscCall(ISCreateGeneral(PetscObjectComm((PetscObject)p->dm), o->ncloc * nvc, idx, PETSC_OWN_POINTER, &is));
  PetscCall(ISSetBlockSize(is, nvc));
  PetscCall(PetscObjectSetName((PetscObject)is, "cells"));
  PetscCall(view_in(o->viewer, "/mesh", (PetscObject)is));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

static PetscErrorCode write_mesh(FeProblem *p, FeOutput *o) {
  PetscSection       cs;
  Vec                X, C;
  const PetscScalar *x;
  PetscScalar       *c;
  PetscFunctionBeginUser;
  PetscCall(DMGetCoordinateSection(p->dm, &cs));
  PetscCall(DMGetCoordinatesLocal(p->dm, &X));
  PetscCall(block_vec(PetscObjectComm((PetscObject)p->dm), o->nvloc, p->dim, "coordinates", &C));
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(C, &c));
  for (PetscInt k = 0; k < o->nvloc; k++) {
    PetscInt off;
    PetscCall(PetscSectionGetOffset(cs, o->vown[k], &off));
    for (PetscInt d = 0; d < p->dim; d++) c[k * p->dim + d] = x[off + d];
  }
  PetscCall(VecRestoreArray(C, &c));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(view_in(o->viewer, "/mesh", (PetscObject)C));
  PetscCall(VecDestroy(&C));
  PetscCall(write_cells(p, o));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "tensor_components", PETSC_STRING, tensor_components(p)));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "cell_values", PETSC_STRING,
                                          "averages over the quadrature points of a cell, weighted by the volume"));
  PetscCall(PetscViewerHDF5WriteAttribute(o->viewer, "/fields", "displacement_values", PETSC_STRING,
                                          p->order > 1 ? "at the vertices: the P1 interpolant of the P2 field"
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
  PetscCheck(n == o->nc * (p->dim + 1), PetscObjectComm((PetscObject)p->dm), PETSC_ERR_FILE_UNEXPECTED,
             "%s: /mesh/cells has %d entries, but this mesh has %d cells of %d vertices: the file is not this run's output",
             path, (int)n, (int)o->nc, (int)(p->dim + 1));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o) {
  MPI_Comm    comm = PetscObjectComm((PetscObject)p->dm);
  char        path[700];
  IS          num;
  PetscInt    vStart, vEnd;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof *o));
  PetscCall(PetscSNPrintf(o->dir, sizeof o->dir, "%s", outdir));
  o->comm = comm;
  o->promoted = append;
  PetscCall(DMPlexGetDepthStratum(p->dm, 0, &vStart, &vEnd));
  PetscCall(DMPlexGetVertexNumbering(p->dm, &num));
  PetscCall(owned_points(num, vStart, &o->nvloc, &o->vown));
  PetscCall(DMPlexGetCellNumbering(p->dm, &num));
  PetscCall(owned_points(num, p->cStart, &o->ncloc, &o->cown));
  PetscCall(MPIU_Allreduce(&o->nvloc, &o->nv, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&o->ncloc, &o->nc, 1, MPIU_INT, MPI_SUM, comm));
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

/* The displacement at the owned vertices, boundary values in, padded to 3 components. */
static PetscErrorCode displacement_vec(FeProblem *p, Vec U, FeOutput *o, Vec *D) {
  Vec                Uloc;
  PetscSection       s;
  PetscScalar       *u;
  PetscScalar       *d;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(p->dm, &Uloc));
  PetscCall(DMGlobalToLocal(p->dm, U, INSERT_VALUES, Uloc));
  PetscCall(DMGetLocalSection(p->dm, &s));
  PetscCall(block_vec(PetscObjectComm((PetscObject)p->dm), o->nvloc, 3, "displacement", D));
  PetscCall(VecGetArray(Uloc, &u));
  PetscCall(fe_constraint_to_global(&p->con, u)); /* the fixed components' zeros; nodal frames to global axes */
  PetscCall(VecGetArray(*D, &d));
  for (PetscInt k = 0; k < o->nvloc; k++) {
    PetscInt off, ndof;
    PetscCall(PetscSectionGetOffset(s, o->vown[k], &off));
    PetscCall(PetscSectionGetDof(s, o->vown[k], &ndof));
    PetscCheck(ndof == p->dim, PETSC_COMM_SELF, PETSC_ERR_PLIB, "fe_output: %d dofs at a vertex", (int)ndof);
    for (PetscInt c = 0; c < 3; c++) d[3 * k + c] = c < p->dim ? u[off + c] : 0;
  }
  PetscCall(VecRestoreArray(*D, &d));
  PetscCall(VecRestoreArray(Uloc, &u));
  PetscCall(DMRestoreLocalVector(p->dm, &Uloc));
  PetscFunctionReturn(0);
}

/* A cell field: per owned cell, the average over its quadrature points (weights w detJ). In 2D the 13 and
 * 23 slots of stress and strain are not the UMAT's (NTENS = 4) and are written as the zeros they are. */
static PetscErrorCode cell_vec(FeProblem *p, const CellField *cf, FeOutput *o, Vec *F) {
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(block_vec(PetscObjectComm((PetscObject)p->dm), o->ncloc, cf->nc, cf->name, F));
  PetscCall(VecGetArray(*F, &a));
  for (PetscInt k = 0; k < o->ncloc; k++) {
    const PetscInt c = o->cown[k] - p->cStart;
    for (PetscInt j = 0; j < cf->nc; j++) {
      PetscReal sum = 0, vol = 0;
      for (PetscInt q = 0; q < p->nq; q++) {
        const PetscInt  pt = c * p->nq + q;
        const PetscReal w  = p->wdetJ[pt];
        sum += w * (cf->offset < 0 ? p->phi[c] : p->state[pt * p->nsv + cf->offset + j]);
        vol += w;
      }
      a[k * cf->nc + j] = p->dim == 2 && cf->offset < ST_STATEV && j >= 4 ? 0 : sum / vol;
    }
  }
  PetscCall(VecRestoreArray(*F, &a));
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
static void data_item(FILE *fp, const char *type, int prec, PetscInt n, PetscInt nc, const char *h5path) {
  fprintf(fp, "          <DataItem DataType=\"%s\" Precision=\"%d\" Format=\"HDF\" Dimensions=\"%d", type, prec, (int)n);
  if (nc > 1) fprintf(fp, " %d", (int)nc);
  fprintf(fp, "\">fields.h5:%s</DataItem>\n", h5path);
}

static void xmf_grid(FILE *fp, const FeProblem *p, const FeOutput *o, PetscInt k) {
  char ds[96];
  fprintf(fp, "    <Grid Name=\"output %d\" GridType=\"Uniform\">\n      <Time Value=\"%.17g\"/>\n", (int)k, (double)o->times[k]);
  fprintf(fp, "      <Topology TopologyType=\"%s\" NumberOfElements=\"%d\">\n", p->dim == 3 ? "Tetrahedron" : "Triangle", (int)o->nc);
  data_item(fp, "Int", (int)sizeof(PetscInt), o->nc, p->dim + 1, "/mesh/cells");
  fprintf(fp, "      </Topology>\n      <Geometry GeometryType=\"%s\">\n", p->dim == 3 ? "XYZ" : "XY");
  data_item(fp, "Float", 8, o->nv, p->dim, "/mesh/coordinates");
  fprintf(fp, "      </Geometry>\n      <Attribute Name=\"displacement\" AttributeType=\"Vector\" Center=\"Node\">\n");
  snprintf(ds, sizeof ds, "/fields/displacement/%06d", (int)k);
  data_item(fp, "Float", 8, o->nv, 3, ds);
  fprintf(fp, "      </Attribute>\n");
  for (PetscInt f = 0; f < NCELLFIELDS; f++) {
    const CellField *cf = &cell_fields[f];
    if (!field_present(p, cf)) continue;
    fprintf(fp, "      <Attribute Name=\"%s\" AttributeType=\"%s\" Center=\"Cell\">\n", cf->name, cf->nc == 6 ? "Tensor6" : "Scalar");
    snprintf(ds, sizeof ds, "/fields/%s/%06d", cf->name, (int)k);
    data_item(fp, "Float", 8, o->nc, cf->nc, ds);
    fprintf(fp, "      </Attribute>\n");
  }
  fprintf(fp, "    </Grid>\n");
}

/* Rank 0 writes the whole index to a temporary file and renames it over the current one, so a reader
 * never sees half a file. */
static PetscErrorCode xmf_write(FeProblem *p, FeOutput *o) {
  PetscMPIInt rank;
  char        tmp[700], path[700];
  int         err = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)p->dm), &rank));
  PetscCall(file_path(o, "fields.xmf", o->promoted, path, sizeof path));
  PetscCall(PetscSNPrintf(tmp, sizeof tmp, "%s/.fields.xmf.tmp", o->dir));
  if (!rank) {
    FILE *fp = fopen(tmp, "w");
    if (fp) {
      fprintf(fp, "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
      fprintf(fp, "    <Information Name=\"tensor_components\" Value=\"%s\"/>\n", tensor_components(p));
      fprintf(fp, "    <Information Name=\"strain_shear\" Value=\"engineering (2 eps_ij)\"/>\n");
      fprintf(fp, "    <Information Name=\"cell_values\" Value=\"averages over the quadrature points\"/>\n");
      fprintf(fp, "    <Information Name=\"displacement\" Value=\"%s\"/>\n",
              p->order > 1 ? "vertex values of the P2 field (P1 interpolant)" : "vertex values (P1)");
      fprintf(fp, "    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
      for (PetscInt k = 0; k < o->nout; k++) xmf_grid(fp, p, o, k);
      fprintf(fp, "    </Grid>\n  </Domain>\n</Xdmf>\n");
      err = ferror(fp) ? EIO : 0;
      if (fclose(fp) && !err) err = errno;
      if (!err && rename(tmp, path)) err = errno;
    } else err = errno;
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, PetscObjectComm((PetscObject)p->dm)));
  PetscCheck(!err, PetscObjectComm((PetscObject)p->dm), PETSC_ERR_FILE_WRITE, "fe_output: cannot write %s: %s", path, strerror(err));
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

PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, FeOutput *o) {
  char group[64], name[16];
  Vec  v;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(driver_event(EV_OUTPUT), 0, 0, 0, 0));
  PetscCall(PetscSNPrintf(name, sizeof name, "%06d", (int)o->nout));
  PetscCall(displacement_vec(p, U, o, &v));
  PetscCall(PetscObjectSetName((PetscObject)v, name));
  PetscCall(view_in(o->viewer, "/fields/displacement", (PetscObject)v));
  PetscCall(VecDestroy(&v));
  for (PetscInt f = 0; f < NCELLFIELDS; f++) {
    const CellField *cf = &cell_fields[f];
    if (!field_present(p, cf)) continue;
    PetscCall(cell_vec(p, cf, o, &v));
    PetscCall(PetscObjectSetName((PetscObject)v, name));
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

static int rename_part(const FeOutput *o, const char *base) {
  char from[700], to[700];
  snprintf(from, sizeof from, "%s/%s.part", o->dir, base);
  snprintf(to, sizeof to, "%s/%s", o->dir, base);
  if (rename(from, to) == 0 || (errno == ENOENT && access(to, F_OK) == 0)) return 0;
  return errno;
}

PetscErrorCode fe_output_promote(FeOutput *o) {
  MPI_Comm    comm = o->comm;
  PetscMPIInt rank;
  int         err[2] = {0, 0};
  PetscFunctionBeginUser;
  if (o->promoted) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    err[0] = rename_part(o, "fields.h5");
    if (!err[0] && o->nout > 0) err[1] = rename_part(o, "fields.xmf"); /* it names fields.h5 already */
  }
  PetscCallMPI(MPI_Bcast(err, 2, MPI_INT, 0, comm));
  PetscCheck(!err[0] && !err[1], comm, PETSC_ERR_FILE_WRITE, "fe_output: cannot rename %s/%s.part to its final name: %s",
             o->dir, err[0] ? "fields.h5" : "fields.xmf", strerror(err[0] ? err[0] : err[1]));
  o->promoted = PETSC_TRUE;
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o) {
  PetscFunctionBeginUser;
  if (o->nout > 0) PetscCall(xmf_write(p, o)); /* after a resume without further outputs: its times */
  PetscCall(PetscViewerDestroy(&o->viewer));
  PetscCall(PetscFree(o->vown));
  PetscCall(PetscFree(o->cown));
  PetscCall(PetscFree(o->times));
  PetscFunctionReturn(0);
}
