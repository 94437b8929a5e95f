// A 3D block under a rigid indenter whose tip touches the top at the origin, meshed with unstructured
// tetrahedra graded toward the tip. The block is x, y in [-L/2, L/2], z in [-L, 0] (top at z = 0); with
// half = 1 only x >= 0 is kept, the plane x = 0 being a mirror plane.
// Parameters (override with gmsh -setnumber NAME VALUE): L (side), half (0 or 1), h_tip (element size
// within r_fine of the tip), h_far (element size from about L/2 on), r_fine, r_contact (the square
// |x|, |y| <= r_contact of the top, x >= 0 when half = 1, is a surface of its own: the potential
// contact surface).
// Physical groups: volume "block"; surfaces "bottom" (z = -L), "x0" (x = min: the mirror plane when
// half = 1), "x1" (x = max), "y0" (y = -L/2), "y1" (y = L/2), "top" (all of z = 0), "contact" (the
// central square of the top); point "tip" (the origin).
SetFactory("OpenCASCADE");
If (!Exists(L))
  L = 2;
EndIf
If (!Exists(half))
  half = 0;
EndIf
If (!Exists(h_tip))
  h_tip = 0.05;
EndIf
If (!Exists(h_far))
  h_far = 0.4;
EndIf
If (!Exists(r_fine))
  r_fine = 0.3;
EndIf
If (!Exists(r_contact))
  r_contact = 0.4 * L / 2;
EndIf
If (r_contact <= 0 || r_contact >= L / 2)
  Error("indent_cube.geo: need 0 < r_contact < L/2 (r_contact = %g, L = %g)", r_contact, L);
EndIf
xmin = (half == 1) ? 0 : -L / 2;
xmax = L / 2;
Box(1) = {xmin, -L / 2, -L, xmax - xmin, L, L};
// The contact square and the tip are cut into the top face by fragmenting the box with a square at
// z = 0 and a point at the origin: the top face is split into the square and the rest (sharing the
// square's edges, so the triangles and tetrahedra are conforming across them), and the tip becomes a
// mesh vertex (inside the square when half = 0, on its edge x = 0 when half = 1).
cx = (half == 1) ? 0 : -r_contact;
sq = news;
Rectangle(sq) = {cx, -r_contact, 0, r_contact - cx, 2 * r_contact};
p = newp;
Point(p) = {0, 0, 0};
BooleanFragments{ Volume{1}; Delete; }{ Surface{sq}; Point{p}; Delete; }
// Groups by position, not by tag: the fragment operation renumbers entities.
e = 1e-6 * L;
Physical Volume("block") = Volume In BoundingBox {xmin - e, -L / 2 - e, -L - e, xmax + e, L / 2 + e, e};
Physical Surface("bottom") = Surface In BoundingBox {xmin - e, -L / 2 - e, -L - e, xmax + e, L / 2 + e, -L + e};
Physical Surface("x0") = Surface In BoundingBox {xmin - e, -L / 2 - e, -L - e, xmin + e, L / 2 + e, e};
Physical Surface("x1") = Surface In BoundingBox {xmax - e, -L / 2 - e, -L - e, xmax + e, L / 2 + e, e};
Physical Surface("y0") = Surface In BoundingBox {xmin - e, -L / 2 - e, -L - e, xmax + e, -L / 2 + e, e};
Physical Surface("y1") = Surface In BoundingBox {xmin - e, L / 2 - e, -L - e, xmax + e, L / 2 + e, e};
Physical Surface("top") = Surface In BoundingBox {xmin - e, -L / 2 - e, -e, xmax + e, L / 2 + e, e};
Physical Surface("contact") = Surface In BoundingBox {cx - e, -r_contact - e, -e, r_contact + e, r_contact + e, e};
tip[] = Point In BoundingBox {-e, -e, -e, e, e, e};
Physical Point("tip") = {tip[]};
// Element size: h_tip within r_fine of the tip, growing linearly with the distance to h_far at about
// L/2 (at least 2 r_fine, so that the ramp never degenerates), h_far beyond. The field alone governs:
// sizes from the geometry's points, from curvature and extended from the boundary are off, so that
// the coarse boundary does not coarsen the interior near the tip nor the other way round.
d_far = (L / 2 > 2 * r_fine) ? L / 2 : 2 * r_fine;
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
