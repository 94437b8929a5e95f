/* Field output: one HDF5 file, fields.h5, with each field stored once per output, and an XDMF3 index,
 * fields.xmf, that ParaView (Xdmf3ReaderS, Xdmf3ReaderT) and meshio read as a time series. Layout
 * (docs/driver.md, "Output"), every array in the serial mesh's order (fe_natural.h: the same file on any
 * number of ranks):
 *   /mesh/coordinates          (nnodes, dim)       node coordinates (2D: x y, axisymmetric: r z); P1: the
 *                                                  vertices; P2: the vertices, then the edge midpoints
 *   /mesh/cells                (ncells, n)         node numbers of each simplex, positively oriented, in VTK's
 *                                                  order: n = dim + 1 (P1), or 10 / 6 with the mid-side nodes
 *                                                  (P2: Tetrahedron_10, Triangle_6)
 *   /time                      (nout,)             the output times
 *   /fields/displacement/<k>   (nnodes, 3)         at the nodes (P2: the field's own values at the vertices and
 *                                                  mid-sides); 2D padded with a zero third component
 *   /fields/<name>/<k>         (ncells, 9) or (ncells,)  cell averages over the quadrature points of stress,
 *                                                  strain, evp_hard, evp_soft, evp as full 3x3 tensors, row by
 *                                                  row (11 12 13 21 22 23 31 32 33; strains as tensors,
 *                                                  eps_12 = gamma_12 / 2), and of pc_hard, pc_soft, phi,
 *                                                  error_indicator, error_indicator_max (fe_estimate.h)
 * with <k> the output number as six digits. The .xmf is rewritten after every output.
 *
 * Output files of a fresh run are first written as fields.h5.part and fields.xmf.part (this index names
 * fields.h5.part, so it shows this run's outputs, never an earlier run's); fe_output_promote renames the
 * data to fields.h5, writes fields.xmf for it and removes the .part index, so a run that fails before its
 * first valid output leaves an earlier run's results untouched. */
#ifndef FE_OUTPUT_H
#define FE_OUTPUT_H

#include "fe_natural.h"
#include "fe_problem.h"

typedef struct {
  MPI_Comm    comm;
  PetscViewer viewer;
  PetscInt    nout, cap;
  PetscReal  *times;          /* the output times written so far */
  char        dir[512];
  PetscBool   promoted;       /* the files have their final names (always so when appending) */
  FeNatural   nodes, cells;   /* the owned nodes (vertices; P2: and edges) and cells, in natural order */
  PetscInt    npc;            /* nodes per cell */
} FeOutput;

/* append: continue the fields.h5 of a checkpointed run (-restart), whose times fe_output_resume gives. */
PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o);
PetscErrorCode fe_output_resume(FeOutput *o, PetscInt nout, const PetscReal *times);
/* The fields at time; report: a time the run reports at, whose error indicator enters its history (fe_estimate.h). */
PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, PetscBool report, FeOutput *o);
/* Rename fields.h5.part to fields.h5, write fields.xmf for it and remove fields.xmf.part (collective; rank 0
 * renames). Safe to call more than once; a no-op when appending. */
PetscErrorCode fe_output_promote(FeProblem *p, FeOutput *o);
PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o);

#endif
