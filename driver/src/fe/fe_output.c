#include "fe_output.h"

#include <petscviewerhdf5.h>

#include "camclay9.h"
#include <stdio.h>

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
static const char *voigt[6] = {"11", "22", "33", "12", "13", "23"};

static PetscErrorCode p0_dm(DM dm, PetscInt nc, DM *out) {
  PetscFE fe;
  PetscInt dim;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMClone(dm, out));
  PetscCall(PetscFECreateLagrange(PetscObjectComm((PetscObject)dm), dim, nc, PETSC_TRUE, 0, 0, &fe));
  PetscCall(DMSetField(*out, 0, NULL, (PetscObject)fe));
  PetscCall(DMCreateDS(*out));
  PetscCall(PetscFEDestroy(&fe));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o) {
  char path[700];
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(o, sizeof *o));
  PetscCall(PetscSNPrintf(o->dir, sizeof o->dir, "%s", outdir));
  PetscCall(PetscSNPrintf(path, sizeof path, "%s/fields.h5", outdir));
  PetscCall(PetscViewerHDF5Open(PetscObjectComm((PetscObject)p->dm), path, append ? FILE_MODE_APPEND : FILE_MODE_WRITE,
                                 &o->viewer));
  PetscCall(PetscViewerPushFormat(o->viewer, PETSC_VIEWER_HDF5_VIZ));
  if (!append) PetscCall(DMView(p->dm, o->viewer));
  PetscCall(PetscViewerHDF5PushTimestepping(o->viewer));
  PetscCall(p0_dm(p->dm, 6, &o->dm6));
  PetscCall(p0_dm(p->dm, 1, &o->dm1));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_resume(FeOutput *o, PetscInt nout, const PetscReal *times) {
  PetscFunctionBeginUser;
  o->cap = PetscMax(64, 2 * nout);
  PetscCall(PetscMalloc1(o->cap, &o->times));
  PetscCall(PetscArraycpy(o->times, times, nout));
  o->nout = nout;
  PetscFunctionReturn(0);
}

PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, FeOutput *o) {
  Vec Uloc;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5SetTimestep(o->viewer, o->nout));
  /* Displacement with the boundary values in, as a global vector of the problem's DM. */
  PetscCall(DMGetLocalVector(p->dm, &Uloc));
  PetscCall(DMGlobalToLocal(p->dm, U, INSERT_VALUES, Uloc));
  PetscCall(DMPlexInsertBoundaryValues(p->dm, PETSC_TRUE, Uloc, p->time, NULL, NULL, NULL));
  PetscCall(PetscObjectSetName((PetscObject)Uloc, "displacement"));
  PetscCall(VecView(Uloc, o->viewer));
  PetscCall(DMRestoreLocalVector(p->dm, &Uloc));
  for (PetscInt f = 0; f < NCELLFIELDS; f++) {
    const CellField *cf = &cell_fields[f];
    if (cf->offset >= ST_STATEV && cf->offset + cf->nc > ST_STATEV + p->mat.nstatv) continue; /* UMAT without these slots */
    DM           cdm = cf->nc == 6 ? o->dm6 : o->dm1;
    Vec          loc, glob;
    PetscSection s;
    PetscScalar *a;
    PetscCall(DMGetLocalSection(cdm, &s));
    PetscCall(DMGetLocalVector(cdm, &loc));
    PetscCall(VecGetArray(loc, &a));
    for (PetscInt c = p->cStart; c < p->cEnd; c++) {
      PetscInt off;
      PetscCall(PetscSectionGetOffset(s, c, &off));
      for (PetscInt k = 0; k < cf->nc; k++) {
        PetscReal sum = 0, vol = 0;
        for (PetscInt q = 0; q < p->nq; q++) {
          PetscInt  pt = (c - p->cStart) * p->nq + q;
          PetscReal w  = p->wdetJ[pt];
          sum += w * (cf->offset < 0 ? p->phi[c - p->cStart] : p->state[pt * p->nsv + cf->offset + k]);
          vol += w;
        }
        a[off + k] = sum / vol;
      }
    }
    PetscCall(VecRestoreArray(loc, &a));
    PetscCall(DMGetGlobalVector(cdm, &glob));
    PetscCall(DMLocalToGlobal(cdm, loc, INSERT_VALUES, glob));
    PetscCall(PetscObjectSetName((PetscObject)glob, cf->name));
    PetscCall(VecView(glob, o->viewer));
    PetscCall(DMRestoreGlobalVector(cdm, &glob));
    PetscCall(DMRestoreLocalVector(cdm, &loc));
  }
  if (o->nout == o->cap) {
    o->cap = o->cap ? 2 * o->cap : 64;
    PetscCall(PetscRealloc(sizeof(PetscReal) * o->cap, &o->times));
  }
  o->times[o->nout++] = time;
  PetscFunctionReturn(0);
}

/* The XDMF file: every output time a grid on the same mesh; every component an attribute read from
 * the HDF5 time series by a hyperslab. */
