// A rectangle [X0, X0 + Lx] x [0, Ly] meshed with unstructured triangles (element size 'size'), for 2D
// tests (plane strain; axisymmetric with x1 = r >= 0). Groups: surface "body"; edges "x0", "x1", "y0",
// "y1"; point "origin" (X0, 0).
SetFactory("OpenCASCADE");
If (!Exists(X0))
  X0 = 0;
EndIf
If (!Exists(Lx))
  Lx = 1;
EndIf
If (!Exists(Ly))
  Ly = 1;
EndIf
If (!Exists(size))
  size = 0.25;
EndIf
Rectangle(1) = {X0, 0, 0, Lx, Ly};
e = 1e-6 * (Lx + Ly);
Physical Surface("body") = {1};
Physical Curve("x0") = Curve In BoundingBox {X0 - e, -e, -e, X0 + e, Ly + e, e};
Physical Curve("x1") = Curve In BoundingBox {X0 + Lx - e, -e, -e, X0 + Lx + e, Ly + e, e};
Physical Curve("y0") = Curve In BoundingBox {X0 - e, -e, -e, X0 + Lx + e, e, e};
Physical Curve("y1") = Curve In BoundingBox {X0 - e, Ly - e, -e, X0 + Lx + e, Ly + e, e};
Physical Point("origin") = Point In BoundingBox {X0 - e, -e, -e, X0 + e, e, e};
Mesh.CharacteristicLengthMax = size;
