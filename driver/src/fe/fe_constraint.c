#include "fe_constraint.h"

#include <math.h>

/* The constraint directions of one point: an orthonormal basis E (k vectors of dim components) of the span of
   the normals given to it so far (Gram-Schmidt; a normal in the span already adds nothing). */
typedef struct {
  PetscInt  k;
  PetscReal E[3][3];
} PointSpan;

static void span_add(PointSpan *s, PetscInt dim, const PetscReal v[]) {
  PetscReal w[3] = {0, 0, 0}, norm = 0;
  for (PetscInt a = 0; a < dim; a++) w[a] = v[a];
  for (PetscInt i = 0; i < s->k; i++) {
    PetscReal d = 0;
    for (PetscInt a = 0; a < dim; a++) d += w[a] * s->E[i][a];
    for (PetscInt a = 0; a < dim; a++) w[a] -= d * s->E[i][a];
  }
  for (PetscInt a = 0; a < dim; a++) norm += w[a] * w[a];
  norm = PetscSqrtReal(norm);
  if (norm < 1e-10 || s->k == dim) return;
  for (PetscInt a = 0; a < dim; a++) s->E[s->k][a] = w[a] / norm;
  s->k++;
}

/* Whether the span is that of global axes (its projector diagonal, of zeros and ones), and which ones. */
static PetscBool span_axes(const PointSpan *s, PetscInt dim, PetscInt *mask) {
  *mask = 0;
  for (PetscInt a = 0; a < dim; a++)
    for (PetscInt b = 0; b < dim; b++) {
      PetscReal P = 0;
      for (PetscInt i = 0; i < s->k; i++) P += s->E[i][a] * s->E[i][b];
      if (a != b && PetscAbsReal(P) > 1e-12) return PETSC_FALSE;
      if (a == b && PetscAbsReal(P) > 1e-12 && PetscAbsReal(P - 1) > 1e-12) return PETSC_FALSE;
      if (a == b && P > 0.5) *mask |= 1 << a;
    }
  return PETSC_TRUE;
}

/* The frame of a point with an inclined constraint span: axes 0..k-1 the span's basis, the others the global
   axes from the last one on (z, then y, then x), each orthogonalised against the axes taken, the first whose
   remainder exceeds 1/2 (else the largest). R[i dim + j] = component i of axis j. */
static void span_frame(const PointSpan *s, PetscInt dim, PetscReal R[]) {
  PetscReal ax[3][3];
  PetscInt  taken = s->k, used[3] = {0, 0, 0};
  for (PetscInt i = 0; i < s->k; i++)
    for (PetscInt a = 0; a < dim; a++) ax[i][a] = s->E[i][a];
  for (PetscInt slot = dim - 1; slot >= s->k; slot--) {
    PetscReal best[3] = {0, 0, 0}, bestn = -1;
    PetscInt  besta = -1;
    for (PetscInt cand = dim - 1; cand >= 0; cand--) {
      if (used[cand]) continue;
      PetscReal w[3] = {0, 0, 0}, norm = 0;
      w[cand] = 1;
      for (PetscInt i = 0; i < taken; i++) {
        PetscInt  j = i < s->k ? i : dim - 1 - (i - s->k); /* the free axes fill the slots from the last */
        PetscReal d = 0;
        for (PetscInt a = 0; a < dim; a++) d += w[a] * ax[j][a];
        for (PetscInt a = 0; a < dim; a++) w[a] -= d * ax[j][a];
      }
      for (PetscInt a = 0; a < dim; a++) norm += w[a] * w[a];
      norm = PetscSqrtReal(norm);
      if (norm > bestn) {
        bestn = norm, besta = cand;
        for (PetscInt a = 0; a < dim; a++) best[a] = w[a];
      }
      if (norm > 0.5) break;
    }
    used[besta] = 1;
    for (PetscInt a = 0; a < dim; a++) ax[slot][a] = best[a] / bestn;
    taken++;
  }
  for (PetscInt i = 0; i < dim; i++)
    for (PetscInt j = 0; j < dim; j++) R[i * dim + j] = ax[j][i];
}

