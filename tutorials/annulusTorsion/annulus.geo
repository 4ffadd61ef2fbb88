// The elastic annulus a + d < r < b - d, d < z < H - d (inset d from the
// fluid's walls so that every node lies inside a fluid cell): the (r, z)
// rectangle, nr x nz squares split into triangles, revolved about the z
// axis in four quarters of nq layers; each prism split into three tets
// (no Recombine). gmsh built-in kernel, msh 2.2.
DefineConstant[ a = 0.5, b = 1.0, H = 0.1, d = 0.0025, nr = 30, nz = 2, nq = 24 ];
Mesh.MshFileVersion = 2.2;
Point(1) = {a + d, 0, d};
Point(2) = {b - d, 0, d};
Point(3) = {b - d, 0, H - d};
Point(4) = {a + d, 0, H - d};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nr + 1;
Transfinite Curve{2, 4} = nz + 1;
Transfinite Surface{1} Alternate;
s = 1;
For q In {0 : 3}
    out[] = Extrude {{0, 0, 1}, {0, 0, 0}, Pi/2} { Surface{s}; Layers{nq}; };
    s = out[0];
    vol[q] = out[1];
    bottom[q] = out[2];
    outer[q] = out[3];
    top[q] = out[4];
    inner[q] = out[5];
EndFor
Coherence;
Physical Volume("annulus") = {vol[]};
Physical Surface("inner") = {inner[]};     // held: the inner cylinder
Physical Surface("outer") = {outer[]};     // held: the outer cylinder
Physical Surface("ends") = {bottom[], top[]};   // free
