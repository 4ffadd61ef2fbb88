#!/usr/bin/python3
"""Valve metrics of a smoothedSolidRun result of the three leaflets.

    metrics.py <results dir> <leaflets.msh> <rootWall.stl> [options]

For every VTU file of <results dir>/solid.pvd (or only the last, --last):
  time, geometric orifice area (the part of the disk r < r_c, seen along the
  valve axis z, that no leaflet covers), largest displacement, largest von
  Mises stress and its 95th percentile over the elements (the largest sits
  in one element at the clamped attachment), the largest maximum principal
  (Cauchy) stress, the smallest signed gap
  between leaflets (negative: a node of one leaflet lies inside another
  leaflet, by that depth) and between the leaflets and the root wall
  (negative: a free leaflet node lies behind the wall), the number of free
  nodes behind the wall, and the contact area of each pair of leaflets
  (coaptation: nodes with a contact pressure whose nearest other leaflet is
  that pair's, half the sum of both sides' tributary areas).

Options:
  --r_c R          radius of the orifice disk in mm (default 9.10, the
                   paper's commissure radius)
  --log FILE       smoothedSolidRun log: stable step and sub-steps
  --wallTime FILE  a file holding the run's wall time in seconds
  --last           only the last output time
  --summary FILE   write the last time's values as 'name value' lines
  --table FILE     write the time history as a table (also printed)

Leaflet k is the connected part whose centroid lies nearest to the angle
120 (k - 1) degrees. The nodes of the 'attachment' group (fixed) are left
out of the wall gap: they lie on the wall by construction.
"""
import argparse
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components
from scipy.spatial import cKDTree


def boundary_faces(tets):
    """Boundary triangles of a tet mesh, oriented outwards."""
    local = [(1, 2, 3, 0), (0, 3, 2, 1), (0, 1, 3, 2), (0, 2, 1, 3)]
    faces, opposite = [], []
    for a, b, c, d in local:
        faces.append(tets[:, [a, b, c]])
        opposite.append(tets[:, d])
    faces = np.concatenate(faces)
    opposite = np.concatenate(opposite)
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    inverse = inverse.ravel()
    return faces[counts[inverse] == 1], opposite[counts[inverse] == 1]


def orient_out(x, faces, opposite):
    """Flip faces whose normal points towards the opposite tet node."""
    n = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    inward = np.einsum("ij,ij->i", n, x[opposite] - x[faces[:, 0]]) > 0
    faces = faces.copy()
    faces[inward] = faces[inward][:, [0, 2, 1]]
    return faces


def closest_on_triangles(p, a, b, c):
    """Closest points of triangles (a, b, c) to points p (row-wise; Ericson 5.1.5)."""
    ab, ac, ap = b - a, c - a, p - a
    d1 = np.einsum("ij,ij->i", ab, ap)
    d2 = np.einsum("ij,ij->i", ac, ap)
    bp = p - b
    d3 = np.einsum("ij,ij->i", ab, bp)
    d4 = np.einsum("ij,ij->i", ac, bp)
    cp = p - c
    d5 = np.einsum("ij,ij->i", ab, cp)
    d6 = np.einsum("ij,ij->i", ac, cp)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = 1.0 / (va + vb + vc)
        v = vb * denom
        w = vc * denom
        q = a + ab * v[:, None] + ac * w[:, None]
        # edges
        t_ab = d1 / (d1 - d3)
        t_ac = d2 / (d2 - d6)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
    m = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
    q[m] = a[m] + ab[m] * t_ab[m, None]
    m = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
    q[m] = a[m] + ac[m] * t_ac[m, None]
    m = (va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0)
    q[m] = b[m] + (c[m] - b[m]) * t_bc[m, None]
    # vertices
    m = (d1 <= 0) & (d2 <= 0)
    q[m] = a[m]
    m = (d3 >= 0) & (d4 <= d3)
    q[m] = b[m]
    m = (d6 >= 0) & (d5 <= d6)
    q[m] = c[m]
    return q


