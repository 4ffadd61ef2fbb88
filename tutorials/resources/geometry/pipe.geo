// Round pipe along z, radius R, length L, tetrahedra of size h.
// Physical groups (OpenFOAM patch names after gmshToFoam):
//   inlet (z = 0), outlet (z = L), wall; volume: fluid.
// Override with e.g.  gmsh -3 -setnumber h 0.1 pipe.geo
SetFactory("OpenCASCADE");

If (!Exists(R)) R = 1; EndIf
If (!Exists(L)) L = 6; EndIf
If (!Exists(h)) h = 0.15; EndIf

Cylinder(1) = {0, 0, 0, 0, 0, L, R};

eps = 1e-3*R;   // OpenCASCADE bounding boxes are slightly enlarged
inlet() = Surface In BoundingBox{-2*R, -2*R, -eps, 2*R, 2*R, eps};
outlet() = Surface In BoundingBox{-2*R, -2*R, L - eps, 2*R, 2*R, L + eps};
all() = Surface{:};
wall() = all();
wall() -= inlet();
wall() -= outlet();

Physical Surface("inlet") = inlet();
Physical Surface("outlet") = outlet();
Physical Surface("wall") = wall();
Physical Volume("fluid") = {1};

Mesh.CharacteristicLengthMin = h;
Mesh.CharacteristicLengthMax = h;
Mesh.Algorithm3D = 1;      // Delaunay
Mesh.Optimize = 1;
Mesh.MshFileVersion = 2.2; // the format gmshToFoam reads
