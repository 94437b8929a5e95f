/* Field output: one HDF5 file, fields.h5, with each field stored once per output, and an XDMF3 index,
 * fields.xmf, that ParaView (Xdmf3ReaderS, Xdmf3ReaderT) and meshio read as a time series. Layout
 * (docs/driver.md, "Output"):
 *   /mesh/coordinates          (nverts, dim)       vertex coordinates (2D: x y, axisymmetric: r z)
 *   /mesh/cells                (ncells, dim + 1)   vertex numbers of each simplex, positively oriented
 *   /time                      (nout,)             the output times
 *   /fields/displacement/<k>   (nverts, 3)         at the vertices (P2: the vertex values, i.e. the P1
 *                                                  interpolant); 2D padded with a zero third component
 *   /fields/<name>/<k>         (ncells, 6) or (ncells,)  cell averages over the quadrature points of
 *                                                  stress, strain, evp_hard, evp_soft, evp (6 components,
 *                                                  Voigt 11 22 33 12 13 23, strains with engineering
 *                                                  shear), pc_hard, pc_soft, phi
 * with <k> the output number as six digits. The .xmf is rewritten after every output.
 *
 * Output files of a fresh run are first written as fields.h5.part and fields.xmf.part (the .xmf refers
 * to fields.h5, so it is valid after the rename); fe_output_promote renames them to their final names,
 * so a run that fails before its first valid output leaves an earlier run's results untouched. */
#ifndef FE_OUTPUT_H
#define FE_OUTPUT_H

#include "fe_problem.h"

typedef struct {
  MPI_Comm    comm;
  PetscViewer viewer;
  PetscInt    nout, cap;
  PetscReal  *times;          /* the output times written so far */
  char        dir[512];
  PetscBool   promoted;       /* the files have their final names (always so when appending) */
  PetscInt    nv, nc;         /* global vertices and cells */
  PetscInt    nvloc, ncloc;   /* those owned by this rank, a contiguous block of the global numbering */
  PetscInt   *vown, *cown;    /* their local mesh points, in global order */
} FeOutput;

/* append: continue the fields.h5 of a checkpointed run (-restart), whose times fe_output_resume gives. */
PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o);
PetscErrorCode fe_output_resume(FeOutput *o, PetscInt nout, const PetscReal *times);
PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, FeOutput *o);
/* Rename fields.h5.part and fields.xmf.part to fields.h5 and fields.xmf (collective; rank 0 renames).
 * Safe to call more than once; a no-op when appending. */
PetscErrorCode fe_output_promote(FeOutput *o);
PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o);

#endif
