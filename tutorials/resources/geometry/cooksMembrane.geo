// Cook's membrane as a slab: corners (0,0) (48,44) (48,60) (0,44) mm,
// thickness t, unstructured tetrahedra of size h (plane strain is imposed by
// the case). Physical groups: xmin (clamped edge), xmax (loaded edge),
// solid. Usage: gmsh -3 -setnumber h 2.4 cooksMembrane.geo -o cook.msh
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 2.4; EndIf
If (!Exists(t)) t = 2.4; EndIf
Point(1) = {0, 0, 0, h}; Point(2) = {48, 44, 0, h}; Point(3) = {48, 60, 0, h}; Point(4) = {0, 44, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
out[] = Extrude {0, 0, t} { Surface{1}; };
eps = 1e-3;
left() = Surface In BoundingBox{-eps, -eps, -eps, eps, 44 + eps, t + eps};
right() = Surface In BoundingBox{48 - eps, 44 - eps, -eps, 48 + eps, 60 + eps, t + eps};
Physical Surface("xmin") = left();
Physical Surface("xmax") = right();
Physical Volume("solid") = {out[1]};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h;
Mesh.Algorithm3D = 10;  // HXT: fewer slivers, so a larger explicit time step
