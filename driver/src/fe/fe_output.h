/* Field output for ParaView: one HDF5 file written by PETSc's viewer in its VIZ layout (mesh,
 * displacement at the vertices, per-cell averages over the quadrature points of stress, per-frame and
 * overall viscoplastic strain, pc per frame and phi) as a time series, and an XDMF file that names
 * every tensor component explicitly (11 22 33 12 13 23, the UMAT's Voigt order, strains engineering),
 * so that nothing depends on a reader's component order (PETSc's own XDMF script orders tensors
 * xx yy zz xy yz xz). */
#ifndef FE_OUTPUT_H
#define FE_OUTPUT_H

#include "fe_problem.h"

typedef struct {
  PetscViewer viewer;
  DM          dm6, dm1;    /* P0 cell fields with 6 and 1 components */
  PetscInt    nout, cap;
  PetscReal  *times;
  char        dir[512];
} FeOutput;

/* append: continue the fields.h5 of a checkpointed run (-restart), whose times fe_output_resume gives. */
PetscErrorCode fe_output_open(FeProblem *p, const char *outdir, PetscBool append, FeOutput *o);
PetscErrorCode fe_output_resume(FeOutput *o, PetscInt nout, const PetscReal *times);
PetscErrorCode fe_output_write(FeProblem *p, Vec U, PetscReal time, FeOutput *o);
PetscErrorCode fe_output_close(FeProblem *p, FeOutput *o);

#endif
