// The elastic flag of Turek & Hron (2006) as a slab: x from where it meets
// the cylinder (centre (0.2, 0.2), r = 0.05) to 0.6, y 0.19..0.21, thickness
// t (plane strain is imposed by the case). Physical groups: clamp, flag.
// Usage: gmsh -3 -setnumber h 0.0033 turekHronFlag.geo -o flag.msh
SetFactory("OpenCASCADE");
If (!Exists(h)) h = 0.0033; EndIf
If (!Exists(t)) t = 0.005; EndIf
x0 = 0.2 + Sqrt(0.05^2 - 0.01^2);
Box(1) = {x0, 0.19, 0, 0.6 - x0, 0.02, t};
eps = 1e-6;
Physical Surface("clamp") = Surface In BoundingBox{x0 - eps, 0.19 - eps, -eps, x0 + eps, 0.21 + eps, t + eps};
Physical Volume("flag") = {1};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h;
Mesh.Algorithm3D = 10;  // HXT: fewer slivers, so a larger explicit time step
