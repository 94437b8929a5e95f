/* The driver's own options (-checkpoint_every, -fe_*, -indent_*, ...): each module declares and reads them in
 * one PetscOptionsBegin/End block through these functions, each option with its default and its range (an
 * integer's [lo, hi], a number's interval, a word's choices), which check the value first (the message names the
 * option, its value and the range, io/text.h) and remember the name, so that main can call every module's block
 * before the run and refuse a bad value or a misspelt option of the driver's (options_check_unknown) before
 * anything runs, and -help lists them all with their ranges ("[1 to 10000]") and defaults. PETSc options the
 * driver sets as defaults: options_default. */
#ifndef OPTIONS_H
#define OPTIONS_H

#include <petscsys.h>

/* Sets option name to value unless it is set already (the user's choice wins). */
PetscErrorCode options_default(const char *name, const char *value);
/* Whether name was set by options_default, not by the user (the warning about unused options leaves it out). */
int options_set_by_driver(const char *name);

/* Inside PetscOptionsBegin/End (PetscOptionsObject is the block's). */
PetscErrorCode options_int(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscInt def, PetscInt lo,
                           PetscInt hi, PetscInt *value, PetscBool *set);
/* A number in [lo, hi] (NAN: no bound on that side; open: OPTIONS_LO_OPEN, OPTIONS_HI_OPEN for > lo, < hi). */
enum { OPTIONS_LO_OPEN = 1, OPTIONS_HI_OPEN = 2 };
PetscErrorCode options_real(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscReal def, PetscReal lo,
                            PetscReal hi, unsigned open, PetscReal *value, PetscBool *set);
PetscErrorCode options_bool(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscBool def,
                            PetscBool *value, PetscBool *set);
PetscErrorCode options_string(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, const char *def,
                              char *value, size_t len, PetscBool *set);
PetscErrorCode options_elist(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, const char *const *list,
                             PetscInt n, PetscInt def, PetscInt *value, PetscBool *set);

/* A module's PETSc solver takes this options prefix (KSPSetOptionsPrefix: "indent_"): the options of PETSc's objects
 * under it (-indent_ksp_*, -indent_pc_*, -indent_mat_*, -indent_fieldsplit_*) are PETSc's to check, not the driver's. */
void options_petsc_prefix(const char *prefix);

/* After every module's block has run: an option given (on the command line or, source non-NULL, in a scene's
 * solver.options) that starts like one of the driver's options (its first word: -indent_, -fe_, -checkpoint_,
 * ..., or one of extra_prefixes) but is none of them is an error: fills err ("option -checkpoint_evry: not an
 * option of the driver (misspelt -checkpoint_every?) ...") and sets *bad. names: the options to check (NULL:
 * every option never read so far). */
PetscErrorCode options_check_unknown(const char *const *names, int n, const char *const *extra_prefixes, const char *source, char *err,
                                     size_t errlen, PetscBool *bad);

/* After the blocks' first reading (main): the driver's options given are marked as not read again, so that
 * the warning at the end of a run still names one that this kind of scene never reads (-indent_rtol for a point
 * scene). */
PetscErrorCode options_forget_reads(void);

#endif
