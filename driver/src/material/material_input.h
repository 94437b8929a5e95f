/* The 'material:' block of a scene: which PROPS the UMAT gets (theory.md's Woodford values by name,
 * overrides by slot name), the bedding normal, NSTATV; checked with the UMAT's own property check. */
#ifndef MATERIAL_INPUT_H
#define MATERIAL_INPUT_H

#include <petscsys.h>

#include "../io/yaml_doc.h"
#include "umat_call.h"

/* Read the block into mat (ntens must already be set). Returns 0, or 1 with err filled. */
/* The PROPS and STATEV slots of Cam-Clay IX (camclay != 0) or none (all -1): UmatMaterial.pr and .sv. */
void material_slots(int camclay, UmatPropSlots *pr, UmatStateSlots *sv);
int material_read(const YdDoc *doc, YdNode *node, int ntens, UmatMaterial *mat, char *err, size_t errlen);

/* -material_set (declared and read here; io/options.h): its text, whether given. */
PetscErrorCode material_options(char *set, size_t n, PetscBool *given);

/* Index (0-based) of a named Cam-Clay IX PROPS slot, or -1. */
int material_slot(const char *name);
/* The PROPS slots' names, comma-separated, into buf (for messages); returns buf. */
const char *material_slot_list(char *buf, size_t n);

#endif
