/* Rigid indenter shapes: the signed distance from a point to the indenter surface and its gradient.
 * The indenter moves along the indentation direction d = -e_z in 3D, -e_y in 2D (x2 = z in
 * axisymmetry); it occupies the region above its surface. The gap g >= 0 outside the indenter;
 * n = dg/dx is the unit normal of the surface at the closest point, pointing away from the indenter,
 * i.e. along the push of the contact pressure on the material (Yin et al. 2021 eq. 5 with the
 * indenter as the master body). */
#ifndef INDENTER_SHAPE_H
#define INDENTER_SHAPE_H

typedef enum { SHAPE_BERKOVICH, SHAPE_CONE, SHAPE_WEDGE, SHAPE_SPHERE, SHAPE_FLAT_PUNCH } ShapeKind;

typedef struct {
  ShapeKind kind;
  int       dim;        /* 2 or 3 */
  double    half_angle; /* radians: cone, wedge (half the tip angle), Berkovich (axis to face) */
  double    radius;     /* sphere, flat punch */
  double    rotation;   /* Berkovich: radians about the axis; 0: a face normal points along +y */
  double    tip[3];     /* the tip at u_r = 0 (a sphere's lowest point, a punch's face centre) */
  int       vertical;   /* 1: the gap along the indentation axis at the reference lateral position (the
                           linearised half-space contact of Sneddon and Hertz: forces along the axis only) */
} IndenterShape;

/* Gap of a point x (current coordinates; X: its reference coordinates) to the indenter displaced by u_r
 * along d, and n = dg/dx. The derivative of g with respect to u_r is -n.d. */
double indenter_gap(const IndenterShape *s, const double X[], const double x[], double ur, double n[]);

#endif