def signed_gap(points, x, tris, k=12):
    """Distance of each point to the surface (x, tris) and the signed gap
    along the normal of the closest triangle (positive on the side the
    triangle normal points to); the closest triangle's index."""
    a, b, c = x[tris[:, 0]], x[tris[:, 1]], x[tris[:, 2]]
    centroid = (a + b + c) / 3
    tree = cKDTree(centroid)
    k = min(k, len(tris))
    _, idx = tree.query(points, k=k)
    idx = idx.reshape(len(points), k)
    best = np.full(len(points), np.inf)
    gap = np.zeros(len(points))
    which = np.zeros(len(points), dtype=int)
    normal = np.cross(b - a, c - a)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    for j in range(k):
        t = idx[:, j]
        q = closest_on_triangles(points, a[t], b[t], c[t])
        d = np.linalg.norm(points - q, axis=1)
        better = d < best
        best[better] = d[better]
        gap[better] = np.einsum("ij,ij->i", points[better] - q[better], normal[t[better]])
        which[better] = t[better]
    return best, gap, which


def inside_tets(points, x, tets, k=40):
    """True where a point lies inside one of the tets (x, tets)."""
    cen = x[tets].mean(axis=1)
    tree = cKDTree(cen)
    k = min(k, len(tets))
    _, idx = tree.query(points, k=k)
    idx = idx.reshape(len(points), k)
    inside = np.zeros(len(points), dtype=bool)
    for j in range(k):
        t = tets[idx[:, j]]
        x0 = x[t[:, 0]]
        A = np.stack([x[t[:, 1]] - x0, x[t[:, 2]] - x0, x[t[:, 3]] - x0], axis=2)
        try:
            lam = np.linalg.solve(A, (points - x0)[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            continue
        w = np.column_stack([1 - lam.sum(axis=1), lam])
        inside |= np.all(w > 1e-9, axis=1)
    return inside


def orifice_area(x, faces, r_c, h=2e-5):
    """Area of the disk r < r_c (z projection) not covered by the triangles."""
    n = int(math.ceil(2 * r_c / h))
    g = (np.arange(n) + 0.5) * h - r_c
    gx, gy = np.meshgrid(g, g, indexing="ij")
    inDisk = gx**2 + gy**2 < r_c**2
    covered = np.zeros_like(inDisk)
    P = x[:, :2]
    for f in faces:
        a, b, c = P[f[0]], P[f[1]], P[f[2]]
        lo = np.minimum(np.minimum(a, b), c)
        hi = np.maximum(np.maximum(a, b), c)
        i0 = max(int((lo[0] + r_c) / h), 0)
        i1 = min(int((hi[0] + r_c) / h) + 1, n)
        j0 = max(int((lo[1] + r_c) / h), 0)
        j1 = min(int((hi[1] + r_c) / h) + 1, n)
        if i0 >= i1 or j0 >= j1:
            continue
        X = gx[i0:i1, j0:j1]
        Y = gy[i0:i1, j0:j1]
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(det) < 1e-30:
            continue
        l1 = ((X - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (Y - a[1])) / det
        l2 = ((b[0] - a[0]) * (Y - a[1]) - (X - a[0]) * (b[1] - a[1])) / det
        covered[i0:i1, j0:j1] |= (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
    return float(np.sum(inDisk & ~covered)) * h * h


def read_pvd(directory):
    pvd = os.path.join(directory, "solid.pvd")
    root = ET.parse(pvd).getroot()
    out = []
    for ds in root.iter("DataSet"):
        out.append((float(ds.get("timestep")), os.path.join(directory, ds.get("file"))))
    return out


def cell_array(m, name):
    return np.asarray(m.cell_data[name][0]).reshape(len(m.cells[0].data), -1)[:, 0]


class Valve:
    """Leaflet parts, attachment nodes and boundary faces of the mesh."""

    def __init__(self, first, leafletsMsh):
        tets = first.cells_dict["tetra"]
        nn = len(first.points)
        X = first.points - first.point_data["displacement"]
        self.X, self.tets = X, tets
        # parts: connected components of the tets through shared nodes
        rows = np.repeat(np.arange(len(tets)), 4)
        A = coo_matrix((np.ones(rows.size), (rows, tets.ravel())), shape=(len(tets), nn)).tocsr()
        _, label = connected_components(A @ A.T, directed=False)
        centroids = X[tets].mean(axis=1)
        nPart = label.max() + 1
        if nPart != 3:
            sys.exit("metrics.py: expected three leaflets, found %d parts" % nPart)
        angle = {}
        for p in range(nPart):
            c = centroids[label == p].mean(axis=0)
            angle[p] = math.degrees(math.atan2(c[1], c[0])) % 360
        # leaflet k is centred at 120 (k - 1) degrees
        order = sorted(range(nPart), key=lambda p: angle[p] if angle[p] < 300 else angle[p] - 360)
        self.leafletOfTet = np.zeros(len(tets), dtype=int)
        for k, p in enumerate(order):
            self.leafletOfTet[label == p] = k
        self.leafletOfNode = np.zeros(nn, dtype=int)
        self.leafletOfNode[tets.ravel()] = np.repeat(self.leafletOfTet, 4)
        faces, opposite = boundary_faces(tets)
        self.faces = orient_out(X, faces, opposite)
        self.faceLeaflet = self.leafletOfNode[self.faces[:, 0]]
        self.bnodes = np.unique(self.faces)
        # attachment nodes from the gmsh file, matched by position
        msh = meshio.read(leafletsMsh)
        names = {v[0]: k for k, v in msh.field_data.items() if v[1] == 2}
        att = set()
        for block, tags in zip(msh.cells, msh.cell_data["gmsh:physical"]):
            if block.type != "triangle":
                continue
            for tri, tag in zip(block.data, tags):
                if names.get(tag) == "attachment":
                    att.update(tri.tolist())
        attPts = msh.points[sorted(att)]
        d, idx = cKDTree(X).query(attPts)
        if d.max() > 1e-9:
            sys.exit("metrics.py: the attachment nodes of %s are not in the results" % leafletsMsh)
        self.fixed = np.zeros(nn, dtype=bool)
        self.fixed[idx] = True
        self.free = np.setdiff1d(self.bnodes, np.nonzero(self.fixed)[0])
        # smallest element height (reference), for the penetration tolerance
        self.hMin = min_height(X, tets)

    def tributary(self, x):
        area = np.zeros(len(x))
        f = self.faces
        A = 0.5 * np.linalg.norm(np.cross(x[f[:, 1]] - x[f[:, 0]], x[f[:, 2]] - x[f[:, 0]]), axis=1)
        for j in range(3):
            np.add.at(area, f[:, j], A / 3)
        return area


def min_height(X, tets):
    x0, x1, x2, x3 = (X[tets[:, i]] for i in range(4))
    vol = np.abs(np.einsum("ij,ij->i", x1 - x0, np.cross(x2 - x0, x3 - x0))) / 6
    largest = np.zeros(len(tets))
    for a, b, c in ((x1, x2, x3), (x0, x2, x3), (x0, x1, x3), (x0, x1, x2)):
        largest = np.maximum(largest, 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1))
    return float(np.min(3 * vol / largest))


def read_wall(path):
    w = meshio.read(path)
    tris = np.concatenate([b.data for b in w.cells if b.type == "triangle"])
    return w.points, tris


def frame_metrics(v, m, wallX, wallTris, r_c):
    x = m.points
    u = m.point_data["displacement"]
    out = {}
    out["orificeArea_mm2"] = orifice_area(x, v.faces, r_c) * 1e6
    out["maxDisplacement_mm"] = float(np.linalg.norm(u, axis=1).max()) * 1e3
    vm = cell_array(m, "vonMises")
    out["maxVonMises_kPa"] = float(vm.max()) / 1e3
    out["vonMises95_kPa"] = float(np.percentile(vm, 95)) / 1e3
    out["maxPrincipal_kPa"] = float(cell_array(m, "maxPrincipalStress").max()) / 1e3
    out["minJ"] = float(cell_array(m, "J").min())
    cp = np.asarray(m.point_data.get("contactPressure", np.zeros(len(x)))).reshape(len(x), -1)[:, 0]
    area = v.tributary(x)
    # leaflet-leaflet: each leaflet's boundary nodes against the others
    minGap = np.inf
    maxPen = 0.0
    pairArea = {(0, 1): 0.0, (1, 2): 0.0, (0, 2): 0.0}
    for i in range(3):
        nodes = v.bnodes[v.leafletOfNode[v.bnodes] == i]
        others = [j for j in range(3) if j != i]
        dist = np.full(len(nodes), np.inf)
        near = np.full(len(nodes), -1)
        for j in others:
            tris = v.faces[v.faceLeaflet == j]
            d, _, _ = signed_gap(x[nodes], x, tris)
            tj = v.tets[v.leafletOfTet == j]
            ins = inside_tets(x[nodes], x, tj)
            s = np.where(ins, -d, d)
            if ins.any():
                maxPen = max(maxPen, float(d[ins].max()))
            minGap = min(minGap, float(s.min()))
            closer = d < dist
            dist[closer] = d[closer]
            near[closer] = j
        touching = (cp[nodes] > 0) & (dist < v.hMin)
        for j in others:
            key = (min(i, j), max(i, j))
            pairArea[key] += 0.5 * float(area[nodes[touching & (near == j)]].sum())
    out["minLeafletGap_mm"] = minGap * 1e3
    out["maxLeafletPenetration_mm"] = maxPen * 1e3
    for (i, j), a in sorted(pairArea.items()):
        out["contactArea%d%d_mm2" % (i + 1, j + 1)] = a * 1e6
    # leaflet-wall: free boundary nodes (the attachment lies on the wall)
    d, g, _ = signed_gap(x[v.free], wallX, wallTris)
    # far from the wall the sign of the closest triangle means nothing (the
    # open ends of the wall surface): count only nodes within 1 mm
    g = np.where(d < 1e-3, g, d)
    out["minWallGap_mm"] = float(g.min()) * 1e3
    out["nodesBehindWall"] = int(np.sum(g < 0))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("results")
    ap.add_argument("leaflets")
    ap.add_argument("wall")
    ap.add_argument("--r_c", type=float, default=9.10)
    ap.add_argument("--log")
    ap.add_argument("--wallTime")
    ap.add_argument("--last", action="store_true")
    ap.add_argument("--summary")
    ap.add_argument("--table")
    a = ap.parse_args()

    frames = read_pvd(a.results)
    if not frames:
        sys.exit("metrics.py: no output in %s" % a.results)
    if a.last:
        frames = [frames[0], frames[-1]]
    first = meshio.read(frames[0][1])
    v = Valve(first, a.leaflets)
    wallX, wallTris = read_wall(a.wall)
    r_c = a.r_c * 1e-3

    rows = []
    for t, f in frames:
        m = first if f == frames[0][1] else meshio.read(f)
        r = frame_metrics(v, m, wallX, wallTris, r_c)
        r = {"time_ms": t * 1e3, **r}
        rows.append(r)
    keys = list(rows[0].keys())
    lines = ["# " + " ".join(keys)]
    for r in rows:
        lines.append(" ".join("%.6g" % r[k] for k in keys))
    text = "\n".join(lines) + "\n"
    print(text, end="")
    if a.table:
        with open(a.table, "w") as fh:
            fh.write(text)

    last = dict(rows[-1])
    last["hMin_mm"] = v.hMin * 1e3
    last["initialOrificeArea_mm2"] = rows[0]["orificeArea_mm2"]
    last["initialMinWallGap_mm"] = rows[0]["minWallGap_mm"]
    last["initialNodesBehindWall"] = rows[0]["nodesBehindWall"]
    if a.log and os.path.exists(a.log):
        txt = open(a.log).read()
        mm = re.search(r"stable step dt = ([0-9.eE+-]+)", txt)
        if mm:
            last["initialStableStep_s"] = float(mm.group(1))
        steps = re.findall(r"sub-step ([0-9.eE+-]+) \.\. ([0-9.eE+-]+) s", txt)
        if steps:
            last["smallestSubStep_s"] = min(float(s[0]) for s in steps)
            last["largestSubStep_s"] = max(float(s[1]) for s in steps)
        mm = re.search(r"after (\d+) sub-steps", txt)
        if mm:
            last["subSteps"] = int(mm.group(1))
        mm = re.findall(r"kinetic energy ([0-9.eE+-]+)", txt)
        if mm:
            last["finalKineticEnergy_J"] = float(mm[-1])
    if a.wallTime and os.path.exists(a.wallTime):
        last["wallTime_s"] = float(open(a.wallTime).read().split()[0])
    print("summary (last time):")
    for k, val in last.items():
        print("  %-26s %.6g" % (k, val))
    if a.summary:
        with open(a.summary, "w") as fh:
            for k, val in last.items():
                fh.write("%s %.9g\n" % (k, val))


if __name__ == "__main__":
    main()
