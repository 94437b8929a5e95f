// Triaxial specimen (Yin, Liu & Borja 2021 §5): a cylinder of radius R and height H on the x3 axis, bottom at
// x3 = 0, mm. Parameters (override with gmsh -setnumber NAME VALUE): R, H, size (target element size).
// Physical groups: volume "rock"; surfaces "bottom", "top", "side"; point "pin" (bottom centre, a mesh
// vertex so that rigid motions in the bottom plane can be fixed); point "rim" (R, 0, 0) on the bottom
// edge, whose y displacement fixes the rotation about the axis.
SetFactory("OpenCASCADE");
If (!Exists(R))
  R = 12.7;
EndIf
If (!Exists(H))
  H = 50.8;
EndIf
If (!Exists(size))
  size = 4.0;
EndIf
Cylinder(1) = {0, 0, 0, 0, 0, H, R};
eps = 1e-6 * H;
bottom[] = Surface In BoundingBox {-2*R, -2*R, -eps, 2*R, 2*R, eps};
top[] = Surface In BoundingBox {-2*R, -2*R, H - eps, 2*R, 2*R, H + eps};
all[] = Boundary{ Volume{1}; };
side[] = {};
For k In {0 : #all[] - 1}
  If (all[k] != bottom[0] && all[k] != top[0])
    side[] += all[k];
  EndIf
EndFor
pin = newp;
Point(pin) = {0, 0, 0};
Point{pin} In Surface{bottom[0]};
Physical Volume("rock") = {1};
Physical Surface("bottom") = {bottom[]};
Physical Surface("top") = {top[]};
Physical Surface("side") = {side[]};
Physical Point("pin") = {pin};
Physical Point("rim") = Point In BoundingBox {R - eps, -eps, -eps, R + eps, eps, eps};
Mesh.CharacteristicLengthMax = size;
Mesh.CharacteristicLengthMin = 0.5 * size;
