#include "fe_groups.h"

#include <petscsf.h>

#include <stdio.h>
#include <string.h>

#include "fe_constraint.h"

/* Each point's number of cells over all ranks (a face on a partition boundary has one on each side). */
static PetscErrorCode global_support(DM dm, PetscInt **supp) {
  PetscInt pStart, pEnd, *local;
  PetscSF  sf;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscMalloc1(pEnd - pStart + 1, &local));
  PetscCall(PetscCalloc1(pEnd - pStart + 1, supp));
  for (PetscInt p = pStart; p < pEnd; p++) PetscCall(DMPlexGetSupportSize(dm, p, &local[p - pStart]));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscArraycpy(*supp, local, pEnd - pStart));
  PetscCall(PetscSFReduceBegin(sf, MPIU_INT, local, *supp, MPI_SUM));
  PetscCall(PetscSFReduceEnd(sf, MPIU_INT, local, *supp, MPI_SUM));
  PetscCall(PetscSFBcastBegin(sf, MPIU_INT, *supp, *supp, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, MPIU_INT, *supp, *supp, MPI_REPLACE));
  PetscCall(PetscFree(local));
  PetscFunctionReturn(0);
}

/* Whether point p is a ghost here (another rank owns it). */
static PetscErrorCode is_ghost(PetscInt nleaves, const PetscInt *leaves, PetscInt p, PetscBool *ghost) {
  PetscInt loc = -1;
  PetscFunctionBeginUser;
  if (leaves) PetscCall(PetscFindInt(p, nleaves, leaves, &loc));
  *ghost = (leaves ? loc >= 0 : p < nleaves) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode fe_group_shape(DM dm, const char *group, const PetscReal n[], FeGroupShape *g) {
  MPI_Comm           comm = PetscObjectComm((PetscObject)dm);
  DMLabel            label;
  IS                 pointIS;
  const PetscInt    *pts, *leaves;
  PetscInt           dim, npts, pStart, vStart, vEnd, *supp, top = -1, cnt[2] = {0, 0}, nleaves, *sorted = NULL;
  PetscReal          lo = PETSC_MAX_REAL, hi = -PETSC_MAX_REAL, gmin[3] = {0, 0, 0}, gmax[3] = {0, 0, 0};
  PetscSection       cs;
  Vec                coords;
  const PetscScalar *x;
  PetscSF            sf;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMGetLabel(dm, group, &label));
  PetscCheck(label, comm, PETSC_ERR_ARG_WRONG, "the mesh has no physical group '%s'", group);
  PetscCall(global_support(dm, &supp));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCall(PetscSFGetGraph(sf, NULL, &nleaves, &leaves, NULL));
  if (leaves) { /* sorted, for the ghost test */
    PetscCall(PetscMalloc1(nleaves + 1, &sorted));
    PetscCall(PetscArraycpy(sorted, leaves, nleaves));
    PetscCall(PetscSortInt(nleaves, sorted));
  }
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinatesLocal(dm, &coords));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(VecGetArrayRead(coords, &x));
  PetscCall(fe_label_points(label, &pointIS));
  PetscCall(ISGetLocalSize(pointIS, &npts));
  PetscCall(ISGetIndices(pointIS, &pts));
  for (PetscInt k = 0; k < npts; k++) {
    PetscInt  depth, *cl = NULL, ncl;
    PetscBool ghost = PETSC_TRUE;
    PetscCall(DMPlexGetPointDepth(dm, pts[k], &depth));
    top = PetscMax(top, depth);
    if (depth == dim - 1) PetscCall(is_ghost(nleaves, sorted ? sorted : leaves, pts[k], &ghost));
    if (depth == dim - 1 && !ghost) cnt[0]++, cnt[1] += supp[pts[k] - pStart] > 1;
    PetscCall(DMPlexGetTransitiveClosure(dm, pts[k], PETSC_TRUE, &ncl, &cl));
    for (PetscInt j = 0; j < 2 * ncl; j += 2) {
      PetscInt  off;
      PetscReal d = 0;
      if (cl[j] < vStart || cl[j] >= vEnd) continue;
      PetscCall(PetscSectionGetOffset(cs, cl[j], &off));
      for (PetscInt a = 0; a < dim; a++) d += PetscRealPart(x[off + a]) * (n ? n[a] : 0);
      lo = PetscMin(lo, d), hi = PetscMax(hi, d);
    }
    PetscCall(DMPlexRestoreTransitiveClosure(dm, pts[k], PETSC_TRUE, &ncl, &cl));
  }
  PetscCall(ISRestoreIndices(pointIS, &pts));
  PetscCall(ISDestroy(&pointIS));
  PetscCall(VecRestoreArrayRead(coords, &x));
  PetscCall(PetscFree(supp));
  PetscCall(PetscFree(sorted));
  PetscCall(MPIU_Allreduce(&top, &g->top_dim, 1, MPIU_INT, MPI_MAX, comm));
  PetscInt all[2];
  PetscCall(MPIU_Allreduce(cnt, all, 2, MPIU_INT, MPI_SUM, comm));
  g->nfacets = all[0], g->ninside = all[1];
  PetscReal glo, ghi;
  PetscCall(MPIU_Allreduce(&lo, &glo, 1, MPIU_REAL, MPIU_MIN, comm));
  PetscCall(MPIU_Allreduce(&hi, &ghi, 1, MPIU_REAL, MPIU_MAX, comm));
  g->spread = ghi >= glo ? ghi - glo : 0;
  PetscCall(DMGetBoundingBox(dm, gmin, gmax));
  g->size = 0;
  for (PetscInt a = 0; a < dim; a++) g->size += PetscSqr(gmax[a] - gmin[a]);
  g->size = PetscSqrtReal(g->size);
  PetscFunctionReturn(0);
}

