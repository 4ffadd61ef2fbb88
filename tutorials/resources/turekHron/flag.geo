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
Mesh.MshFileVersion = 2.2;
DefineConstant[ h = 0.0032, dz = 0.005 ];
x0 = 0.2501;
x1 = 0.6;
z0 = 1e-4*dz;
// Triangles of size h on the face z = z0 (frontal-Delaunay), extruded
// through the depth in one layer of prisms, each split into 3 tets: the
// solid is plane strain (every node held in z), so one layer carries it.
// gmsh's 3D HXT mesher (used before) gave a different mesh from run to run
// (it depends on memory addresses: three variants in 16 runs of the same
// command, another with address randomisation off, and another again from
// another directory), so the Turek-Hron results varied between identical
// runs; its 3D Delaunay leaves slivers (smallest altitude 1e-5 m, the
// explicit step with it). Measured at h = 3.18 mm (N = 44), CSM1 (gravity,
// smoothedSolidRun) on this mesh: u_y(A) -64.90 mm (HXT -64.80, reference
// -66.10: clamped at x = 0.2501, 1.1 % stiffer), 5,004 tets against 5,749
// and a stable step of 2.78e-5 s against 2.24e-5 s (0.70 of the solid's
// cost); the same file from every run, directory and environment.
Point(1) = {x0, 0.19, z0, h};
Point(2) = {x1, 0.19, z0, h};
Point(3) = {x1, 0.21, z0, h};
Point(4) = {x0, 0.21, z0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Mesh.Algorithm = 6;     // frontal-Delaunay (2D)
out[] = Extrude {0, 0, dz - 2*z0} { Surface{1}; Layers{1}; };
// out[]: the top face, the volume, then the sides extruded from lines 1..4
Physical Surface("clamp") = {out[5]};   // x = x0, from line 4
Physical Volume("flag") = {out[1]};
