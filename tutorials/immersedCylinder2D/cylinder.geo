// immersedCylinder2D: the DFG 2D-1 cylinder (D = 0.1 at (0.2, 0.2)) as an
// immersed solid, tets, inside the fluid slab z in [0, 0.01] (nodes must lie
// inside fluid cells: z from 0.001 to 0.009). Element size: -setnumber h.
SetFactory("OpenCASCADE");
Mesh.MshFileVersion = 2.2;
DefineConstant[ h = 0.0025 ];
Cylinder(1) = {0.2, 0.2, 0.001, 0, 0, 0.008, 0.05};
Mesh.CharacteristicLengthMax = h;
Mesh.CharacteristicLengthMin = h;
Physical Surface("surface") = {1, 2, 3};
Physical Volume("cylinder") = {1};