/* What a group of points of dimension d is, in words. */
static const char *kind_of(PetscInt d, PetscInt dim) {
  if (d < 0) return "empty (no mesh entity)";
  if (d == dim) return dim == 3 ? "a group of 3D cells (a gmsh Physical Volume)" : "a group of 2D cells (a gmsh Physical Surface)";
  if (d == dim - 1) return dim == 3 ? "a group of faces" : "a group of edges";
  return d == 0 ? "a group of points" : "a group of edges (a curve)";
}

/* The line of key 'group' of list[k] under boundary.LIST (or of boundary.LIST[k] itself when it is a name). */
static int entry_line(YdDoc *doc, const char *list, size_t k) {
  YdNode *b = yd_get(doc->root, "boundary"), *l = b ? yd_get(b, list) : NULL;
  if (!l || l->kind != YD_SEQUENCE || k >= l->n) return b ? b->line : 0;
  return l->items[k]->kind == YD_MAPPING ? yd_key_line(l->items[k], "group") : l->items[k]->line;
}

/* The group of a key that needs faces of the boundary (mirror, pressure, traction, contact). */
static int need_boundary_faces(YdDoc *doc, int line, const char *key, const char *what, const char *group, const FeGroupShape *g,
                               PetscInt dim, char *err, size_t errlen) {
  if (g->top_dim != dim - 1) {
    snprintf(err, errlen, "%s:%d: key '%s': the group '%s' is %s: %s needs a group of %s on the body's boundary (a gmsh Physical %s)",
             doc->file, line, key, group, kind_of(g->top_dim, dim), what, dim == 3 ? "faces" : "edges", dim == 3 ? "Surface" : "Curve");
    return 2;
  }
  if (g->ninside > 0) {
    snprintf(err, errlen, "%s:%d: key '%s': the group '%s' has %d of its %d %s inside the body (between two cells): %s needs them on the "
             "body's boundary", doc->file, line, key, group, (int)g->ninside, (int)g->nfacets, dim == 3 ? "faces" : "edges", what);
    return 2;
  }
  return 0;
}

