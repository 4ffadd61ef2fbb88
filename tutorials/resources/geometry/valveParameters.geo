// Parameters of the idealised aortic valve (Yao et al. 2012, Table 1; the
// construction follows Labrosse et al., J Biomech 39:2665, 2006), their
// checks, and the quantities derived from them. Included by aorticRoot.geo
// and aorticLeaflets.geo; every number can be set with
//     gmsh -setnumber <name> <value> ...
// Lengths in mm (the mesh files are written in metres: Mesh.ScalingFactor).
// A parameter that makes no valid valve stops gmsh with an error naming it
// (exit status 1).
//
// Frame: z is the valve axis, z = 0 the valve base (annulus, nadir of the
// leaflet attachments), flow towards +z (ventricle z < 0, aorta z > 0).
// Leaflet k (k = 1, 2, 3) is centred at the angle 120 (k - 1) degrees,
// the commissures are at 60, 180 and 300 degrees.
//
//   r_b    radius at the base of the valve (z = 0)
//   r_c    radius at the commissures (z = h) and of the ascending aorta
//   h      valve height: height of the commissures
//   r_sm   largest radius of the sinuses (at the centre of each sinus)
//   h_sm   height of r_sm
//   h_s    sinus height: the sinuses end (sinotubular junction) at z = h_s
//   L_h    leaflet height: length of the leaflet's mid-line, from the nadir
//          of its attachment to the valve centre
//   L_t    leaflet thickness
//   gap    clear gap between neighbouring closed leaflets (between their
//          faces; their mid-surfaces are gap + L_t apart)
//   belly  sag of the leaflet's mid-line towards the ventricle, as a
//          fraction of its chord (0: a ruled, flat-bellied leaflet)
//   coapt  height of the coaptation band at the leaflet's centre: the
//          leaflet turns up along the line of symmetry with each neighbour
//          and runs parallel to the neighbour's band, gap apart, for this
//          height, tapering to 0 at the commissures (0: no band, closed
//          leaflets meet edge to edge). L_h includes the band.
//   L_in   length of the inlet (ventricular) extension, radius r_b
//   L_out  length of the outlet (aortic) extension above h_s, radius r_c
//   fluidSize    tetrahedron size of the fluid domain
//   fluidAlgorithm3D  gmsh's 3D mesher for it (aorticRoot.geo): 10 HXT
//                (default; its mesh differs from call to call), 1 Delaunay
//                (the same mesh on every call)
//   leafletSize  triangle size of the leaflets' mid-surfaces
//   wallSize     triangle size of the rigid contact surface (root wall)

If (!Exists(r_b))   r_b = 11.75; EndIf
If (!Exists(r_c))   r_c = 9.10;  EndIf
If (!Exists(h))     h = 17.8;    EndIf
If (!Exists(r_sm))  r_sm = 13.3; EndIf
If (!Exists(h_sm))  h_sm = 10.0; EndIf
If (!Exists(h_s))   h_s = 18.33; EndIf
If (!Exists(L_h))   L_h = 16.0;  EndIf
If (!Exists(L_t))   L_t = 0.3;   EndIf
If (!Exists(gap))   gap = 0.4;   EndIf
If (!Exists(belly)) belly = 0.15; EndIf
If (!Exists(coapt)) coapt = 0;   EndIf
If (!Exists(L_in))  L_in = 2*r_b; EndIf
If (!Exists(L_out)) L_out = 3*r_b; EndIf
// mesh sizes: the 'coarse' preset (makeValveMeshes sets the others)
If (!Exists(fluidSize))   fluidSize = 1.6;   EndIf
If (!Exists(leafletSize)) leafletSize = 1.2; EndIf
If (!Exists(wallSize))    wallSize = 0.8;    EndIf

//------------------------------------------------------------------------------
// Checks: each names the parameter and what a valid value is

If (r_b <= 0 || r_c <= 0 || h <= 0 || h_sm <= 0 || h_s <= 0)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: r_b = %g, r_c = %g, h = %g, h_sm = %g, h_s = %g: all must be positive", r_b, r_c, h, h_sm, h_s);
    Abort;
EndIf
If (L_t <= 0)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: L_t = %g: the leaflet thickness must be positive", L_t);
    Abort;
EndIf
If (r_c > r_sm || r_b > r_sm)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: r_sm = %g must be at least r_c = %g and r_b = %g (the sinuses bulge outwards)", r_sm, r_c, r_b);
    Abort;
EndIf
If (h_sm >= h_s)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: h_sm = %g must be below the sinus height h_s = %g", h_sm, h_s);
    Abort;
