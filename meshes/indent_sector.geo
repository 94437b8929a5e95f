// A hexagonal prism under a rigid Berkovich indenter whose tip touches the top at the origin, cut by mirror planes
// through its axis (z), meshed with unstructured tetrahedra graded toward the tip as indent_cube.geo does.
// The hexagon has apothem L/2 (the cube's half side) and its corners at azimuths 30, 90, 150, ... degrees; the
// prism is z in [-L, 0] (top at z = 0). Kept: the azimuths [90 - span, 90] degrees:
//   span = 60:  the 60-degree sector between the planes at 30 and 90 degrees (x = 0), both mirror planes of
//               the Berkovich of indenter_shape.c with rotation 0 (its face normals at 90, 210 and 330 degrees:
//               each mirror plane holds one face normal and the opposite edge) and of the hexagon;
//   span = 180: the half x >= 0, the same hexagon (the sector's reference: three sectors).
// Parameters (override with gmsh -setnumber NAME VALUE): L, span (60 or 180), h_tip (element size within r_fine
// of the tip), h_far (element size from about L/2 on), r_fine, r_contact (the part of the top within this
// radius of the tip is a surface of its own: the potential contact surface; r_contact < L/2).
// Physical groups: volume "block"; surfaces "bottom" (z = -L), "top" (all of z = 0), "contact" (the top within
// r_contact), "mirror_a" (the plane at azimuth 90 - span: 30 degrees, or x = 0 with y < 0 when span = 180),
// "mirror_b" (x = 0, y > 0), "side1", "side2", "side3" (the hexagon's faces from mirror_a on: outward normals at
// azimuths 60; or -60, 0, 60); point "tip" (the origin).
If (!Exists(L))
  L = 2;
EndIf
If (!Exists(span))
  span = 60;
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
If (span != 60 && span != 180)
  Error("indent_sector.geo: span must be 60 or 180 (degrees), got %g", span);
EndIf
If (r_contact <= 0 || r_contact >= L / 2)
  Error("indent_sector.geo: need 0 < r_contact < L/2 (r_contact = %g, L = %g)", r_contact, L);
EndIf
R = L / 2 / Cos(Pi / 6); // the hexagon's corner radius
nv = span / 60 + 1;      // its corners in the kept part: 2 or 4, 60 degrees apart
t0 = Pi / 2 - span * Pi / 180;
tip = newp;
Point(tip) = {0, 0, 0};
bot = newp;
Point(bot) = {0, 0, -L};
For i In {0 : nv - 1}
  t = t0 + i * Pi / 3;
  c = Cos(t);
  If (Fabs(c) < 1e-12) // exactly on x = 0
    c = 0;
  EndIf
  V[i] = newp;
  Point(V[i]) = {R * c, R * Sin(t), 0};
  W[i] = newp;
  Point(W[i]) = {R * c, R * Sin(t), -L};
  C[i] = newp;
  Point(C[i]) = {r_contact * c, r_contact * Sin(t), 0};
EndFor
// Edges: the contact's rim (arcs of 60 degrees about the tip), the hexagon's edges at top and bottom, the
// vertical edges, the axis, and the radial edges in the two mirror planes.
For i In {0 : nv - 2}
  arc[i] = newl;
  Circle(arc[i]) = {C[i], tip, C[i + 1]};
  te[i] = newl;
  Line(te[i]) = {V[i], V[i + 1]};
  be[i] = newl;
  Line(be[i]) = {W[i], W[i + 1]};
EndFor
For i In {0 : nv - 1}
  ve[i] = newl;
  Line(ve[i]) = {V[i], W[i]};
EndFor
axis = newl;
Line(axis) = {tip, bot};
la = newl;
Line(la) = {tip, C[0]};
lb = newl;
Line(lb) = {tip, C[nv - 1]};
ma = newl;
Line(ma) = {C[0], V[0]};
mb = newl;
Line(mb) = {C[nv - 1], V[nv - 1]};
ba = newl;
Line(ba) = {bot, W[0]};
bb = newl;
Line(bb) = {bot, W[nv - 1]};
// Faces.
cl = newll;
Curve Loop(cl) = {la, arc[], -lb};
s_contact = news;
Plane Surface(s_contact) = {cl};
For i In {0 : nv - 2}
  rev[i] = -arc[nv - 2 - i];
EndFor
cl = newll;
Curve Loop(cl) = {ma, te[], -mb, rev[]};
s_rest = news;
Plane Surface(s_rest) = {cl};
cl = newll;
Curve Loop(cl) = {ba, be[], -bb};
s_bottom = news;
Plane Surface(s_bottom) = {cl};
cl = newll;
Curve Loop(cl) = {la, ma, ve[0], -ba, -axis};
s_a = news;
Plane Surface(s_a) = {cl};
cl = newll;
Curve Loop(cl) = {lb, mb, ve[nv - 1], -bb, -axis};
s_b = news;
Plane Surface(s_b) = {cl};
For i In {0 : nv - 2}
  cl = newll;
  Curve Loop(cl) = {te[i], ve[i + 1], -be[i], -ve[i]};
  s_side[i] = news;
  Plane Surface(s_side[i]) = {cl};
EndFor
sl = newsl;
Surface Loop(sl) = {s_contact, s_rest, s_bottom, s_a, s_b, s_side[]};
Volume(1) = {sl};
Physical Volume("block") = {1};
Physical Surface("bottom") = {s_bottom};
Physical Surface("top") = {s_contact, s_rest};
Physical Surface("contact") = {s_contact};
Physical Surface("mirror_a") = {s_a};
Physical Surface("mirror_b") = {s_b};
For i In {0 : nv - 2}
  Physical Surface(Sprintf("side%g", i + 1)) = {s_side[i]};
EndFor
Physical Point("tip") = {tip};
// Element size as in indent_cube.geo: h_tip within r_fine of the tip, growing linearly with the distance to
// h_far at about L/2 (at least 2 r_fine), h_far beyond; the field alone governs.
d_far = (L / 2 > 2 * r_fine) ? L / 2 : 2 * r_fine;
Field[1] = Distance;
Field[1].PointsList = {tip};
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