PetscErrorCode fe_label_points(DMLabel label, IS *points) {
  IS              valueIS, *parts;
  const PetscInt *values;
  PetscInt        nvalues;
  PetscFunctionBeginUser;
  PetscCall(DMLabelGetValueIS(label, &valueIS));
  PetscCall(ISGetLocalSize(valueIS, &nvalues));
  PetscCall(ISGetIndices(valueIS, &values));
  PetscCall(PetscMalloc1(PetscMax(nvalues, 1), &parts));
  for (PetscInt v = 0; v < nvalues; v++) {
    PetscCall(DMLabelGetStratumIS(label, values[v], &parts[v]));
    if (!parts[v]) PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 0, NULL, PETSC_OWN_POINTER, &parts[v]));
  }
  if (nvalues) PetscCall(ISConcatenate(PETSC_COMM_SELF, nvalues, parts, points));
  else PetscCall(ISCreateGeneral(PETSC_COMM_SELF, 0, NULL, PETSC_OWN_POINTER, points));
  for (PetscInt v = 0; v < nvalues; v++) PetscCall(ISDestroy(&parts[v]));
  PetscCall(PetscFree(parts));
  PetscCall(ISRestoreIndices(valueIS, &values));
  PetscCall(ISDestroy(&valueIS));
  PetscFunctionReturn(0);
}

/* Every group's points with dofs (their labels completed: closures), their constraint directions. */
static PetscErrorCode collect_spans(DM dm, const PetscInt nd[], const FeFixed *fixed, PetscInt nfixed, PointSpan *span) {
  PetscInt dim, pStart;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetChart(dm, &pStart, NULL));
  for (PetscInt f = 0; f < nfixed; f++) {
    DMLabel         label;
    IS              pointIS;
    const PetscInt *points;
    PetscInt        npoints;
    PetscCall(DMGetLabel(dm, fixed[f].group, &label));
    PetscCheck(label, PetscObjectComm((PetscObject)dm), PETSC_ERR_ARG_WRONG, "boundary condition: the mesh has no physical group '%s'",
               fixed[f].group);
    PetscCall(DMPlexLabelComplete(dm, label)); /* as PETSc does for DMAddBoundary's essential conditions */
    PetscCall(fe_label_points(label, &pointIS));
    PetscCall(ISGetLocalSize(pointIS, &npoints));
    PetscCall(ISGetIndices(pointIS, &points));
    for (PetscInt k = 0; k < npoints; k++) {
      PetscInt depth;
      PetscCall(DMPlexGetPointDepth(dm, points[k], &depth));
      if (!nd[depth]) continue;
      PointSpan *s = &span[points[k] - pStart];
      if (fixed[f].mirror) span_add(s, dim, fixed[f].normal);
      for (PetscInt c = 0; c < fixed[f].ncomp; c++) {
        PetscReal e[3] = {0, 0, 0};
        e[fixed[f].comp[c]] = 1;
        span_add(s, dim, e);
      }
    }
    PetscCall(ISRestoreIndices(pointIS, &points));
    PetscCall(ISDestroy(&pointIS));
  }
  PetscFunctionReturn(0);
}

/* The local section with the constrained components: one boundary condition of DMPlexCreateSection per set of
   constrained components (each point in exactly one), so that no label completion merges them. */
