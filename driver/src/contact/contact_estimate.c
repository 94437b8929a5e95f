/* The contact surface's share of the error indicator (contact_estimate.h). */
#include "contact_estimate.h"

#include "../fe/fe_estimate.h"
#include "contact_mortar.h"

#include <petscsf.h>

struct ContactEstimate {
  PetscInt   nf, nq;     /* facets here; Gauss points per facet */
  PetscInt  *cell, *vx;  /* nf: the facet's cell; nf x dim: its vertices (plex points) */
  PetscReal *Xv;         /* nf x dim x dim: the vertices' reference coordinates */
  PetscReal *nF, *meas;  /* nf x dim: the outward unit normal; nf: its measure (length, area) */
  PetscReal *L, *qw;     /* nq x dim barycentric coordinates and weights of the reference facet (measure 2) */
};

/* Facet k's data: cell, vertices, outward normal (away from its cell's centroid), measure. */
static PetscErrorCode facet_geometry(DM dm, PetscInt dim, PetscInt f, PetscInt k, struct ContactEstimate *e) {
  const PetscInt *supp;
  PetscInt       *cl = NULL, ncl, nv = 0, vStart, vEnd, off;
  PetscReal       meas, c[3], nrm[3], vol, cc[3], dot = 0, len = 0;
  PetscSection    cs;
  Vec             X;
  const PetscScalar *xa;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetSupport(dm, f, &supp));
  PetscCall(DMPlexComputeCellGeometryFVM(dm, f, &meas, c, nrm));
  PetscCall(DMPlexComputeCellGeometryFVM(dm, supp[0], &vol, cc, NULL));
  for (PetscInt d = 0; d < dim; d++) dot += nrm[d] * (c[d] - cc[d]), len += nrm[d] * nrm[d];
  for (PetscInt d = 0; d < dim; d++) e->nF[k * dim + d] = (dot < 0 ? -nrm[d] : nrm[d]) / PetscSqrtReal(len);
  e->cell[k] = supp[0], e->meas[k] = meas;
  PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
  PetscCall(DMGetCoordinateSection(dm, &cs));
  PetscCall(DMGetCoordinatesLocal(dm, &X));
  PetscCall(VecGetArrayRead(X, &xa));
  PetscCall(DMPlexGetTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  for (PetscInt j = 0; j < ncl && nv < dim; j++) {
    const PetscInt pt = cl[2 * j];
    if (pt < vStart || pt >= vEnd) continue;
    PetscCall(PetscSectionGetOffset(cs, pt, &off));
    for (PetscInt d = 0; d < dim; d++) e->Xv[(k * dim + nv) * dim + d] = PetscRealPart(xa[off + d]);
    e->vx[k * dim + nv++] = pt;
  }
  PetscCall(DMPlexRestoreTransitiveClosure(dm, f, PETSC_TRUE, &ncl, &cl));
  PetscCall(VecRestoreArrayRead(X, &xa));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_estimate_setup(FeProblem *p, DMLabel label, Contact *ct) {
  const FeSpace          *sp  = fe_problem_space(p);
  const PetscInt          dim = sp->dim;
  struct ContactEstimate *e;
  PetscInt               *facets;
  PetscFunctionBeginUser;
  PetscCall(PetscNew(&e));
  ct->est = e;
  /* Gauss points of degree 4: the square of a linear residual on a facet, with the weight 2 pi r */
  PetscCall(contact_facet_rule(dim, 4, &e->nq, &e->L, &e->qw));
  PetscCall(contact_facets(sp->dm, label, &e->nf, &facets));
  const PetscInt nf = PetscMax(e->nf, 1);
  PetscCall(PetscMalloc5(nf, &e->cell, nf * dim, &e->vx, nf * dim * dim, &e->Xv, nf * dim, &e->nF, nf, &e->meas));
  for (PetscInt k = 0; k < e->nf; k++) PetscCall(facet_geometry(sp->dm, dim, facets[k], k, e));
  PetscCall(PetscFree(facets));
  PetscFunctionReturn(0);
}

PetscErrorCode contact_estimate_destroy(Contact *ct) {
  struct ContactEstimate *e = ct->est;
  PetscFunctionBeginUser;
  if (!e) PetscFunctionReturn(0);
  PetscCall(PetscFree2(e->L, e->qw));
  PetscCall(PetscFree5(e->cell, e->vx, e->Xv, e->nF, e->meas));
  PetscCall(PetscFree(ct->est));
  PetscFunctionReturn(0);
}

/* lambda_i n_i of every plex vertex (dim values; zero off the contact nodes), the owners' values on the ghosts too. */
static PetscErrorCode vertex_pressures(Contact *ct, Vec lam, DM dm, PetscReal **ln) {
  const PetscInt     dim = ct->dim;
  PetscInt           pStart, pEnd;
  const PetscScalar *la;
  PetscSF            sf;
  MPI_Datatype       unit;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(dm, &pStart, &pEnd));
  PetscCall(PetscCalloc1((pEnd - pStart) * dim + 1, ln));
  PetscCall(VecGetArrayRead(lam, &la));
  for (PetscInt i = 0; i < ct->n; i++)
    for (PetscInt d = 0; d < dim; d++) (*ln)[(ct->vtx[i] - pStart) * dim + d] = PetscRealPart(la[i]) * ct->nrm[i * dim + d];
  PetscCall(VecRestoreArrayRead(lam, &la));
  PetscCall(DMGetPointSF(dm, &sf));
  PetscCallMPI(MPI_Type_contiguous((int)dim, MPIU_REAL, &unit));
  PetscCallMPI(MPI_Type_commit(&unit));
  PetscCall(PetscSFBcastBegin(sf, unit, *ln, *ln, MPI_REPLACE));
  PetscCall(PetscSFBcastEnd(sf, unit, *ln, *ln, MPI_REPLACE));
  PetscCallMPI(MPI_Type_free(&unit));
  PetscFunctionReturn(0);
}

