// isfem tutorial thinPlate: the plate, gmsh built-in kernel, msh 2.2.
// A square plate normal to x: upstream face at x = x0, thickness t, spanning
// [d, W - d]^2 in y-z, inset d from the duct walls y, z = 0 and W so that
// its edge nodes lie inside the wall cells of the fluid (a solid node
// outside every fluid cell is a FatalError). With the duct's cells of
// h = 0.05 m (system/blockMeshDict): t = h/2, d = h/20, the plate inside
// the column of cells x in [0.5, 0.55] (x0 = 0.5 + h/40).
// Structured: n x n squares in the plane (elements about two fluid cells
// across), each split into two triangles (alternating diagonals), extruded
// through the thickness in 'layers' layers of prisms, each prism split into
// three tets (no Recombine): 1200 tets, 363 nodes.
//   gmsh -3 plate.geo -o plate.msh [-setnumber n 10 ...]
DefineConstant[ W = 1, d = 0.0025, t = 0.025, x0 = 0.50125, n = 10, layers = 2 ];
Mesh.MshFileVersion = 2.2;

Point(1) = {x0, d, d};
Point(2) = {x0, W - d, d};
Point(3) = {x0, W - d, W - d};
Point(4) = {x0, d, W - d};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1;
Transfinite Surface{1} Alternate;

out[] = Extrude {t, 0, 0} { Surface{1}; Layers{layers}; };

// Named sets of smoothedSolid (surfaces -> face and node sets)
Physical Surface("upstream") = {1};         // loaded face (pressure side)
Physical Surface("downstream") = {out[0]};
Physical Surface("edges") = {out[2], out[3], out[4], out[5]};  // clamped
Physical Volume("plate") = {out[1]};
