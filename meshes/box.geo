// A box [0, Lx] x [0, Ly] x [0, Lz] meshed with unstructured tetrahedra (element size 'size'), for
// tests and homogeneous scenes. Physical groups: volume "body"; faces "x0", "x1", "y0", "y1", "z0", "z1";
// point "origin" (0, 0, 0).
SetFactory("OpenCASCADE");
If (!Exists(Lx))
  Lx = 1;
EndIf
If (!Exists(Ly))
  Ly = 1;
EndIf
If (!Exists(Lz))
  Lz = 1;
EndIf
If (!Exists(size))
  size = 0.5;
EndIf
Box(1) = {0, 0, 0, Lx, Ly, Lz};
e = 1e-6 * (Lx + Ly + Lz);
Physical Volume("body") = {1};
Physical Surface("x0") = Surface In BoundingBox {-e, -e, -e, e, Ly + e, Lz + e};
Physical Surface("x1") = Surface In BoundingBox {Lx - e, -e, -e, Lx + e, Ly + e, Lz + e};
Physical Surface("y0") = Surface In BoundingBox {-e, -e, -e, Lx + e, e, Lz + e};
Physical Surface("y1") = Surface In BoundingBox {-e, Ly - e, -e, Lx + e, Ly + e, Lz + e};
Physical Surface("z0") = Surface In BoundingBox {-e, -e, -e, Lx + e, Ly + e, e};
Physical Surface("z1") = Surface In BoundingBox {-e, -e, Lz - e, Lx + e, Ly + e, Lz + e};
Physical Point("origin") = Point In BoundingBox {-e, -e, -e, e, e, e};
Mesh.CharacteristicLengthMax = size;
