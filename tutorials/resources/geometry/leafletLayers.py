#!/usr/bin/python3
"""Tetrahedra of the three aortic valve leaflets, in layers through the
thickness, built from the triangulated mid-surfaces of aorticLeaflets.geo.

    leafletLayers.py out.msh [-layers N] [-setnumber name value ...]

Each mid-surface node x gets N+1 copies x + (i/N - 1/2) L_t n(x), i = 0..N,
with n the unit normal of the CAD mid-surface at x (pointing to the aortic
side); each triangle gives N prisms, each prism 3 tetrahedra, split along
the diagonals that run from the lower- to the higher-numbered node of each
side, so that neighbouring prisms share their faces. Every node of every
tetrahedron lies on one of the N+1 offset surfaces; N = 2 (the default) is
the paper's two layers, with the nodes on the ventricular face, the
mid-surface and the aortic face.

Beside out.msh, out.circumferential holds each tetrahedron's circumferential
direction (e_theta at its triangle's centre projected onto the mid-surface's
tangent plane, unit, counter-clockwise about +z; the fibre direction of
leaflet tissue), one line per tetrahedron in the order of out.msh.

Written as gmsh msh 2.2 in metres (the geometry is in mm) with the physical
groups (read by smoothedSolid's TetMesh::fromGmsh):
    volumes   leaflet1, leaflet2, leaflet3
    surfaces  ventricular1..3, aortic1..3 (the leaflet faces),
              attachment (the side faces along the attachment to the root
              wall, all three leaflets: fix these nodes), freeEdge1..3
Other arguments (-setnumber ...) go to gmsh as on its command line.
"""
import os
import sys

import numpy as np

import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
SCALE = 1e-3  # mm -> m


def fail(message):
    sys.stderr.write("leafletLayers.py: %s\n" % message)
    sys.exit(1)


def parseArguments(argv):
    if len(argv) < 2 or argv[1].startswith("-"):
        fail("usage: leafletLayers.py out.msh [-layers N] [-setnumber name value ...]")
    out = argv[1]
    layers = 2
    gmshArgs = []
    i = 2
    while i < len(argv):
        if argv[i] == "-layers":
            if i + 1 >= len(argv):
                fail("-layers needs a value")
            try:
                layers = int(argv[i + 1])
            except ValueError:
                fail("-layers %s: not an integer" % argv[i + 1])
            if layers < 1:
                fail("-layers %d: at least 1" % layers)
            i += 2
        else:
            gmshArgs.append(argv[i])
            i += 1
    return out, layers, gmshArgs


def openLeaflets(gmshArgs):
    """Open aorticLeaflets.geo with the parameters, mesh its surfaces (2D).
    A parameter error in the .geo exits the process with status 1."""
    gmsh.initialize(["leafletLayers.py"] + gmshArgs)
    gmsh.option.setNumber("General.Terminal", 1)
    gmsh.option.setNumber("General.Verbosity", 2)
    gmsh.open(os.path.join(HERE, "aorticLeaflets.geo"))


def groupEntity(dim, name):
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        if gmsh.model.getPhysicalName(d, tag) == name:
            ents = gmsh.model.getEntitiesForPhysicalGroup(d, tag)
            if len(ents) != 1:
                fail("physical group %s holds %d entities, expected 1" % (name, len(ents)))
            return int(ents[0])
    fail("aorticLeaflets.geo has no physical group %s" % name)


def surfaceMesh(surf):
    """Nodes (mm), CAD normals and triangles of one mid-surface."""
    tags, coord, param = gmsh.model.mesh.getNodes(2, surf, includeBoundary=True,
                                                   returnParametricCoord=True)
    X = coord.reshape(-1, 3)
    normals = gmsh.model.getNormal(surf, param).reshape(-1, 3)
    local = {int(t): i for i, t in enumerate(tags)}
    etags, enodes = gmsh.model.mesh.getElementsByType(2, surf)
    tris = np.array([local[int(t)] for t in enodes], dtype=int).reshape(-1, 3)
    return tags, X, normals, tris, local


def curveNodes(curve, local):
    tags, _, _ = gmsh.model.mesh.getNodes(1, curve, includeBoundary=True)
    return {local[int(t)] for t in tags if int(t) in local}


def boundaryEdges(tris):
    count = {}
    for t in tris:
        for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
            key = (min(a, b), max(a, b))
            count[key] = count.get(key, 0) + 1
    return [e for e, n in count.items() if n == 1]


def tetVolumes(X, tets):
    a = X[tets[:, 1]] - X[tets[:, 0]]
    b = X[tets[:, 2]] - X[tets[:, 0]]
    c = X[tets[:, 3]] - X[tets[:, 0]]
    return np.einsum("ij,ij->i", np.cross(a, b), c) / 6.0


