#!/usr/bin/python3
"""The aortic root wall as a triangulated surface, for the leaflets' rigid
contact (smoothedSolid RigidSurface): the wall of aorticRoot.geo from
z = -r_b/4 (a band of the inlet extension) to z = h_s + r_c/2 (a band of the
outlet extension), meshed with triangles of size wallSize, every normal
pointing into the fluid (towards the axis), which is the leaflets' side.

    rootWall.py out.stl [-setnumber name value ...]

Writes out.stl (ASCII STL) and, beside it, the same surface as gmsh msh 2.2
(out.msh, physical surface rootWall), both in metres.
"""
import os
import sys

import numpy as np

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
SCALE = 1e-3  # mm -> m


def fail(message):
    sys.stderr.write("rootWall.py: %s\n" % message)
    sys.exit(1)


def main(argv):
    if len(argv) < 2 or not argv[1].endswith(".stl"):
        fail("usage: rootWall.py out.stl [-setnumber name value ...]")
    out = argv[1]
    gmsh.initialize(["rootWall.py"] + argv[2:])
    gmsh.option.setNumber("General.Terminal", 1)
    gmsh.option.setNumber("General.Verbosity", 2)
    gmsh.open(os.path.join(HERE, "aorticRoot.geo"))
    value = {n: gmsh.onelab.getNumber("valve/" + n)[0]
             for n in ("r_b", "r_c", "h_s", "wallSize")}
    zLo = -0.25 * value["r_b"]
    zHi = value["h_s"] + 0.5 * value["r_c"]
    gmsh.option.setNumber("Mesh.MeshSizeMin", value["wallSize"])
    gmsh.option.setNumber("Mesh.MeshSizeMax", value["wallSize"])
    gmsh.model.mesh.generate(2)

    wall = []
    for d, tag in gmsh.model.getPhysicalGroups(2):
        if gmsh.model.getPhysicalName(d, tag) == "wall":
            wall = gmsh.model.getEntitiesForPhysicalGroup(d, tag)
    if len(wall) == 0:
        fail("aorticRoot.geo has no physical surface wall")
    tags, coord, _ = gmsh.model.mesh.getNodes()
    X = coord.reshape(-1, 3)
    local = {int(t): i for i, t in enumerate(tags)}
    tris = []
    for s in wall:
        _, nodes = gmsh.model.mesh.getElementsByType(2, s)
        tris.append(np.array([local[int(n)] for n in nodes], dtype=int).reshape(-1, 3))
    gmsh.finalize()
    T = np.vstack(tris)
    c = X[T].mean(axis=1)
    T = T[(c[:, 2] >= zLo) & (c[:, 2] <= zHi)]
    c = X[T].mean(axis=1)
    # normals into the fluid: against the radial direction (the wall is
    # r = r(phi, z), star-shaped about the axis at every height)
    n = np.cross(X[T[:, 1]] - X[T[:, 0]], X[T[:, 2]] - X[T[:, 0]])
    radial = np.einsum("ij,ij->i", n[:, :2], c[:, :2])
    T[radial > 0] = T[radial > 0][:, [0, 2, 1]]
    n = np.cross(X[T[:, 1]] - X[T[:, 0]], X[T[:, 2]] - X[T[:, 0]])
    radial = np.einsum("ij,ij->i", n[:, :2], c[:, :2])
    if np.any(radial >= 0):
        fail("%d wall triangles have no inward normal" % int(np.sum(radial >= 0)))
    used, T = np.unique(T, return_inverse=True)
    T = T.reshape(-1, 3)
    X = X[used] * SCALE
    n = np.cross(X[T[:, 1]] - X[T[:, 0]], X[T[:, 2]] - X[T[:, 0]])
    n /= np.linalg.norm(n, axis=1)[:, None]

    with open(out, "w") as f:
        f.write("solid rootWall\n")
        for t, nn in zip(T, n):
            f.write("  facet normal %.9g %.9g %.9g\n    outer loop\n" % tuple(nn))
            for v in t:
                f.write("      vertex %.16g %.16g %.16g\n" % tuple(X[v]))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid rootWall\n")
    mshOut = os.path.splitext(out)[0] + ".msh"
    with open(mshOut, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n1\n2 1 "rootWall"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % len(X))
        for i, x in enumerate(X):
            f.write("%d %.16g %.16g %.16g\n" % (i + 1, x[0], x[1], x[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % len(T))
        for i, t in enumerate(T):
            f.write("%d 2 2 1 1 %d %d %d\n" % (i + 1, t[0] + 1, t[1] + 1, t[2] + 1))
        f.write("$EndElements\n")
    print("rootWall.py: wrote %s and %s: %d triangles, %d nodes, z from %g to %g mm, "
          "normals into the fluid" % (out, mshOut, len(T), len(X), zLo, zHi))


if __name__ == "__main__":
    main(sys.argv)
