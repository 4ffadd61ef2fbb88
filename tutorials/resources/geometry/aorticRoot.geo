// Fluid domain of the idealised aortic valve (Yao et al. 2012, Sect. 5):
// the aortic root with three sinuses (valveParameters.geo), an inlet
// (ventricular) extension of length L_in and radius r_b below the valve
// base, and an outlet (aortic) extension of length L_out and radius r_c
// above the sinotubular junction. The leaflets are immersed: they are not
// cut out of this domain.
// Physical groups (OpenFOAM patch names after gmshToFoam):
//   inlet (z = -L_in), outlet (z = h_s + L_out), wall; volume: fluid.
// Written in metres (Mesh.ScalingFactor = 1e-3); parameters in mm.
// Usage:  gmsh -3 -format msh22 [-setnumber name value ...] aorticRoot.geo -o fluid.msh
SetFactory("OpenCASCADE");
Include "valveParameters.geo";

If (!Exists(nSections)) nSections = 20; EndIf   // cross-sections of the root
If (!Exists(nPhi)) nPhi = 120; EndIf            // points per cross-section

// Cross-sections of the root between the base (z = 0) and the sinotubular
// junction (z = h_s); circles at both ends, closed splines between, joined
// by ruled surfaces, mildly clustered towards the base where the sinuses
// start narrow. With the defaults the ruled wall is within 0.02 mm of the
// formula. A smooth loft through splines of this many points takes 40 times
// longer to build and its projections (checks, meshing) are slow; thinner
// bands at the base (stronger clustering) give flat tets at the wall (max
// non-orthogonality 79 instead of 67 at the coarse preset).
wires[] = {};
For i In {0:nSections}
    zw = h_s*(i/nSections)^1.2;
    If (i == 0 || i == nSections)
        rr = r_b;
        If (i == nSections) rr = r_c; EndIf
        c = newc; Circle(c) = {0, 0, zw, rr};
        wl = newll; Curve Loop(wl) = {c};
    Else
        pts[] = {};
        For j In {0:nPhi-1}
            theta = 2*Pi*j/nPhi;
            // angle from the nearest sinus centre (0, 120, 240 deg)
            phiw = theta - 2*Pi/3*Round(theta/(2*Pi/3));
            Call WallRadius;
            p = newp; Point(p) = {rw*Cos(theta), rw*Sin(theta), zw};
            pts[] += {p};
        EndFor
        c = newc; Spline(c) = {pts[], pts[0]};
        wl = newll; Curve Loop(wl) = {c};
    EndIf
    wires[] += {wl};
EndFor
root = newv; Ruled ThruSections(root) = {wires[]};
inl = newv; Cylinder(inl) = {0, 0, -L_in, 0, 0, L_in, r_b};
outl = newv; Cylinder(outl) = {0, 0, h_s, 0, 0, L_out, r_c};
vols() = BooleanFragments{ Volume{inl, root, outl}; Delete; }{};

R = 2*r_sm;
eps = 1e-3*r_b;
inlet() = Surface In BoundingBox{-R, -R, -L_in - eps, R, R, -L_in + eps};
outlet() = Surface In BoundingBox{-R, -R, h_s + L_out - eps, R, R, h_s + L_out + eps};
inner() = Surface In BoundingBox{-R, -R, -eps, R, R, eps};
inner() += Surface In BoundingBox{-R, -R, h_s - eps, R, R, h_s + eps};
wall() = Surface{:};
wall() -= inlet();
wall() -= outlet();
wall() -= inner();

Physical Surface("inlet") = inlet();
Physical Surface("outlet") = outlet();
Physical Surface("wall") = wall();
Physical Volume("fluid") = vols();

Mesh.MeshSizeMin = fluidSize;
Mesh.MeshSizeMax = fluidSize;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;        // Frontal-Delaunay surfaces
// 10: HXT (fewer slivers; its mesh differs from call to call), 1: Delaunay
// (the same mesh on every call: -setnumber fluidAlgorithm3D 1)
If (!Exists(fluidAlgorithm3D)) fluidAlgorithm3D = 10; EndIf
Mesh.Algorithm3D = fluidAlgorithm3D;
Mesh.Optimize = 1;
Mesh.ScalingFactor = 1e-3; // mm -> m
Mesh.MshFileVersion = 2.2; // the format gmshToFoam reads