def main():
    out, layers, gmshArgs = parseArguments(sys.argv)
    openLeaflets(gmshArgs)
    L_t = gmsh.onelab.getNumber("valve/L_t")[0]
    gmsh.model.mesh.generate(2)

    allX = []
    tets = []           # (tet node ids, leaflet)
    circumferential = []  # unit vector per tet
    faces = {}          # physical surface name -> list of triangles
    offset = 0
    for k in (1, 2, 3):
        surf = groupEntity(2, "leaflet%d" % k)
        _, X, n, tris, local = surfaceMesh(surf)
        nm = len(X)
        # the normal towards the aortic side: on the whole, +z
        if np.sum(n[:, 2]) < 0:
            n = -n
        # orient the triangles' normals along n
        tn = np.cross(X[tris[:, 1]] - X[tris[:, 0]], X[tris[:, 2]] - X[tris[:, 0]])
        flip = np.einsum("ij,ij->i", tn, n[tris].mean(axis=1)) < 0
        tris[flip] = tris[flip][:, [0, 2, 1]]

        for i in range(layers + 1):
            allX.append(X + (i / layers - 0.5) * L_t * n)

        def node(level, j):
            return offset + level * nm + j

        # circumferential direction of each triangle: e_theta at its centre,
        # in the tangent plane of the mid-surface
        centre = X[tris].mean(axis=1)
        normal = n[tris].mean(axis=1)
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        etheta = np.stack([-centre[:, 1], centre[:, 0], np.zeros(len(tris))], axis=1)
        etheta -= np.einsum("ij,ij->i", etheta, normal)[:, None] * normal
        etheta /= np.linalg.norm(etheta, axis=1)[:, None]

        for t, e in zip(tris, etheta):
            a, b, c = sorted(t)
            for l in range(layers):
                A, B, C = (node(l, a), node(l, b), node(l, c))
                A1, B1, C1 = (node(l + 1, a), node(l + 1, b), node(l + 1, c))
                for tet in ((A, B, C, C1), (A, B, B1, C1), (A, A1, B1, C1)):
                    tets.append((tet, k))
                    circumferential.append(e)

        faces["ventricular%d" % k] = [[node(0, v) for v in t[[0, 2, 1]]] for t in tris]
        faces["aortic%d" % k] = [[node(layers, v) for v in t] for t in tris]

        onAttach = curveNodes(groupEntity(1, "attachment%d" % k), local)
        onFree = curveNodes(groupEntity(1, "freeEdge%d" % k), local)
        for name, on in (("attachment", onAttach), ("freeEdge%d" % k, onFree)):
            side = faces.setdefault(name, [])
            for a, b in boundaryEdges(tris):
                if a in on and b in on:
                    lo, hi = min(a, b), max(a, b)
                    for l in range(layers):
                        # the diagonal of the prisms' split: lo(l) - hi(l+1)
                        side.append([node(l, lo), node(l, hi), node(l + 1, hi)])
                        side.append([node(l, lo), node(l + 1, hi), node(l + 1, lo)])
        offset += (layers + 1) * nm

    X = np.vstack(allX)
    T = np.array([t for t, _ in tets], dtype=int)
    part = np.array([k for _, k in tets], dtype=int)
    vol = tetVolumes(X, T)
    neg = vol < 0
    T[neg] = T[neg][:, [0, 2, 1, 3]]
    vol = np.abs(vol)
    if np.any(vol <= 0):
        fail("%d degenerate tetrahedra: try a larger leafletSize or smaller L_t"
             % int(np.sum(vol <= 0)))

    gmsh.finalize()
    writeMsh22(out, X * SCALE, T, part, faces)
    circ = os.path.splitext(out)[0] + ".circumferential"
    with open(circ, "w") as f:
        f.write("# circumferential direction (unit) of each tetrahedron of %s, in the\n"
                "# order of its $Elements (leaflet1, leaflet2, leaflet3): ex ey ez\n"
                % os.path.basename(out))
        for d in circumferential:
            f.write("%.9g %.9g %.9g\n" % tuple(d))
    print("leafletLayers.py: wrote %s: %d tetrahedra, %d nodes, %d layers"
          % (out, len(T), len(X), layers))


def writeMsh22(fileName, X, T, part, faces):
    names = [(3, k, "leaflet%d" % k) for k in (1, 2, 3)]
    surfaceNames = sorted(faces)
    names += [(2, 10 + i, s) for i, s in enumerate(surfaceNames)]
    with open(fileName, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write("$PhysicalNames\n%d\n" % len(names))
        for dim, tag, name in names:
            f.write('%d %d "%s"\n' % (dim, tag, name))
        f.write("$EndPhysicalNames\n")
        f.write("$Nodes\n%d\n" % len(X))
        for i, x in enumerate(X):
            f.write("%d %.16g %.16g %.16g\n" % (i + 1, x[0], x[1], x[2]))
        f.write("$EndNodes\n")
        nElem = len(T) + sum(len(faces[s]) for s in surfaceNames)
        f.write("$Elements\n%d\n" % nElem)
        e = 0
        for i, s in enumerate(surfaceNames):
            for t in faces[s]:
                e += 1
                f.write("%d 2 2 %d %d %d %d %d\n" % (e, 10 + i, 10 + i, t[0] + 1, t[1] + 1, t[2] + 1))
        for t, k in zip(T, part):
            e += 1
            f.write("%d 4 2 %d %d %d %d %d %d\n" % (e, k, k, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1))
        f.write("$EndElements\n")



if __name__ == "__main__":
    main()
