// A quarter of a thick-walled cylinder's cross-section (Lame problem, plane strain): ri <= r <= ro,
// x, y >= 0, unstructured triangles of size 'size'. Groups: surface "body"; arcs "inner", "outer";
// straight edges "xaxis" (y = 0) and "yaxis" (x = 0), the symmetry planes.
SetFactory("OpenCASCADE");
If (!Exists(ri))
  ri = 1;
EndIf
If (!Exists(ro))
  ro = 2;
EndIf
If (!Exists(size))
  size = 0.2;
EndIf
Disk(1) = {0, 0, 0, ro};
Disk(2) = {0, 0, 0, ri};
Rectangle(3) = {0, 0, 0, 2 * ro, 2 * ro};
BooleanIntersection(4) = { Surface{1}; Delete; }{ Surface{3}; Delete; };
BooleanDifference(5) = { Surface{4}; Delete; }{ Surface{2}; Delete; };
e = 1e-6 * ro;
Physical Surface("body") = {5};
Physical Curve("xaxis") = Curve In BoundingBox {ri - e, -e, -e, ro + e, e, e};
Physical Curve("yaxis") = Curve In BoundingBox {-e, ri - e, -e, e, ro + e, e};
Physical Curve("inner") = Curve In BoundingBox {-e, -e, -e, ri + e, ri + e, e};
all[] = Curve In BoundingBox {-e, -e, -e, ro + e, ro + e, e};
inner[] = Curve In BoundingBox {-e, -e, -e, ri + e, ri + e, e};
xa[] = Curve In BoundingBox {ri - e, -e, -e, ro + e, e, e};
ya[] = Curve In BoundingBox {-e, ri - e, -e, e, ro + e, e};
outer[] = {};
For k In {0 : #all[] - 1}
  If (all[k] != inner[0] && all[k] != xa[0] && all[k] != ya[0])
    outer[] += all[k];
  EndIf
EndFor
Physical Curve("outer") = {outer[]};
Mesh.CharacteristicLengthMax = size;
