// Mid-surfaces of the three leaflets of the idealised aortic valve in the
// closed position (Yao et al. 2012, Sect. 5; construction after Labrosse
// et al. 2006; parameters and shape in valveParameters.geo). Each
// mid-surface is bounded by its attachment to the root wall and its free
// edge, and passes through its mid-line (nadir to valve centre, length L_h).
// makeValveMeshes meshes these surfaces with triangles (size leafletSize)
// and builds the leaflets' tetrahedra from them by leafletLayers.py: two
// layers through the thickness L_t, offset along the surface normal.
// Physical groups: surfaces leaflet1..3, curves attachment1..3 and
// freeEdge1..3.
// Usage:  gmsh -2 [-setnumber name value ...] aorticLeaflets.geo
SetFactory("OpenCASCADE");
Include "valveParameters.geo";

If (!Exists(nEdge)) nEdge = 40; EndIf   // points along attachment and free edge

// Leaflet 1 (centre at angle 0); the commissure ends C- (y < 0) and C+
pCm = newp; Point(pCm) = {x_C, -y_C, z_C};
pCp = newp; Point(pCp) = {x_C, y_C, z_C};

// attachment, C- -> nadir -> C+, on the cone r_ns(z) = r_b + (r_c - r_b) z/h
pts[] = {pCm};
For j In {1:nEdge-1}
    phi = Phi*(-1 + 2*j/nEdge);
    za = h*(1 - Cos(1.5*phi));
    ra = r_b + (r_c - r_b)*za/h;
    p = newp; Point(p) = {ra*Cos(phi), ra*Sin(phi), za};
    pts[] += {p};
EndFor
pts[] += {pCp};
attach = newc; Spline(attach) = pts[];

// free edge, C+ -> M -> C-: straight in a top view, parallel to the
// neighbours' free edges at gap/2 from the line of symmetry between them,
// rounded over eps_r near the centre M = (d_M, 0, z_M)
sC = Sqrt(y_C^2 + eps_r^2) - eps_r;
pts[] = {pCp};
For j In {1:nEdge-1}
    y = y_C*(1 - 2*j/nEdge);
    s = (Sqrt(y^2 + eps_r^2) - eps_r)/sC;
    p = newp; Point(p) = {d_M + (x_C - d_M)*s, y, z_M + (z_C - z_M)*s};
    pts[] += {p};
EndFor
pts[] += {pCm};
free = newc; Spline(free) = pts[];

// mid-line (the filling passes through its inner points): the quadratic
// Bezier from the nadir N = (r_b, 0, 0) over Q = (q_r, 0, q_z) to M
mid[] = {};
For j In {1:7}
    t = j/8;
    p = newp;
    Point(p) = {(1-t)^2*r_b + 2*t*(1-t)*q_r + t^2*d_M, 0, 2*t*(1-t)*q_z + t^2*z_M};
    mid[] += {p};
EndFor

loop = newll; Curve Loop(loop) = {attach, free};
s1 = news; Surface(s1) = {loop} Using Point{mid[]};
Recursive Delete { Point{mid[]}; }
s2[] = Rotate {{0, 0, 1}, {0, 0, 0}, 2*Pi/3} { Duplicata { Surface{s1}; } };
s3[] = Rotate {{0, 0, 1}, {0, 0, 0}, 4*Pi/3} { Duplicata { Surface{s1}; } };
leaflets[] = {s1, s2[0], s3[0]};

For k In {1:3}
    Physical Surface(Sprintf("leaflet%g", k)) = {leaflets[k-1]};
    b[] = Boundary{ Surface{leaflets[k-1]}; };
    If (#b[] != 2)
        General.AbortOnError = 4;
        Error("aorticLeaflets.geo: leaflet %g has %g boundary curves, expected 2 (attachment, free edge)", k, #b[]);
    EndIf
    // the attachment reaches down to the base (z = 0), the free edge not
    bb[] = BoundingBox Curve{Abs(b[0])};
    ia = 0;
    If (bb[2] > 0.5*z_M) ia = 1; EndIf
    Physical Curve(Sprintf("attachment%g", k)) = {Abs(b[ia])};
    Physical Curve(Sprintf("freeEdge%g", k)) = {Abs(b[1 - ia])};
EndFor

Mesh.MeshSizeMin = leafletSize;
Mesh.MeshSizeMax = leafletSize;
Mesh.MeshSizeFromCurvature = 0;
Mesh.Algorithm = 6;        // Frontal-Delaunay: well-shaped triangles