EndIf
If (h > h_s)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: h = %g: the commissures must not lie above the sinotubular junction h_s = %g", h, h_s);
    Abort;
EndIf
If (gap <= 0 || gap >= 0.25*r_c)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: gap = %g must lie in (0, r_c/4 = %g)", gap, 0.25*r_c);
    Abort;
EndIf
If (belly < 0 || belly > 0.4)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: belly = %g must lie in [0, 0.4]", belly);
    Abort;
EndIf
If (coapt < 0 || coapt > 0.5*h)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: coapt = %g must lie in [0, h/2 = %g]", coapt, 0.5*h);
    Abort;
EndIf
If (L_t > 0.1*h)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: L_t = %g is too thick for this valve (at most 0.1 h = %g)", L_t, 0.1*h);
    Abort;
EndIf
If (L_in <= 0 || L_out <= 0)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: L_in = %g and L_out = %g must be positive (at least 2 r_b = %g keeps the outlet clear of the sinus flow)", L_in, L_out, 2*r_b);
    Abort;
EndIf
If (fluidSize <= 0 || leafletSize <= 0 || wallSize <= 0)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: fluidSize = %g, leafletSize = %g, wallSize = %g must be positive", fluidSize, leafletSize, wallSize);
    Abort;
EndIf

//------------------------------------------------------------------------------
// Root wall, r(phi, z) = r_ns(z) + (r_s(z) - r_ns(z)) w(phi, z) with phi the
// angle from the nearest sinus centre:
//   r_ns(z)  commissural (inter-leaflet) wall: a cone from r_b at z = 0 to
//            r_c at z = h, then r_c;
//   r_s(z)   sinus centre: r_b at 0, rising (quarter sine) to r_sm at h_sm,
//            falling (quarter cosine) to r_c at h_s;
//   w        = cos^2(pi/2 phi/phi_w(z)) inside the sinus, 0 outside, where
//            phi_w(z) is the sinus' half-width at z: the leaflet attachment
//            z_a(phi) = h (1 - cos(3 phi/2)) inverted, and 60 degrees above h.
// The sinus starts at the leaflet attachment (w = 0 there), so each leaflet
// attaches to the root along the curve z_a on the cone r_ns.

//------------------------------------------------------------------------------
// Leaflets (closed), in the frame of leaflet 1 (centre at phi = 0):
//   attachment  z_a(phi), radius r_ns(z_a), for |phi| <= Phi = 60 deg - dPhi,
//               dPhi chosen so that neighbouring mid-surfaces are gap + L_t
//               apart at//               the commissures;
//   free edge   in a top view the hyperbola x = d_V + k sqrt(y^2 + eps_r^2)
//               through the commissure ends C: nearly straight, and
//               parallel to the line of symmetry between neighbouring
//               leaflets at (gap + L_t)/2 from it (d_V = (gap + L_t)/2/
//               sin(60)), rounded near the leaflet's centre point
//               M = (d_M, 0, z_M) and never closer to that line; height
//               from z_M at M to z_C at C;
//   mid-line    (phi = 0) the quadratic Bezier from the nadir N = (r_b, 0, 0)
//               to M with its control point belly * chord below the chord;
//               z_M is chosen so that its length is L_h.
//   coaptation  with coapt > 0 the curve above is the coaptation line, not
//               the free edge: each section's Bezier arrives at it
//               vertically (control point straight below it, belly * chord
//               from the chord, at most 0.9 of the section's rise below
//               it) and the leaflet goes on vertically, parallel to its
//               neighbour's band, by coapt (1 - s) with s = 0 at M and 1 at
//               C, to the free edge. The mid-line's length L_h is the
//               Bezier's plus coapt; the free edge's centre is z_M + coapt.
dPhi = Asin(0.5*(gap + L_t)/r_c);
Phi = Pi/3 - dPhi;
z_C = h*(1 - Cos(1.5*Phi));
r_C = r_b + (r_c - r_b)*z_C/h;
x_C = r_C*Cos(Phi);
y_C = r_C*Sin(Phi);
// rounding of the free edge (the coaptation line) at the centre; with a
// coaptation band, less, so that the bands face each other gap apart up to
// near the centre
If (!Exists(eps_r))
    eps_r = 0.1*r_c;
    If (coapt > 0) eps_r = 0.05*r_c; EndIf
EndIf
d_V = 0.5*(gap + L_t)/Sin(Pi/3);
k_F = (x_C - d_V)/Sqrt(y_C^2 + eps_r^2);
d_M = d_V + k_F*eps_r;

