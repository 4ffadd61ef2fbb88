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

// Leaflet 1 (centre at angle 0), parametrised by u in [-1, 1] from the
// commissure end C- (y < 0) to C+ and v in [0, 1] from the attachment to the
// free edge:
//   attachment  A(u): phi = u Phi, z = z_a(phi), on the cone r_ns(z);
//   free edge   F(u): y = u y_C, x = d_V + k_F sqrt(y^2 + eps_r^2) (see
//               valveParameters.geo), height from z_M at M to z_C at C;
//   between     the quadratic Bezier A - Q - F, Q the chord's midpoint moved
//               by belly * |AF| perpendicular to the chord in the vertical
//               plane through A and F, downwards (towards the ventricle). In
//               a top view it runs straight from A to F, so the leaflet never
//               reaches beyond its free edge towards its neighbours;
//   band        with coapt > 0 (valveParameters.geo), F(u) is the
//               coaptation line: the Bezier's control point lies straight
//               below F (belly * |AF| from the chord, at most 0.9 of the
//               rise from A to F), so that the section arrives at F
//               vertically, and the leaflet goes on vertically from F by
//               coapt (1 - s(u)) to the free edge T(u) (s = 0 at the
//               centre, 1 at the commissures). Neighbouring bands are
//               parallel, their faces gap apart.
// The mid-surface is the OpenCASCADE filling of the curve loop attachment +
// free edge through the Bezier points of an inner (u, v) grid; at u = 0 the
// Bezier is the mid-line whose length is L_h (valveParameters.geo).
Macro AttachmentPoint   // in u, out ax, ay, az
    phi = u*Phi;
    az = h*(1 - Cos(1.5*phi));
    ar = r_b + (r_c - r_b)*az/h;
    ax = ar*Cos(phi); ay = ar*Sin(phi);
Return
sC = Sqrt(y_C^2 + eps_r^2) - eps_r;
Macro FreeEdgePoint     // in u, out fx, fy, fz
    fy = u*y_C;
    fs = (Sqrt(fy^2 + eps_r^2) - eps_r)/sC;
    fx = d_V + k_F*Sqrt(fy^2 + eps_r^2);
    fz = z_M + (z_C - z_M)*fs;
    fh = coapt*(1 - fs);  // the band's height above F
Return
Macro SurfacePoint      // in u, v, out sx, sy, sz
    Call AttachmentPoint;
    Call FreeEdgePoint;
    cx = fx - ax; cy = fy - ay; cz = fz - az;
    cl = Sqrt(cx^2 + cy^2 + cz^2);
    // downward normal of the chord in its vertical plane: -(e_z - (e_z.c) c)
    px = cz*cx/cl^2; py = cz*cy/cl^2; pz = cz*cz/cl^2 - 1;
    pl = Sqrt(px^2 + py^2 + pz^2);
    qx = 0.5*(ax + fx) + belly*cl*px/pl;
    qy = 0.5*(ay + fy) + belly*cl*py/pl;
    qz = 0.5*(az + fz) + belly*cl*pz/pl;
    tb = v;
    If (coapt > 0)
        // control point below F: its distance from the chord is
        // depth * (horizontal chord) / |AF|
        ch = Sqrt(cx^2 + cy^2);
        depth = Min(belly*cl^2/ch, 0.9*cz);
        qx = fx; qy = fy; qz = fz - depth;
        // v in [0, vb]: the Bezier; [vb, 1]: the band (by length)
        vb = cl/(cl + fh);
        tb = Min(v/vb, 1);
    EndIf
    sx = (1-tb)^2*ax + 2*tb*(1-tb)*qx + tb^2*fx;
    sy = (1-tb)^2*ay + 2*tb*(1-tb)*qy + tb^2*fy;
    sz = (1-tb)^2*az + 2*tb*(1-tb)*qz + tb^2*fz;
    If (coapt > 0)
        If (v > vb)
            sz = fz + fh*(v - vb)/(1 - vb);
        EndIf
    EndIf
Return

pCm = newp; Point(pCm) = {x_C, -y_C, z_C};
pCp = newp; Point(pCp) = {x_C, y_C, z_C};

// attachment, C- -> nadir -> C+
pts[] = {pCm};
For j In {1:nEdge-1}
    u = -1 + 2*j/nEdge;
    Call AttachmentPoint;
    p = newp; Point(p) = {ax, ay, az};
    pts[] += {p};
EndFor
pts[] += {pCp};
attach = newc; Spline(attach) = pts[];

// free edge (the top of the band), C+ -> M -> C-
pts[] = {pCp};
For j In {1:nEdge-1}
    u = 1 - 2*j/nEdge;
    Call FreeEdgePoint;
    p = newp; Point(p) = {fx, fy, fz + fh};
    pts[] += {p};
EndFor
pts[] += {pCm};
free = newc; Spline(free) = pts[];

// inner points the filling passes through
If (!Exists(nFillU)) nFillU = 12; EndIf
If (!Exists(nFillV))
    nFillV = 6;
    If (coapt > 0) nFillV = 10; EndIf   // the band's bend
EndIf
mid[] = {};
For i In {1:nFillU-1}
    u = -1 + 2*i/nFillU;
    For j In {1:nFillV-1}
        v = j/nFillV;
        Call SurfacePoint;
        p = newp; Point(p) = {sx, sy, sz};
        mid[] += {p};
    EndFor
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
