#!/usr/bin/python3
"""Tetrahedra of the three aortic valve leaflets, in layers through the
thickness, built from the triangulated mid-surfaces of aorticLeaflets.geo.

    leafletLayers.py out.msh [-layers N] [-setnumber name value ...]

Each mid-surface node x gets N+1 copies x + (i/N - 1/2) L_t n(x), i = 0..N,
with n the unit normal of the CAD mid-surface at x (pointing to the aortic
side; with a coaptation band, coapt > 0, the nodes are first moved onto the
construction of aorticLeaflets.geo and n is its normal S_u x S_v, since the
CAD filling rounds the band's bend by up to about 0.1 mm); each triangle gives N prisms, each prism 3 tetrahedra, split along
the diagonals that run from the lower- to the higher-numbered node of each
side, so that neighbouring prisms share their faces. Every node of every
tetrahedron lies on one of the N+1 offset surfaces; N = 2 (the default) is
the paper's two layers, with the nodes on the ventricular face, the
mid-surface and the aortic face.

Beside out.msh, out.circumferential holds each tetrahedron's circumferential
direction, the fibre direction of leaflet tissue: the leaflet's
commissure-to-commissure direction, tangent to the lines v = const of the
construction in aorticLeaflets.geo (the attachment at v = 0, the free edge
at v = 1; dS/du, u from the commissure at y < 0 to the one at y > 0 for
leaflet 1) at its triangle's centre, projected onto the mid-surface's
tangent plane, unit; one line per tetrahedron in the order of out.msh. The
centre's (u, v) is that of the construction's nearest point; the largest
distance from a triangle's centre to it is printed (the OpenCASCADE
filling against the construction it passes through; with a band, whose
nodes lie on the construction, the flat triangles across its bend).

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


class LeafletConstruction:
    """The mid-surface S(u, v) of leaflet 1 as aorticLeaflets.geo builds it
    (macros AttachmentPoint, FreeEdgePoint, SurfacePoint), in mm."""

    def __init__(self):
        g = lambda name: gmsh.onelab.getNumber("valve/" + name)[0]
        for name in ("r_b", "r_c", "h", "belly", "coapt", "z_C", "z_M", "Phi",
                     "y_C", "eps_r", "d_V", "k_F"):
            setattr(self, name, g(name))
        self.sC = np.sqrt(self.y_C**2 + self.eps_r**2) - self.eps_r

    def point(self, u, v):
        u = np.asarray(u, dtype=float)
        v = np.asarray(v, dtype=float)
        phi = u * self.Phi
        az = self.h * (1 - np.cos(1.5 * phi))
        ar = self.r_b + (self.r_c - self.r_b) * az / self.h
        A = np.stack([ar * np.cos(phi), ar * np.sin(phi), az], axis=-1)
        fy = u * self.y_C
        rho = np.sqrt(fy**2 + self.eps_r**2)
        fs = (rho - self.eps_r) / self.sC
        F = np.stack([self.d_V + self.k_F * rho, fy,
                      self.z_M + (self.z_C - self.z_M) * fs], axis=-1)
        fh = self.coapt * (1 - fs)
        c = F - A
        cl = np.linalg.norm(c, axis=-1)
        cl = np.where(cl > 0, cl, 1e-300)
        t = v
        if self.coapt > 0:
            ch = np.maximum(np.hypot(c[..., 0], c[..., 1]), 1e-300)
            depth = np.minimum(self.belly * cl**2 / ch, 0.9 * c[..., 2])
            Q = F.copy()
            Q[..., 2] -= depth
            vb = cl / (cl + fh)
            t = np.minimum(v / vb, 1.0)
        else:
            p = np.stack([c[..., 2] * c[..., 0], c[..., 2] * c[..., 1],
                          c[..., 2]**2 - cl**2], axis=-1) / (cl**2)[..., None]
            pl = np.linalg.norm(p, axis=-1)
            pl = np.where(pl > 0, pl, 1e-300)
            Q = 0.5 * (A + F) + (self.belly * cl / pl)[..., None] * p
        t = t[..., None]
        S = (1 - t)**2 * A + 2 * t * (1 - t) * Q + t**2 * F
        if self.coapt > 0:
            band = (v > vb)
            zBand = F[..., 2] + fh * (v - vb) / np.where(vb < 1, 1 - vb, 1)
            S[..., 2] = np.where(band, zBand, S[..., 2])
        return S

    def tangents(self, u, v, h=1e-6):
        """S_u and S_v by central differences (one-sided at the bounds;
        S_u taken just inside the commissure ends, where S_v vanishes)."""
        u = np.clip(u, -1 + h, 1 - h)
        Su = (self.point(u + h, v) - self.point(u - h, v)) / (2 * h)
        Sv = (self.point(u, np.clip(v + h, 0, 1))
              - self.point(u, np.clip(v - h, 0, 1))) / (2 * h)
        return Su, Sv

    def nearestParameters(self, points, iterations=4, nu=801, nv=401):
        """(u, v) of the point nearest each of 'points' (leaflet 1's
        frame): nearest point of a nu x nv grid (its search tree built
        once), then Gauss-Newton steps."""
        if not hasattr(self, "_grid"):
            from scipy.spatial import cKDTree
            U, V = np.meshgrid(np.linspace(-1, 1, nu), np.linspace(0, 1, nv),
                               indexing="ij")
            self._grid = (U.ravel(), V.ravel(),
                          cKDTree(self.point(U, V).reshape(-1, 3)))
        U, V, tree = self._grid
        _, idx = tree.query(points)
        u, v = U[idx], V[idx]
        for _ in range(iterations):
            Su, Sv = self.tangents(u, v)
            r = points - self.point(u, v)
            a11 = np.einsum("ij,ij->i", Su, Su)
            a12 = np.einsum("ij,ij->i", Su, Sv)
            a22 = np.einsum("ij,ij->i", Sv, Sv)
            b1 = np.einsum("ij,ij->i", Su, r)
            b2 = np.einsum("ij,ij->i", Sv, r)
            det = a11 * a22 - a12**2
            good = det > 1e-12 * np.maximum(a11 * a22, 1e-300)
            safe = np.where(good, det, 1)
            u = np.clip(u + np.where(good, (a22 * b1 - a12 * b2) / safe, 0), -1, 1)
            v = np.clip(v + np.where(good, (a11 * b2 - a12 * b1) / safe, 0), 0, 1)
        return u, v

    def normal(self, u, v):
        """Unit S_u x S_v, oriented +z on the whole (the aortic side)"""
        Su, Sv = self.tangents(u, v)
        n = np.cross(Su, Sv)
        n /= np.linalg.norm(n, axis=1)[:, None]
        return -n if np.sum(n[:, 2]) < 0 else n


def rotation(k):
    """Rotation from leaflet 1's frame to leaflet k's (120 (k - 1) degrees
    about z)"""
    a = 2 * np.pi / 3 * (k - 1)
    return np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])


def snapToConstruction(construction, X, k, onAttach, onFree):
    """Mid-surface nodes of leaflet k moved onto the construction (the
    attachment nodes to v = 0, the free edge's to v = 1), with its normal.
    Returns the new coordinates, normals and the largest move (mm)."""
    R = rotation(k)
    u, v = construction.nearestParameters(X @ R)
    v[list(onAttach)] = 0.0
    v[list(onFree)] = 1.0
    P = construction.point(u, v) @ R.T
    return P, construction.normal(u, v) @ R.T, float(np.max(np.linalg.norm(P - X, axis=1)))


def constructionSignedDistance(construction, X, k):
    """Distance of the points X (mm) of leaflet k from the construction's
    mid-surface, positive on its aortic side."""
    local = X @ rotation(k)
    u, v = construction.nearestParameters(local)
    d = local - construction.point(u, v)
    return np.sign(np.einsum("ij,ij->i", d, construction.normal(u, v))) \
        * np.linalg.norm(d, axis=1)


def circumferentialDirections(construction, centre, normal, k):
    """Unit dS/du at the construction's point nearest each centre of
    leaflet k, projected onto the tangent plane of 'normal'; and the
    largest centre-to-construction distance (mm)."""
    R = rotation(k)
    local = centre @ R
    u, v = construction.nearestParameters(local)
    dist = np.linalg.norm(local - construction.point(u, v), axis=1)
    tangent = construction.tangents(u, v)[0] @ R.T   # back to leaflet k's frame
    tangent -= np.einsum("ij,ij->i", tangent, normal)[:, None] * normal
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    return tangent, float(dist.max())


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
    construction = LeafletConstruction()
    farthest = 0.0
    largestSnap = 0.0

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
        onAttach = curveNodes(groupEntity(1, "attachment%d" % k), local)
        onFree = curveNodes(groupEntity(1, "freeEdge%d" % k), local)
        if construction.coapt > 0:
            # the filling rounds the band's bend (0.06 to 0.13 mm, up to a
            # third of the gap): the nodes go onto the construction
            X, n, moved = snapToConstruction(construction, X, k, onAttach, onFree)
            largestSnap = max(largestSnap, moved)
        # orient the triangles' normals along n
        tn = np.cross(X[tris[:, 1]] - X[tris[:, 0]], X[tris[:, 2]] - X[tris[:, 0]])
        flip = np.einsum("ij,ij->i", tn, n[tris].mean(axis=1)) < 0
        tris[flip] = tris[flip][:, [0, 2, 1]]

        for i in range(layers + 1):
            allX.append(X + (i / layers - 0.5) * L_t * n)

        def node(level, j):
            return offset + level * nm + j

        # circumferential direction of each triangle: commissure to
        # commissure (dS/du of the construction), in the tangent plane
        centre = X[tris].mean(axis=1)
        normal = n[tris].mean(axis=1)
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        etheta, off = circumferentialDirections(construction, centre, normal, k)
        farthest = max(farthest, off)

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
    print("leafletLayers.py: mid-surface triangle centres lie within %.3g mm "
          "of the construction (fibre directions from it)" % farthest)
    if construction.coapt > 0:
        print("leafletLayers.py: coaptation band (coapt = %g mm): the mid-surface "
              "nodes moved onto the construction, by at most %.3g mm"
              % (construction.coapt, largestSnap))


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
