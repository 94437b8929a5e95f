/* PETSc options the driver sets as defaults: a value only where the command line or the scene gave none. */
#ifndef OPTIONS_H
#define OPTIONS_H

#include <petscsys.h>

/* Sets option name to value unless it is set already (the user's choice wins). */
PetscErrorCode options_default(const char *name, const char *value);

#endif
