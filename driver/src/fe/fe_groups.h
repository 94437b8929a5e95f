/* The physical groups a scene names, checked against what each key needs before anything is set up
 * (issue 23): a mirror plane is a flat group of faces on the body's boundary with the normal given; a
 * pressure, a traction and the indenter's contact surface are faces on the boundary; fixed components act on
 * points, edges or faces, never on a group of cells (which would hold every node of a volume). Every message
 * names the scene file, the key, the group and what it is. */
#ifndef FE_GROUPS_H
#define FE_GROUPS_H

#include <petscdmplex.h>

#include "../io/yaml_doc.h"
#include "fe_scene.h"

/* A group's shape over all ranks. Collective. */
typedef struct {
  PetscInt  top_dim;           /* the highest dimension of its points (-1: it has none) */
  PetscInt  nfacets, ninside;  /* its facets (dimension dim - 1), and those inside the body (two cells) */
  PetscReal spread, size;      /* max - min of x . n over the vertices of its closure (n given); the mesh's diagonal */
} FeGroupShape;
PetscErrorCode fe_group_shape(DM dm, const char *group, const PetscReal n[], FeGroupShape *g);

/* Every group of boundary.fixed, .mirror, .pressure, .traction and (contact_group non-NULL) indenter.contact,
 * each a label of dm (checked before). The first that does not fit its key sets *bad = 2 with err filled (else
 * *bad = 0). Collective. */
PetscErrorCode fe_groups_check(YdDoc *doc, const FeScene *sc, const char *contact_group, DM dm, char *err, size_t errlen, int *bad);

#endif
