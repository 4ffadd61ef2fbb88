// turekHronFSI1/2: the elastic flag of Turek & Hron (2006), 0.35 x 0.02 m,
// as an immersed solid slab of tets inside the fluid slab z in [0, dz]
// (system/blockMeshDict, depth 0.005). Every solid node must lie inside a
// fluid cell:
//  - the flag starts at x = 0.2501, just right of the cylinder (r = 0.05
//    around (0.2, 0.2), which the fluid mesh has as a hole); the benchmark's
//    flag begins on the cylinder's surface, x = 0.24899 at its edges y =
//    0.19, 0.21 and 0.25 on y = 0.2;
//  - z is inset by 1e-4 dz on each side.
// Physical groups (node sets of constant/solidProperties): clamp (the face
// x = 0.2501), flag (every node: u_z = 0, plane strain).
// Usage: gmsh -3 -setnumber h 0.0032 -setnumber dz 0.005 flag.geo -o flag.msh
SetFactory("OpenCASCADE");
Mesh.MshFileVersion = 2.2;
DefineConstant[ h = 0.0032, dz = 0.005 ];
x0 = 0.2501;
x1 = 0.6;
z0 = 1e-4*dz;
Box(1) = {x0, 0.19, z0, x1 - x0, 0.02, dz - 2*z0};
eps = 1e-7;
Physical Surface("clamp") = Surface In BoundingBox{x0 - eps, 0.19 - eps, -eps, x0 + eps, 0.21 + eps, dz + eps};
Physical Volume("flag") = {1};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h;
Mesh.Algorithm3D = 10;  // HXT: fewer slivers, so a larger explicit time step