static void hyperslab(FILE *fp, const char *name, const char *center, PetscInt step, PetscInt nsteps, PetscInt n,
                      PetscInt ncomp, PetscInt comp, const char *dataset) {
  fprintf(fp, "        <Attribute Name=\"%s\" AttributeType=\"Scalar\" Center=\"%s\">\n"
              "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"%d\" Type=\"HyperSlab\">\n",
          name, center, (int)n);
  if (ncomp > 1) /* a (time, entity, component) dataset: start, stride, count */
    fprintf(fp, "            <DataItem Dimensions=\"3 3\" Format=\"XML\">%d 0 %d 1 1 1 1 %d 1</DataItem>\n"
                "            <DataItem Dimensions=\"%d %d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:%s</DataItem>\n",
            (int)step, (int)comp, (int)n, (int)nsteps, (int)n, (int)ncomp, dataset);
  else /* a (time, entity) dataset */
    fprintf(fp, "            <DataItem Dimensions=\"3 2\" Format=\"XML\">%d 0 1 1 1 %d</DataItem>\n"
                "            <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:%s</DataItem>\n",
            (int)step, (int)n, (int)nsteps, (int)n, dataset);
  fprintf(fp, "          </DataItem>\n        </Attribute>\n");
}

PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o) {
  MPI_Comm        comm = PetscObjectComm((PetscObject)p->dm);
  PetscMPIInt     rank;
  PetscInt        ncells, nverts, cloc = p->cEnd - p->cStart, vloc = 0, n;
  IS              vnum;
  const PetscInt *idx;
  char            vds[64];
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5PopTimestepping(o->viewer));
  PetscCall(PetscViewerPopFormat(o->viewer));
  PetscCall(PetscViewerDestroy(&o->viewer));
  PetscCall(DMDestroy(&o->dm6));
  PetscCall(DMDestroy(&o->dm1));
  /* Mesh sizes of the VIZ layout: all cells, and the vertices each owned by one rank. */
  PetscCall(DMPlexGetVertexNumbering(p->dm, &vnum));
  PetscCall(ISGetLocalSize(vnum, &n));
  PetscCall(ISGetIndices(vnum, &idx));
  for (PetscInt k = 0; k < n; k++) vloc += idx[k] >= 0;
  PetscCall(ISRestoreIndices(vnum, &idx));
  PetscCall(MPIU_Allreduce(&cloc, &ncells, 1, MPIU_INT, MPI_SUM, comm));
  PetscCall(MPIU_Allreduce(&vloc, &nverts, 1, MPIU_INT, MPI_SUM, comm));
  /* PETSc names a vertex field <vector name>_<field name> */
  PetscCall(PetscSNPrintf(vds, sizeof vds, "/vertex_fields/displacement_displacement"));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    char path[700];
    PetscCall(PetscSNPrintf(path, sizeof path, "%s/fields.xmf", o->dir));
    FILE *fp = fopen(path, "w");
    PetscCheck(fp, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write %s", path);
    fprintf(fp, "<?xml version=\"1.0\" ?>\n<!-- Written by the Cam-Clay IX driver: components 11 22 33 12 13 23; "
                "strains with engineering shear; per-cell values are averages over the quadrature points. -->\n"
                "<Xdmf Version=\"2.0\">\n  <Domain>\n    <Grid Name=\"fields\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
    for (PetscInt k = 0; k < o->nout; k++) {
      fprintf(fp, "      <Grid Name=\"step %d\" GridType=\"Uniform\">\n        <Time Value=\"%.17g\"/>\n", (int)k, o->times[k]);
      const int dim = (int)p->dim;
      fprintf(fp, "        <Topology TopologyType=\"%s\" NumberOfElements=\"%d\">\n"
                  "          <DataItem Dimensions=\"%d %d\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">fields.h5:/viz/topology/cells</DataItem>\n"
                  "        </Topology>\n        <Geometry GeometryType=\"%s\">\n"
                  "          <DataItem Dimensions=\"%d %d\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">fields.h5:/geometry/vertices</DataItem>\n"
                  "        </Geometry>\n",
              dim == 3 ? "Tetrahedron" : "Triangle", (int)ncells, (int)ncells, dim + 1, dim == 3 ? "XYZ" : "XY", (int)nverts, dim);
      const char *xyz[3] = {"x", "y", "z"};
      for (PetscInt d = 0; d < dim; d++) {
        char name[32];
        PetscCall(PetscSNPrintf(name, sizeof name, "displacement_%s", xyz[d]));
        hyperslab(fp, name, "Node", k, o->nout, nverts, dim, d, vds);
      }
      for (PetscInt f = 0; f < NCELLFIELDS; f++) {
        const CellField *cf = &cell_fields[f];
        if (cf->offset >= ST_STATEV && cf->offset + cf->nc > ST_STATEV + p->mat.nstatv) continue;
        char ds[64];
        PetscCall(PetscSNPrintf(ds, sizeof ds, "/cell_fields/%s_P0", cf->name));
        for (PetscInt j = 0; j < cf->nc; j++) {
          char name[64];
          if (cf->nc == 6) PetscCall(PetscSNPrintf(name, sizeof name, "%s_%s", cf->name, voigt[j]));
          else PetscCall(PetscSNPrintf(name, sizeof name, "%s", cf->name));
          hyperslab(fp, name, "Cell", k, o->nout, ncells, cf->nc, j, ds);
        }
      }
      fprintf(fp, "      </Grid>\n");
    }
    fprintf(fp, "    </Grid>\n  </Domain>\n</Xdmf>\n");
    fclose(fp);
  }
  PetscCall(PetscFree(o->times));
  PetscFunctionReturn(0);
}
