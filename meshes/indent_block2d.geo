// A 2D block under a rigid indenter whose tip touches the top at the origin, meshed with unstructured
// triangles graded toward the tip. The block is y in [-H, 0] (top at y = 0) and x in [-W/2, W/2]
// (half = 0, plane strain) or x in [0, W/2] (half = 1, axisymmetric with x = r, the axis at x = 0).
// Parameters (override with gmsh -setnumber NAME VALUE): W (full width), H (height), half (0 or 1),
// h_tip (element size within r_fine of the tip), h_far (element size from about W/2 on), r_fine,
// r_contact (the top is split at x = +-r_contact; the central part is the potential contact surface),
// x_mark (if > 0, a mesh node is forced at x = x_mark, and -x_mark when half = 0, on the top, e.g. the
// edge of a flat punch; 0: none), mirror (0 or 1, with half = 0: the half x <= 0 meshed as the mirror image of
// the half x >= 0, so that the whole block's mesh is symmetric and its half x >= 0 is the half = 1 mesh; 0: one
// mesh of the whole block).
// Physical groups: surface "block"; curves "bottom" (y = -H), "left" (x = min: the axis when half = 1),
// "right" (x = max), "top" (all of y = 0), "contact" (the part of y = 0 with |x| <= r_contact); point
// "tip" (the origin).
SetFactory("OpenCASCADE");
If (!Exists(W))
  W = 2;
EndIf
If (!Exists(H))
  H = 2;
EndIf
If (!Exists(half))
  half = 0;
EndIf
If (!Exists(h_tip))
  h_tip = 0.02;
EndIf
If (!Exists(h_far))
  h_far = 0.25;
EndIf
If (!Exists(r_fine))
  r_fine = 0.3;
EndIf
If (!Exists(r_contact))
  r_contact = 0.6 * W / 2;
EndIf
If (!Exists(x_mark))
  x_mark = 0;
EndIf
If (!Exists(mirror))
  mirror = 0;
EndIf
If (r_contact <= 0 || r_contact >= W / 2)
  Error("indent_block2d.geo: need 0 < r_contact < W/2 (r_contact = %g, W = %g)", r_contact, W);
EndIf
If (x_mark < 0 || x_mark >= W / 2)
  Error("indent_block2d.geo: need 0 <= x_mark < W/2 (x_mark = %g, W = %g)", x_mark, W);
EndIf
If (mirror != 0 && (mirror != 1 || half != 0))
  Error("indent_block2d.geo: mirror is 0, or 1 with half = 0 (mirror = %g, half = %g)", mirror, half);
EndIf
xmin = (half == 1) ? 0 : -W / 2;
xmax = W / 2;
If (mirror == 1)
  Rectangle(1) = {0, -H, 0, xmax, H};
  Rectangle(2) = {xmin, -H, 0, -xmin, H};
  blocks[] = {1, 2};
Else
  Rectangle(1) = {xmin, -H, 0, xmax - xmin, H};
  blocks[] = {1};
EndIf
// The top is cut at the tip, at +-r_contact and at +-x_mark by fragmenting the rectangle with points on
// its top edge: OpenCASCADE splits the edge there, so the pieces share their end points and the
// triangles are conforming across them, whatever the order of r_contact and x_mark (a point given twice
// at the same place becomes one vertex). With half = 1 the tip and -r_contact, -x_mark are not cut
// points: the tip is the rectangle's corner, the others lie outside.
cut[] = {};
xcut[] = {r_contact};
If (x_mark > 0)
  xcut[] += x_mark;
EndIf
For k In {0 : #xcut[] - 1}
  p = newp;
  Point(p) = {xcut[k], 0, 0};
  cut[] += p;
  If (half == 0)
    p = newp;
    Point(p) = {-xcut[k], 0, 0};
    cut[] += p;
  EndIf
EndFor
If (half == 0 && mirror == 0)
  p = newp;
  Point(p) = {0, 0, 0};
  cut[] += p;
EndIf
BooleanFragments{ Surface{blocks[]}; Delete; }{ Point{cut[]}; Delete; }
// Groups by position, not by tag: the fragment operation renumbers entities.
e = 1e-6 * (W + H);
Physical Surface("block") = Surface In BoundingBox {xmin - e, -H - e, -e, xmax + e, e, e};
Physical Curve("bottom") = Curve In BoundingBox {xmin - e, -H - e, -e, xmax + e, -H + e, e};
Physical Curve("left") = Curve In BoundingBox {xmin - e, -H - e, -e, xmin + e, e, e};
Physical Curve("right") = Curve In BoundingBox {xmax - e, -H - e, -e, xmax + e, e, e};
Physical Curve("top") = Curve In BoundingBox {xmin - e, -e, -e, xmax + e, e, e};
Physical Curve("contact") = Curve In BoundingBox {-r_contact - e, -e, -e, r_contact + e, e, e};
tip[] = Point In BoundingBox {-e, -e, -e, e, e, e};
Physical Point("tip") = {tip[]};
// Element size: h_tip within r_fine of the tip, growing linearly with the distance to h_far at about
// W/2 (at least 2 r_fine, so that the ramp never degenerates), h_far beyond. The field alone governs:
// sizes from the geometry's points, from curvature and extended from the boundary are off, so that
// the coarse boundary does not coarsen the interior near the tip nor the other way round.
d_far = (W / 2 > 2 * r_fine) ? W / 2 : 2 * r_fine;
Field[1] = Distance;
Field[1].PointsList = {tip[]};
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = h_tip;
Field[2].SizeMax = h_far;
Field[2].DistMin = r_fine;
Field[2].DistMax = d_far;
Background Field = 2;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeMax = h_far;
// mirror = 1: the half x <= 0 is meshed as the mirror image of the half x >= 0 (gmsh copies the mesh through the
// reflection x -> -x), so that the whole block's mesh is symmetric about x = 0 and its half x >= 0 is the mesh of
// half = 1 with the same parameters: a half model and the whole block then run one mesh.
If (mirror == 1)
  right[] = Surface In BoundingBox {-e, -H - e, -e, xmax + e, e, e};
  left[] = Surface In BoundingBox {xmin - e, -H - e, -e, e, e, e};
  Periodic Surface{left[0]} = {right[0]} Affine{-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
EndIf