/* The checks below: bad input sets *bad = 2 with err filled (and stops); a PETSc failure is returned. */
static PetscErrorCode check_mirrors(YdDoc *doc, const FeScene *sc, DM dm, PetscInt dim, char *err, size_t errlen, int *bad) {
  PetscFunctionBeginUser;
  for (int k = 0; k < sc->nfixed && !*bad; k++) {
    const FeFixed *m = &sc->fixed[k];
    FeGroupShape   g;
    char           key[64];
    if (!m->mirror) continue;
    PetscCall(fe_group_shape(dm, m->group, m->normal, &g));
    snprintf(key, sizeof key, "boundary.mirror[%d].group", m->index);
    *bad = need_boundary_faces(doc, entry_line(doc, "mirror", (size_t)m->index), key, "a mirror plane", m->group, &g, dim, err, errlen);
    if (!*bad && g.spread > 1e-6 * g.size) {
      snprintf(err, errlen, "%s:%d: key 'boundary.mirror[%d].normal': the group '%s' is not a plane normal to [%.6g, %.6g, %.6g]: "
               "x . normal varies by %.3g over its nodes (the mesh %s is %.3g across; expected at most 1e-6 of that)", doc->file, m->line,
               m->index, m->group, m->normal[0], m->normal[1], m->normal[2], g.spread, sc->msh, g.size);
      *bad = 2;
    }
  }
  PetscFunctionReturn(0);
}

static PetscErrorCode check_fixed(YdDoc *doc, const FeScene *sc, DM dm, PetscInt dim, char *err, size_t errlen, int *bad) {
  PetscFunctionBeginUser;
  for (int k = 0, i = 0; k < sc->nfixed && !*bad; k++) {
    const FeFixed *f = &sc->fixed[k];
    FeGroupShape   g;
    if (f->mirror) continue;
    PetscCall(fe_group_shape(dm, f->group, NULL, &g));
    if (g.top_dim >= dim || g.top_dim < 0) {
      snprintf(err, errlen, "%s:%d: key 'boundary.fixed[%d].group': the group '%s' is %s: fixed components act on points, edges or "
               "faces (on a group of cells every node of it would be held)", doc->file, entry_line(doc, "fixed", (size_t)i), i, f->group,
               kind_of(g.top_dim, dim));
      *bad = 2;
    }
    i++;
  }
  PetscFunctionReturn(0);
}

/* boundary.pressure and boundary.traction: names straight from the scene (a traction loads GROUP.x, ...). */
static PetscErrorCode check_loads(YdDoc *doc, DM dm, PetscInt dim, char *err, size_t errlen, int *bad) {
  const char *lists[2] = {"pressure", "traction"};
  YdNode     *b        = yd_get(doc->root, "boundary");
  PetscFunctionBeginUser;
  for (int l = 0; l < 2 && !*bad; l++) {
    YdNode *x = b ? yd_get(b, lists[l]) : NULL;
    for (size_t k = 0; x && x->kind == YD_SEQUENCE && k < x->n && !*bad; k++) {
      FeGroupShape g;
      char         key[64], what[32];
      if (x->items[k]->kind != YD_SCALAR) continue;
      PetscCall(fe_group_shape(dm, x->items[k]->text, NULL, &g));
      snprintf(key, sizeof key, "boundary.%s[%zu]", lists[l], k);
      snprintf(what, sizeof what, "a %s", lists[l]);
      *bad = need_boundary_faces(doc, x->items[k]->line, key, what, x->items[k]->text, &g, dim, err, errlen);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_groups_check(YdDoc *doc, const FeScene *sc, const char *contact_group, DM dm, char *err, size_t errlen, int *bad) {
  PetscInt dim;
  PetscFunctionBeginUser;
  *bad = 0;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(check_fixed(doc, sc, dm, dim, err, errlen, bad));
  if (!*bad) PetscCall(check_mirrors(doc, sc, dm, dim, err, errlen, bad));
  if (!*bad) PetscCall(check_loads(doc, dm, dim, err, errlen, bad));
  if (!*bad && contact_group) {
    FeGroupShape g;
    YdNode      *ind = yd_get(doc->root, "indenter");
    PetscCall(fe_group_shape(dm, contact_group, NULL, &g));
    *bad = need_boundary_faces(doc, yd_key_line(ind, "contact"), "indenter.contact", "the potential contact surface", contact_group, &g,
                               dim, err, errlen);
  }
  PetscFunctionReturn(0);
}