static PetscErrorCode create_section(DM dm, const PetscInt nd[], const PetscInt mask[]) {
  PetscInt     dim, pStart, pEnd, nbc = 0, bcField[8] = {0}, count[8] = {0}, *pts[8];
  IS           bcComps[8], bcPoints[8];
  PetscSection s;
  PetscFunctionBeginUser;
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  for (PetscInt q = pStart; q < pEnd; q++) count[mask[q - pStart]]++;
  for (PetscInt m = 1; m < (1 << dim); m++) {
    PetscInt comps[3], nc = 0, n = 0;
    if (!count[m]) continue;
    for (PetscInt j = 0; j < dim; j++)
      if (m >> j & 1) comps[nc++] = j;
    PetscCall(PetscMalloc1(count[m], &pts[nbc]));
    for (PetscInt q = pStart; q < pEnd; q++)
      if (mask[q - pStart] == m) pts[nbc][n++] = q;
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, nc, comps, PETSC_COPY_VALUES, &bcComps[nbc]));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, n, pts[nbc], PETSC_OWN_POINTER, &bcPoints[nbc]));
    nbc++;
  }
  PetscInt numDof[4] = {0, 0, 0, 0};
  for (PetscInt d = 0; d <= dim; d++) numDof[d] = nd[d];
  PetscCall(DMPlexCreateSection(dm, NULL, &dim, numDof, nbc, bcField, bcComps, bcPoints, NULL, &s));
  PetscCall(PetscSectionSetFieldName(s, 0, "displacement"));
  PetscCall(DMSetLocalSection(dm, s));
  PetscCall(PetscSectionDestroy(&s));
  for (PetscInt b = 0; b < nbc; b++) {
    PetscCall(ISDestroy(&bcComps[b]));
    PetscCall(ISDestroy(&bcPoints[b]));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_setup(FeConstraint *con, DM dm, PetscFE fe, const FeFixed *fixed, PetscInt nfixed) {
  PetscInt       dim, pStart, pEnd, *mask, *frame, storage;
  const PetscInt *nd;
  PointSpan     *span;
  PetscSection   s;
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(con, sizeof *con));
  PetscCall(DMGetDimension(dm, &dim));
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscFEGetNumDof(fe, &nd)); /* dofs on a point of each dimension (= depth: interpolated mesh) */
  PetscCall(PetscCalloc3(pEnd - pStart, &span, pEnd - pStart, &mask, pEnd - pStart, &frame));
  PetscCall(collect_spans(dm, nd, fixed, nfixed, span));
  con->dim = dim;
  for (PetscInt q = 0; q < pEnd - pStart; q++) {
    frame[q] = -1;
    if (!span[q].k) continue;
    con->n++;
    if (span[q].k == dim) mask[q] = (1 << dim) - 1; /* all components: no frame needed */
    else if (!span_axes(&span[q], dim, &mask[q])) mask[q] = (1 << span[q].k) - 1, frame[q] = con->nframe++;
  }
  PetscCall(create_section(dm, nd, mask));
  PetscCall(DMGetLocalSection(dm, &s));
  PetscCall(PetscSectionGetStorageSize(s, &storage));
  con->nnode = storage / dim;
  PetscCall(PetscMalloc4(con->n, &con->off, con->n, &con->mask, con->n, &con->frame, PetscMax(con->nnode, 1), &con->node_frame));
  PetscCall(PetscMalloc1(PetscMax(con->nframe, 1) * dim * dim, &con->R));
  for (PetscInt k = 0; k < con->nnode; k++) con->node_frame[k] = -1;
  for (PetscInt q = pStart, i = 0; q < pEnd; q++) {
    PetscInt off, ndof;
    PetscCall(PetscSectionGetDof(s, q, &ndof));
    PetscCall(PetscSectionGetOffset(s, q, &off));
    PetscCheck(ndof == 0 || (ndof == dim && off % dim == 0), PETSC_COMM_SELF, PETSC_ERR_SUP,
               "boundary conditions: a point with %d dofs at offset %d (expected one node of %d components)", (int)ndof, (int)off, (int)dim);
    if (!span[q - pStart].k) continue;
    con->off[i] = off, con->mask[i] = mask[q - pStart], con->frame[i] = frame[q - pStart];
    if (frame[q - pStart] >= 0) {
      span_frame(&span[q - pStart], dim, &con->R[frame[q - pStart] * dim * dim]);
      con->node_frame[off / dim] = frame[q - pStart];
    }
    i++;
  }
  PetscCall(PetscFree3(span, mask, frame));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_destroy(FeConstraint *con) {
  PetscFunctionBeginUser;
  PetscCall(PetscFree4(con->off, con->mask, con->frame, con->node_frame));
  PetscCall(PetscFree(con->R));
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_to_global(const FeConstraint *con, PetscScalar *u) {
  const PetscInt dim = con->dim;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < con->n; i++) {
    PetscScalar *up = &u[con->off[i]], g[3] = {0, 0, 0};
    for (PetscInt j = 0; j < dim; j++)
      if (con->mask[i] >> j & 1) up[j] = 0;
    if (con->frame[i] < 0) continue;
    const PetscReal *R = &con->R[con->frame[i] * dim * dim];
    for (PetscInt a = 0; a < dim; a++)
      for (PetscInt j = 0; j < dim; j++) g[a] += R[a * dim + j] * up[j];
    for (PetscInt a = 0; a < dim; a++) up[a] = g[a];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_to_frame(const FeConstraint *con, PetscScalar *f, PetscReal reaction[3]) {
  const PetscInt dim = con->dim;
  PetscReal      eye3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, eye2[4] = {1, 0, 0, 1};
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < con->n; i++) {
    PetscScalar     *fp = &f[con->off[i]], l[3] = {0, 0, 0};
    const PetscReal *R  = con->frame[i] >= 0 ? &con->R[con->frame[i] * dim * dim] : dim == 3 ? eye3 : eye2;
    for (PetscInt j = 0; j < dim; j++)
      for (PetscInt a = 0; a < dim; a++) l[j] += R[a * dim + j] * fp[a]; /* e_j . f */
    if (reaction)
      for (PetscInt j = 0; j < dim; j++)
        if (con->mask[i] >> j & 1)
          for (PetscInt a = 0; a < dim; a++) reaction[a] += R[a * dim + j] * PetscRealPart(l[j]);
    if (con->frame[i] >= 0)
      for (PetscInt j = 0; j < dim; j++) fp[j] = l[j];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_rotate_cell(const FeConstraint *con, const PetscInt dofs[], PetscInt nb, PetscScalar *Ke) {
  const PetscInt dim = con->dim;
  PetscFunctionBeginUser;
  if (!con->nframe) PetscFunctionReturn(0);
  for (PetscInt a = 0; a < nb / dim; a++) {
    const PetscInt fr = con->node_frame[dofs[a * dim] / dim];
    if (fr < 0) continue;
    const PetscReal *R = &con->R[fr * dim * dim];
    for (PetscInt c = 0; c < nb; c++) { /* rows of node a: R^T Ke */
      PetscScalar t[3] = {0, 0, 0};
      for (PetscInt j = 0; j < dim; j++)
        for (PetscInt i = 0; i < dim; i++) t[j] += R[i * dim + j] * Ke[(a * dim + i) * nb + c];
      for (PetscInt j = 0; j < dim; j++) Ke[(a * dim + j) * nb + c] = t[j];
    }
    for (PetscInt r = 0; r < nb; r++) { /* columns of node a: Ke R */
      PetscScalar t[3] = {0, 0, 0};
      for (PetscInt j = 0; j < dim; j++)
        for (PetscInt i = 0; i < dim; i++) t[j] += Ke[r * nb + a * dim + i] * R[i * dim + j];
      for (PetscInt j = 0; j < dim; j++) Ke[r * nb + a * dim + j] = t[j];
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode fe_constraint_node_frame(const FeConstraint *con, PetscInt off, PetscReal R[9]) {
  const PetscInt dim = con->dim, fr = con->node_frame[off / dim];
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < dim; i++)
    for (PetscInt j = 0; j < dim; j++) R[i * dim + j] = fr >= 0 ? con->R[fr * dim * dim + i * dim + j] : (PetscReal)(i == j);
  PetscFunctionReturn(0);
}
