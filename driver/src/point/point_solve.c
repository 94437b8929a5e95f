/* One step of a material point under mixed stress/strain control: Newton on the unknown strain components
 * with the UMAT's DDSDDE (the equations of the segment's controls and constraints), a check of DDSDDE
 * against central differences. */
#include "point_solve.h"


#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#define MAX_NEWTON 30


/* Solve J x = r in place (n <= 6), partial pivoting. Returns 1 if singular. */
static int solve_small(int n, double J[6][6], double r[6]) {
  for (int k = 0; k < n; k++) {
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(J[i][k]) > fabs(J[p][k])) p = i;
    if (J[p][k] == 0) return 1;
    if (p != k) {
      for (int j = 0; j < n; j++) {
        double t = J[k][j];
        J[k][j] = J[p][j], J[p][j] = t;
      }
      double t = r[k];
      r[k] = r[p], r[p] = t;
    }
    for (int i = k + 1; i < n; i++) {
      double m = J[i][k] / J[k][k];
      for (int j = k; j < n; j++) J[i][j] -= m * J[k][j];
      r[i] -= m * r[k];
    }
  }
  for (int i = n - 1; i >= 0; i--) {
    for (int j = i + 1; j < n; j++) r[i] -= J[i][j] * r[j];
    r[i] /= J[i][i];
  }
  return 0;
}

double point_interp(const Segment *sg, int col, double t) {
  const double *tt = sg->table_time;
  int           n  = sg->table_rows;
  if (t <= tt[0]) return sg->table[col];
  if (t >= tt[n - 1]) return sg->table[(n - 1) * sg->table_cols + col];
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (tt[mid] <= t) lo = mid;
    else hi = mid;
  }
  double w = (t - tt[lo]) / (tt[hi] - tt[lo]);
  return (1 - w) * sg->table[lo * sg->table_cols + col] + w * sg->table[hi * sg->table_cols + col];
}

/* The target of equation i at segment time t (lambda: fraction of the ramp done). */
double point_target(const Segment *sg, int i, const double start[6], double lambda, double t) {
  const Equation *eq = &sg->eq[i];
  if (eq->table_column >= 0) return eq->table_factor * point_interp(sg, eq->table_column, t);
  if (eq->kind == EQ_LINEAR) return start[i];
  return start[i] + lambda * (eq->target - start[i]);
}

/* Residual of equation i for strain eps and stress sig. */
static double residual_of(const Equation *eq, int i, int n, const double eps[6], const double sig[6], double target) {
  switch (eq->kind) {
  case EQ_STRESS: return sig[i] - target;
  case EQ_STRAIN: return eps[i] - target;
  default: {
    double s = -target;
    for (int j = 0; j < n; j++) s += eq->a[j] * eps[j] + eq->b[j] * sig[j];
    return s;
  }
  }
}


/* One step of length dt from the committed state 'cur' to equation targets 'target': Newton on the
 * strain increment. On success 'next' holds the converged call. */
int point_mixed_step(const UmatMaterial *mat, UmatControl c, const Segment *sg, const UmatCall *cur, const double target[6],
                     double dt, double deps[6], UmatCall *next, PointStepResult *res) {
  const int    n   = mat->ntens;
  const double phi = material_phi(mat);
  memset(res, 0, sizeof *res);
  res->pnewdt = DBL_MAX;
  /* Strain-controlled components are known exactly. */
  for (int i = 0; i < n; i++)
    if (sg->eq[i].kind == EQ_STRAIN) deps[i] = target[i] - cur->stran[i];
  double scale = 1;
  for (int i = 0; i < n; i++) scale = fmax(scale, fmax(fabs(cur->stress[i]), fabs(target[i])));
  for (int it = 0; it <= MAX_NEWTON; it++) {
    *next = *cur;
    memcpy(next->dstran, deps, sizeof(double) * n);
    next->dtime = dt;
    MaterialPointDiag diag;
    material_point_update(mat, phi, c, next, &diag);
    res->umat_calls++;
    res->pnewdt = diag.pnewdt;
    if (diag.rejected) {
      material_failed_call_keep(&res->failed, mat, phi, c, cur->stress, cur->statev, next);
      return 1;
    }
    double eps[6], r[6], err = 0;
    for (int i = 0; i < n; i++) eps[i] = cur->stran[i] + deps[i];
    for (int i = 0; i < n; i++) {
      r[i] = residual_of(&sg->eq[i], i, n, eps, next->stress, target[i]);
      double rel = sg->eq[i].kind == EQ_STRAIN ? fabs(r[i]) : fabs(r[i]) / scale;
      err        = fmax(err, rel);
    }
    res->newton        = it;
    res->control_error = err;
    if (err <= 1e-12) return 0;
    if (it == MAX_NEWTON) break;
    double J[6][6];
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double dij = next->ddsdde[i + n * j];
        switch (sg->eq[i].kind) {
        case EQ_STRESS: J[i][j] = dij; break;
        case EQ_STRAIN: J[i][j] = i == j; break;
        default: {
          double s = sg->eq[i].a[j];
          for (int k = 0; k < n; k++) s += sg->eq[i].b[k] * next->ddsdde[k + n * j];
          J[i][j] = s;
        }
        }
      }
    if (solve_small(n, J, r)) return 1;
    for (int i = 0; i < n; i++) deps[i] -= r[i];
  }
  return 1;
}

/* Worst relative difference between DDSDDE and central differences of STRESS in DSTRAN. */
double point_tangent_check(const UmatMaterial *mat, UmatControl c, const UmatCall *cur, const UmatCall *next) {
  int               n = mat->ntens;
  double            worst = 0, dmax = 0;
  MaterialPointDiag diag;
  for (int k = 0; k < n * n; k++) dmax = fmax(dmax, fabs(next->ddsdde[k]));
  for (int j = 0; j < n; j++) {
    double   h = 1e-7 * fmax(1e-3, fabs(next->dstran[j]));
    UmatCall p = *cur, m = *cur;
    memcpy(p.dstran, next->dstran, sizeof p.dstran);
    memcpy(m.dstran, next->dstran, sizeof m.dstran);
    p.dtime = m.dtime = next->dtime;
    p.dstran[j] += h;
    m.dstran[j] -= h;
    material_point_update(mat, material_phi(mat), c, &p, &diag);
    material_point_update(mat, material_phi(mat), c, &m, &diag);
    for (int i = 0; i < n; i++)
      worst = fmax(worst, fabs((p.stress[i] - m.stress[i]) / (2 * h) - next->ddsdde[i + n * j]) / dmax);
  }
  return worst;
}

void point_invariants(const double s[6], int n, double *p, double *q) {
  double t[6] = {0};
  memcpy(t, s, sizeof(double) * n);
  *p         = -(t[0] + t[1] + t[2]) / 3;
  double d[3] = {t[0] + *p, t[1] + *p, t[2] + *p};
  *q = sqrt(1.5 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5])));
}
