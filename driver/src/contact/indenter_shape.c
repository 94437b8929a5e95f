#include "indenter_shape.h"

#include <math.h>

/* Gap and gradient in the frame of the tip: lateral vector l (dim - 1 components), height z above the
 * tip. grad_l and grad_z are the lateral and upward components of n. tie: a length at roundoff level of the
 * coordinates; a point within it of the apex's region belongs to the face. A node on the axis in contact sits at
 * the apex (g = 0, z = 0): the gap's gradient jumps there from the face's (0, -sin psi) to the apex's (0, -1), and
 * roundoff in z alone would pick one or the other from one iterate to the next (Newton then stalls); the face's
 * is kept, as the Berkovich keeps the mean of its tied faces. */
static double cone_gap(double psi, const double l[], int nl, double z, double tie, double gl[], double *gz) {
  double rho = 0;
  for (int k = 0; k < nl; k++) rho += l[k] * l[k];
  rho = sqrt(rho);
  if (rho * sin(psi) + z * cos(psi) < -tie) { /* below the apex: the tip is the closest point */
    double r = sqrt(rho * rho + z * z);
    if (r == 0) {
      for (int k = 0; k < nl; k++) gl[k] = 0;
      *gz = -1;
      return 0;
    }
    for (int k = 0; k < nl; k++) gl[k] = l[k] / r;
    *gz = z / r;
    return r;
  }
  /* on the face: distance to the generating line z = rho cot(psi) (on the axis, rho = 0, only the
     axial part of the gradient is defined; the lateral part is left zero: symmetric) */
  for (int k = 0; k < nl; k++) gl[k] = rho > 0 ? cos(psi) * l[k] / rho : 0;
  *gz = -sin(psi);
  return rho * cos(psi) - z * sin(psi);
}

/* The height of the indenter surface above its tip at lateral offset l (the vertical gap's profile). */
static double profile(const IndenterShape *s, const double l[], int nl) {
  double rho = 0;
  for (int k = 0; k < nl; k++) rho += l[k] * l[k];
  rho = sqrt(rho);
  switch (s->kind) {
  case SHAPE_CONE:
  case SHAPE_WEDGE: return rho / tan(s->half_angle);
  case SHAPE_BERKOVICH: {
    double m = -INFINITY;
    for (int f = 0; f < 3; f++) {
      double a = s->rotation + M_PI / 2 + f * 2 * M_PI / 3;
      m        = fmax(m, l[0] * cos(a) + l[1] * sin(a));
    }
    return m / tan(s->half_angle);
  }
  case SHAPE_SPHERE: return rho < s->radius ? s->radius - sqrt(s->radius * s->radius - rho * rho) : 1e300;
  case SHAPE_FLAT_PUNCH: return rho <= s->radius ? 0 : 1e300; /* beyond the rim: never in contact */
  }
  return 0;
}

double indenter_gap(const IndenterShape *s, const double X[], const double x[], double ur, double n[]) {
  const int nl = s->dim - 1;
  double    l[2], z, gl[2] = {0, 0}, gz = 0, g = 0;
  z = x[nl] - (s->tip[nl] - ur); /* height above the displaced tip */
  if (s->vertical) {             /* g = f(X_lateral) - z: n = d */
    for (int k = 0; k < nl; k++) l[k] = X[k] - s->tip[k], n[k] = 0;
    n[nl] = -1;
    return profile(s, l, nl) - z;
  }
  for (int k = 0; k < nl; k++) l[k] = x[k] - s->tip[k];
  switch (s->kind) {
  case SHAPE_CONE:
  case SHAPE_WEDGE: {
    double tie = 1e-12 * fabs(ur);
    for (int k = 0; k <= nl; k++) tie += 1e-12 * (fabs(x[k]) + fabs(s->tip[k]));
    g = cone_gap(s->half_angle, l, nl, z, tie, gl, &gz);
    break;
  }
  case SHAPE_BERKOVICH: { /* three planes; the gap to the pyramid is the largest plane distance, exact
                             wherever the closest point lies on a face (the contact zone). On an edge or at the
                             tip (faces tied to roundoff) the normal is the mean of the tied faces' gradients, a
                             subgradient of the max (Clarke 1983, Prop. 2.3.12) that keeps the pyramid's mirror
                             symmetry: the same force whether or not a mirror plane of the model holds the edge */
    double gf[3], tol = 1e-12 * (fabs(l[0]) + fabs(l[1]) + fabs(z)), cnt = 0;
    g = -INFINITY;
    for (int f = 0; f < 3; f++) {
      double a = s->rotation + M_PI / 2 + f * 2 * M_PI / 3;
      gf[f]    = cos(s->half_angle) * (l[0] * cos(a) + l[1] * sin(a)) - sin(s->half_angle) * z;
      g        = fmax(g, gf[f]);
    }
    for (int f = 0; f < 3; f++) {
      double a = s->rotation + M_PI / 2 + f * 2 * M_PI / 3;
      if (gf[f] < g - tol) continue;
      gl[0] += cos(s->half_angle) * cos(a), gl[1] += cos(s->half_angle) * sin(a), cnt++;
    }
    gl[0] /= cnt, gl[1] /= cnt, gz = -sin(s->half_angle);
    break;
  }
  case SHAPE_SPHERE: { /* centre one radius above the tip */
    double q[3] = {0, 0, 0}, r = 0;
    for (int k = 0; k < nl; k++) q[k] = l[k];
    q[nl] = z - s->radius;
    for (int k = 0; k <= nl; k++) r += q[k] * q[k];
    r = sqrt(r);
    for (int k = 0; k < nl; k++) gl[k] = r > 0 ? q[k] / r : 0;
    gz = r > 0 ? q[nl] / r : -1;
    g  = r - s->radius;
    break;
  }
  case SHAPE_FLAT_PUNCH: { /* a cylinder of the given radius, face at the tip height */
    double rho = 0;
    for (int k = 0; k < nl; k++) rho += l[k] * l[k];
    rho = sqrt(rho);
    if (rho <= s->radius) {
      g = -z, gz = -1;
    } else if (z >= 0) {
      g = rho - s->radius;
      for (int k = 0; k < nl; k++) gl[k] = l[k] / rho;
    } else { /* below and outside: the rim is the closest point */
      g = hypot(rho - s->radius, z);
      for (int k = 0; k < nl; k++) gl[k] = (rho - s->radius) / g * l[k] / rho;
      gz = z / g;
    }
    break;
  }
  }
  for (int k = 0; k < nl; k++) n[k] = gl[k];
  n[nl] = gz;
  return g;
}
