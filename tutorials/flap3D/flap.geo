// The flap of tutorial flap3D: 0.02 (x) x 0.19 (y) x 0.19 (z) m (its top and
// sides off the fluid cells' faces of both meshes), its base at
// y = eps (just inside the fluid domain: every solid node must lie in a
// fluid cell), tets of size h (gmsh -setnumber h ...).
SetFactory("OpenCASCADE");
If (!Exists(h))
    h = 0.01;
EndIf
eps = 1e-4;
Box(1) = {0.29, eps, 0.105, 0.02, 0.19 - eps, 0.19};
Physical Volume("flap") = {1};
// the base: the face at y = eps
base() = Surface In BoundingBox{0.29 - 1e-6, eps - 1e-6, 0.105 - 1e-6, 0.31 + 1e-6, eps + 1e-6, 0.295 + 1e-6};
Physical Surface("base") = {base()};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h;
Mesh.MshFileVersion = 4.1;
