/* The contact's part of a checkpoint's shared file (PETSc HDF5): per potential contact node its committed
 * multiplier, the multiplier's last increment (the predictor's) and whether it is active, stored at its vertex's
 * place in the serial mesh's order (fe/fe_natural.h), so that the indentation restarts on any number of ranks
 * with the same multipliers at the same nodes. */
#ifndef CONTACT_IO_H
#define CONTACT_IO_H

#include <petscviewer.h>

#include "contact.h"

/* lam0, ratelam: vectors of the contact nodes (ct->n here). Collective. */
PetscErrorCode contact_io_view(const Contact *ct, DM dm, PetscViewer v, Vec lam0, Vec ratelam);
/* Read back into lam0, ratelam and ct->active; a node the file has no entry for is an error. Collective. */
PetscErrorCode contact_io_read(Contact *ct, DM dm, PetscViewer v, Vec lam0, Vec ratelam);

#endif