// Mid-line length for the centre height zm (Bezier N-Q-M, 64 chords), as
// a macro: in zm, out len
dr = r_b - d_M;
Macro MidLineLength
    qr = 0.5*(r_b + d_M) - belly*zm;
    qz = 0.5*zm - belly*dr;
    If (coapt > 0)
        // vertical arrival at M: control point below M, belly * chord from
        // the chord (chord length^2 / dr below M), at most 0.9 zm
        qr = d_M;
        qz = zm - Min(belly*(dr^2 + zm^2)/dr, 0.9*zm);
    EndIf
    len = 0; pr = r_b; pz = 0;
    For j In {1:64}
        t = j/64;
        cr = (1-t)^2*r_b + 2*t*(1-t)*qr + t^2*d_M;
        cz = 2*t*(1-t)*qz + t^2*zm;
        len += Sqrt((cr - pr)^2 + (cz - pz)^2);
        pr = cr; pz = cz;
    EndFor
    len += coapt;
Return
If (L_h <= dr + coapt)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: L_h = %g is too short: the leaflet cannot reach the valve centre from the base (r_b - d_M = %g) with its coaptation band (coapt = %g)", L_h, dr, coapt);
    Abort;
EndIf
zm = z_C - 0.5*L_t - coapt;
If (zm <= 0)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: coapt = %g is too high: the band would rise above the commissures (z = %g)", coapt, z_C);
    Abort;
EndIf
Call MidLineLength;
If (L_h > len)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: L_h = %g is longer than the root allows: the leaflet centre would rise above its commissures (z = %g); with r_b = %g, h = %g, belly = %g, coapt = %g, L_h must be below %g", L_h, z_C, r_b, h, belly, coapt, len);
    Abort;
EndIf
// bisection for z_M in (0, z_C - L_t/2 - coapt]
zLo = 0; zHi = z_C - 0.5*L_t - coapt;
For it In {1:50}
    zm = 0.5*(zLo + zHi);
    Call MidLineLength;
    If (len > L_h)
        zHi = zm;
    Else
        zLo = zm;
    EndIf
EndFor
z_M = 0.5*(zLo + zHi);
zm = z_M;
Call MidLineLength;
q_r = qr;
q_z = qz;
If (q_z < 0.5*L_t)
    General.AbortOnError = 4; // exit(1) at the error
    Error("valveParameters.geo: belly = %g sags the leaflet below the valve base; use a smaller belly or a larger L_h", belly);
    Abort;
EndIf

// Root wall radius (see above) as a macro: in phiw (angle from the nearest
// sinus centre, |phiw| <= 60 deg) and zw (0 <= zw <= h_s), out rw
Macro WallRadius
    If (zw < h)
        rns = r_b + (r_c - r_b)*zw/h;
        phiW = Acos(1 - zw/h)/1.5;
    Else
        rns = r_c;
        phiW = Pi/3;
    EndIf
    If (zw < h_sm)
        rsc = r_b + (r_sm - r_b)*Sin(0.5*Pi*zw/h_sm);
    Else
        rsc = r_c + (r_sm - r_c)*Cos(0.5*Pi*(zw - h_sm)/(h_s - h_sm));
    EndIf
    rw = rns;
    If (Fabs(phiw) < phiW)
        rw = rns + (rsc - rns)*Cos(0.5*Pi*phiw/phiW)^2;
    EndIf
Return

// The values in use, for the scripts that read this geometry through the
// gmsh API (gmsh.onelab.getNumber("valve/<name>"))
SetNumber("valve/r_b", r_b); SetNumber("valve/r_c", r_c); SetNumber("valve/h", h);
SetNumber("valve/r_sm", r_sm); SetNumber("valve/h_sm", h_sm);
SetNumber("valve/h_s", h_s); SetNumber("valve/L_h", L_h);
SetNumber("valve/L_t", L_t); SetNumber("valve/gap", gap);
SetNumber("valve/belly", belly); SetNumber("valve/coapt", coapt); SetNumber("valve/L_in", L_in);
SetNumber("valve/L_out", L_out); SetNumber("valve/fluidSize", fluidSize);
SetNumber("valve/leafletSize", leafletSize);
SetNumber("valve/wallSize", wallSize);
SetNumber("valve/z_C", z_C); SetNumber("valve/z_M", z_M);
SetNumber("valve/Phi", Phi); SetNumber("valve/x_C", x_C);
SetNumber("valve/y_C", y_C); SetNumber("valve/eps_r", eps_r);
SetNumber("valve/d_V", d_V); SetNumber("valve/k_F", k_F);