/* The traction sigma n of a Voigt stress (11, 22, 33, 12, 13, 23; 2D: 11, 22, 33, 12). */
static void traction(PetscInt dim, const PetscReal s[6], const PetscReal n[], PetscReal t[]) {
  if (dim == 2) {
    t[0] = s[0] * n[0] + s[3] * n[1], t[1] = s[3] * n[0] + s[1] * n[1];
    return;
  }
  t[0] = s[0] * n[0] + s[3] * n[1] + s[4] * n[2];
  t[1] = s[3] * n[0] + s[1] * n[1] + s[5] * n[2];
  t[2] = s[4] * n[0] + s[5] * n[1] + s[2] * n[2];
}

PetscErrorCode contact_estimate(Contact *ct, Vec lam, FeProblem *p) {
  const FeSpace          *sp  = fe_problem_space(p);
  const PetscInt          dim = ct->dim;
  struct ContactEstimate *e   = ct->est;
  PetscInt                pStart;
  PetscReal              *ln;
  PetscFunctionBeginUser;
  PetscCall(DMPlexGetChart(sp->dm, &pStart, NULL));
  PetscCall(vertex_pressures(ct, lam, sp->dm, &ln));
  for (PetscInt k = 0; k < e->nf; k++) {
    PetscReal e2 = 0;
    for (PetscInt q = 0; q < e->nq; q++) {
      const PetscReal *L = &e->L[q * dim];
      PetscReal        X[3] = {0, 0, 0}, s[6], t[3], r2 = 0, dA;
      for (PetscInt a = 0; a < dim; a++)
        for (PetscInt d = 0; d < dim; d++) X[d] += L[a] * e->Xv[(k * dim + a) * dim + d];
      PetscCall(fe_estimate_stress_at(p, e->cell[k], X, s));
      traction(dim, s, &e->nF[k * dim], t);
      for (PetscInt d = 0; d < dim; d++) { /* sigma_h n_F - (lambda n)_h */
        PetscReal lnd = 0;
        for (PetscInt a = 0; a < dim; a++) lnd += L[a] * ln[(e->vx[k * dim + a] - pStart) * dim + d];
        r2 += PetscSqr(t[d] - lnd);
      }
      dA = e->qw[q] * e->meas[k] / 2 * fe_space_weight(sp, X[0]);
      e2 += r2 * dA;
    }
    /* h_F: the facet's length (2D), the edge of the equilateral triangle of its area (3D) */
    const PetscReal hF = dim == 2 ? e->meas[k] : PetscSqrtReal(4 * e->meas[k] / PetscSqrtReal(3.0));
    fe_estimate_add_surface(p, e->cell[k], hF * e2);
  }
  PetscCall(PetscFree(ln));
  PetscFunctionReturn(0);
}
