#!/usr/bin/python3
"""Checks of the aortic valve meshes written by makeValveMeshes.

    valveMeshCheck.py quality leaflets.msh
        tetrahedra, nodes, smallest height, largest aspect ratio, smallest
        volume of the leaflets, smallest distance between the leaflets'
        nodes; fails if any volume is not positive
    valveMeshCheck.py layers leaflets.msh [-setnumber name value ...]
        exactly two tetrahedron layers through the thickness everywhere:
        every node lies on the CAD mid-surface of its leaflet or at L_t/2 on
        either side of it, every tetrahedron has nodes on two neighbouring
        of these three levels, the faces ventricular<k>/aortic<k> lie on the
        ventricular/aortic level, and each leaflet has as many nodes on each
        level and as many tetrahedra in each layer
    valveMeshCheck.py volumes fluid.msh leaflets.msh [-setnumber name value ...]
        the fluid domain's volume against the volume integral of the wall
        formula of valveParameters.geo (the OpenCASCADE mass of the CAD
        volumes is printed beside it), each leaflet's volume against L_t
        times the OpenCASCADE area of its CAD mid-surface
        (aorticLeaflets.geo), within 1 %; and the distance of the leaflets'
        attachment nodes from the root wall
    valveMeshCheck.py coaptation leaflets.msh [-setnumber name value ...]
        the coaptation bands (parameter coapt): the area of each leaflet's
        ventricular face that faces a neighbour's ventricular face within
        gap + 0.1 mm, against the band's area from its definition
        (valveParameters.geo: a vertical strip of height coapt (1 - s) over
        the coaptation line), within 15 %; with coapt = 0 the facing area
        must stay below 2 mm2 per pair

The meshes are in metres, the geometry in mm; -setnumber arguments must be
the ones the meshes were made with. Exit status 1 on a failed check, with
the measured value, the reference and the tolerance printed.
"""
import os
import sys

import numpy as np

import meshio
import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
MM = 1e3  # m -> mm


def fail(message):
    sys.stderr.write("valveMeshCheck.py: %s\n" % message)
    sys.exit(1)


def readMesh(fileName):
    if not os.path.isfile(fileName):
        fail("cannot open mesh file '%s'" % fileName)
    try:
        return meshio.read(fileName)
    except Exception as ex:
        fail("cannot read '%s': %s" % (fileName, ex))


def physicalCells(mesh, cellType):
    """cells of one type and their physical tags"""
    cells, tags = [], []
    for block, phys in zip(mesh.cells, mesh.cell_data["gmsh:physical"]):
        if block.type == cellType:
            cells.append(block.data)
            tags.append(phys)
    if not cells:
        return np.zeros((0, 4 if cellType == "tetra" else 3), dtype=int), np.zeros(0, dtype=int)
    return np.vstack(cells), np.concatenate(tags)


def physicalTag(mesh, name):
    if name not in mesh.field_data:
        fail("the mesh has no physical group '%s' (has: %s)"
             % (name, ", ".join(sorted(mesh.field_data))))
    return int(mesh.field_data[name][0])


def tetVolumes(X, T):
    a, b, c = (X[T[:, i]] - X[T[:, 0]] for i in (1, 2, 3))
    return np.einsum("ij,ij->i", np.cross(a, b), c) / 6.0


def quality(leafletFile):
    m = readMesh(leafletFile)
    X = m.points * MM
    T, _ = physicalCells(m, "tetra")
    vol = tetVolumes(X, T)
    faces = ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))
    area = np.stack([0.5 * np.linalg.norm(np.cross(X[T[:, f[1]]] - X[T[:, f[0]]],
                                                     X[T[:, f[2]]] - X[T[:, f[0]]]), axis=1)
                     for f in faces], axis=1)
    height = 3.0 * np.abs(vol) / area.max(axis=1)
    edges = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))
    longest = np.max(np.stack([np.linalg.norm(X[T[:, i]] - X[T[:, j]], axis=1)
                               for i, j in edges], axis=1), axis=1)
    aspect = longest / height
    used = np.unique(T)
    print("leaflets %s:" % leafletFile)
    print("  tetrahedra          %d" % len(T))
    print("  nodes               %d" % len(used))
    print("  smallest height     %.4g mm  (3 V / largest face)" % height.min())
    print("  largest aspect      %.4g  (longest edge / smallest height), median %.3g"
          % (aspect.max(), np.median(aspect)))
    print("  smallest volume     %.4g mm3, largest %.4g mm3" % (vol.min(), vol.max()))
    # clearance between the leaflets (closed valve: about the parameter gap)
    _, part = physicalCells(m, "tetra")
    nodes = [np.unique(T[part == physicalTag(m, "leaflet%d" % k)]) for k in (1, 2, 3)]
    for a, b in ((0, 1), (1, 2), (0, 2)):
        A, B = X[nodes[a]], X[nodes[b]]
        closest = np.inf
        for i in range(0, len(A), 256):
            d2 = np.sum((A[i:i + 256, None, :] - B[None, :, :]) ** 2, axis=2)
            closest = min(closest, float(np.sqrt(d2.min())))
        print("  leaflets %d-%d        smallest node distance %.4g mm" % (a + 1, b + 1, closest))
    nonPositive = int(np.sum(vol <= 0))
    if nonPositive:
        fail("%d tetrahedra of %s have non-positive volume" % (nonPositive, leafletFile))
    print("  all volumes positive: PASS")


def startGmsh(gmshArgs):
    gmsh.initialize(["valveMeshCheck.py"] + gmshArgs)
    gmsh.option.setNumber("General.Terminal", 1)
    gmsh.option.setNumber("General.Verbosity", 2)


def groupEntities(dim, name):
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        if gmsh.model.getPhysicalName(d, tag) == name:
            return [int(e) for e in gmsh.model.getEntitiesForPhysicalGroup(d, tag)]
    fail("the geometry has no physical group %s" % name)


def signedDistance(surf, X):
    """Distance of the points X from the CAD surface, positive on its aortic
    side (the side its normals point to on the whole: +z)."""
    cp, _ = gmsh.model.getClosestPoint(2, surf, X.ravel())
    cp = cp.reshape(-1, 3)
    uv = gmsh.model.getParametrization(2, surf, cp.ravel())
    n = gmsh.model.getNormal(surf, uv).reshape(-1, 3)
    if np.sum(n[:, 2]) < 0:
        n = -n
    return np.einsum("ij,ij->i", X - cp, n), np.linalg.norm(X - cp, axis=1)


def layers(leafletFile, gmshArgs):
    m = readMesh(leafletFile)
    X = m.points * MM
    T, part = physicalCells(m, "tetra")
    tris, triTag = physicalCells(m, "triangle")
    startGmsh(gmshArgs)
    gmsh.open(os.path.join(HERE, "aorticLeaflets.geo"))
    L_t = gmsh.onelab.getNumber("valve/L_t")[0]
    # with a coaptation band the nodes lie on the construction, not on the
    # CAD filling (leafletLayers.py): measured against the construction
    construction = None
    if gmsh.onelab.getNumber("valve/coapt")[0] > 0:
        sys.path.insert(0, HERE)
        import leafletLayers
        construction = leafletLayers.LeafletConstruction()
    # CAD tolerance: the filling surface follows its free edge to ~0.02 mm
    # near the rounded centre; a third layer would put nodes L_t/6 off
    tol = 0.1 * L_t
    ok = True
    print("layers of %s (L_t = %g mm, tolerance %.3g mm; levels from the %s):"
          % (leafletFile, L_t, tol, "CAD mid-surface" if construction is None
             else "construction (coaptation band)"))
    for k in (1, 2, 3):
        (surf,) = groupEntities(2, "leaflet%d" % k)
        Tk = T[part == physicalTag(m, "leaflet%d" % k)]
        nodes = np.unique(Tk)
        if construction is None:
            s, _ = signedDistance(surf, X[nodes])
        else:
            s = leafletLayers.constructionSignedDistance(construction, X[nodes], k)
        level = np.rint(s / (0.5 * L_t)).astype(int)
        off = np.abs(s - 0.5 * L_t * level)
        bad = (off > tol) | (np.abs(level) > 1)
        levelOf = np.full(len(X), 99, dtype=int)
        levelOf[nodes] = np.where(bad, 99, level)
        tetLevels = np.sort(levelOf[Tk], axis=1)
        lo, hi = tetLevels[:, 0], tetLevels[:, 3]
        tetOk = (hi <= 1) & (hi - lo == 1)
        perLevel = [int(np.sum(levelOf[nodes] == l)) for l in (-1, 0, 1)]
        perLayer = [int(np.sum(tetOk & (lo == l))) for l in (-1, 0)]
        print("  leaflet%d: %d nodes, off every level: %d (largest miss %.3g mm); "
              "nodes on levels -L_t/2, 0, +L_t/2: %s; tetrahedra %d, in layers "
              "(ventricular, aortic) %s, spanning other than two neighbouring "
              "levels: %d" % (k, len(nodes), int(np.sum(bad)), off.max(), perLevel,
                                len(Tk), perLayer, int(np.sum(~tetOk))))
        if np.any(bad) or np.any(~tetOk) or perLevel[0] != perLevel[1] \
                or perLevel[1] != perLevel[2] or perLayer[0] != perLayer[1] \
                or perLevel[0] == 0:
            ok = False
        for name, want in (("ventricular%d" % k, -1), ("aortic%d" % k, 1)):
            f = tris[triTag == physicalTag(m, name)]
            wrong = int(np.sum(np.any(levelOf[f] != want, axis=1)))
            print("    %s: %d triangles, %d off the %s level" % (name, len(f), wrong, name[:-1]))
            if wrong or len(f) == 0:
                ok = False
    gmsh.finalize()
    if not ok:
        fail("%s does not have exactly two layers through the thickness" % leafletFile)
    print("  two layers through the thickness everywhere: PASS")


def compare(what, measured, reference, tolerance):
    rel = abs(measured - reference) / reference
    verdict = "PASS" if rel <= tolerance else "FAIL"
    print("  %-22s measured %12.6g mm3  reference %12.6g mm3  difference %6.3f %% "
          "(tolerance %g %%)  %s" % (what, measured, reference, 100 * rel,
                                     100 * tolerance, verdict))
    return rel <= tolerance


def wallRadius(v, phi, z):
    """The root wall r(phi, z) of valveParameters.geo (phi from the nearest
    sinus centre, |phi| <= 60 deg, 0 <= z <= h_s)"""
    if z < v["h"]:
        rns = v["r_b"] + (v["r_c"] - v["r_b"]) * z / v["h"]
        phiW = np.arccos(1 - z / v["h"]) / 1.5
    else:
        rns = v["r_c"]
        phiW = np.pi / 3
    if z < v["h_sm"]:
        rs = v["r_b"] + (v["r_sm"] - v["r_b"]) * np.sin(0.5 * np.pi * z / v["h_sm"])
    else:
        rs = v["r_c"] + (v["r_sm"] - v["r_c"]) * np.cos(
            0.5 * np.pi * (z - v["h_sm"]) / (v["h_s"] - v["h_sm"]))
    w = np.where(np.abs(phi) < phiW,
                 np.cos(0.5 * np.pi * phi / max(phiW, 1e-300)) ** 2, 0.0)
    return rns + (rs - rns) * w


def fluidVolumeFormula(v):
    """Volume of the fluid domain from the wall formula: the root as
    int_0^h_s int r^2/2 dphi dz (trapezoidal rule, 2001 x 2001 points; its
    error is far below 0.01 %) plus the inlet and outlet cylinders"""
    phi = np.linspace(-np.pi / 3, np.pi / 3, 2001)
    z = np.linspace(0.0, v["h_s"], 2001)
    area = [3 * np.trapz(0.5 * wallRadius(v, phi, zz) ** 2, phi) for zz in z]
    root = np.trapz(area, z)
    return root + np.pi * v["r_b"] ** 2 * v["L_in"] + np.pi * v["r_c"] ** 2 * v["L_out"], root


def volumes(fluidFile, leafletFile, gmshArgs):
    tolerance = 0.01
    ok = True
    fl = readMesh(fluidFile)
    Tf, _ = physicalCells(fl, "tetra")
    fluidVolume = np.sum(np.abs(tetVolumes(fl.points * MM, Tf)))
    le = readMesh(leafletFile)
    Xl = le.points * MM
    Tl, part = physicalCells(le, "tetra")
    vl = tetVolumes(Xl, Tl)

    startGmsh(gmshArgs)
    gmsh.open(os.path.join(HERE, "aorticRoot.geo"))
    occFluid = sum(gmsh.model.occ.getMass(3, v) for v in groupEntities(3, "fluid"))
    value = {name: gmsh.onelab.getNumber("valve/" + name)[0]
             for name in ("L_t", "r_b", "r_c", "h", "r_sm", "h_sm", "h_s", "L_in", "L_out")}
    reference, rootVolume = fluidVolumeFormula(value)
    tris, triTag = physicalCells(le, "triangle")
    att = np.unique(tris[triTag == physicalTag(le, "attachment")])
    gmsh.clear()
    gmsh.open(os.path.join(HERE, "aorticLeaflets.geo"))
    L_t = value["L_t"]
    print("volumes: the fluid domain against the wall formula (root %.6g mm3 + inlet and "
          "outlet cylinders), the leaflets against L_t x the OpenCASCADE area of their "
          "CAD mid-surfaces:" % rootVolume)
    ok &= compare("fluid domain", fluidVolume, reference, tolerance)
    print("  (OpenCASCADE mass of the CAD fluid volumes: %.6g mm3, %+.3f %% from the "
          "formula; the mesh converges to the formula as it is refined, OCC's "
          "integration over the ruled spline faces of the root is this far off)"
          % (occFluid, 100 * (occFluid - reference) / reference))
    total, totalRef = 0.0, 0.0
    for k in (1, 2, 3):
        (surf,) = groupEntities(2, "leaflet%d" % k)
        ref = L_t * gmsh.model.occ.getMass(2, surf)
        meas = np.sum(vl[part == physicalTag(le, "leaflet%d" % k)])
        ok &= compare("leaflet%d (L_t x area)" % k, meas, ref, tolerance)
        total += meas
        totalRef += ref
    ok &= compare("leaflets", total, totalRef, tolerance)
    gmsh.finalize()
    # the attachment lies on the commissural wall, the cone r_ns(z) from r_b
    # at z = 0 to r_c at z = h (valveParameters.geo)
    z = Xl[att, 2]
    rns = value["r_b"] + (value["r_c"] - value["r_b"]) * z / value["h"]
    miss = np.abs(np.hypot(Xl[att, 0], Xl[att, 1]) - rns)
    print("  attachment nodes (%d): radial distance from the root wall r_ns(z): "
          "largest %.4g mm, mean %.4g mm (L_t/2 = %g mm)"
          % (len(att), miss.max(), miss.mean(), 0.5 * L_t))
    if not ok:
        fail("a volume differs from its reference by more than %g %%" % (100 * tolerance))


def bandArea(g, n=4001):
    """Area of one leaflet's band facing one neighbour (mm2): the vertical
    strip of height coapt (1 - s(y)) over the coaptation line's horizontal
    projection x = d_V + k_F sqrt(y^2 + eps_r^2), 0 <= y <= y_C, with
    s = (sqrt(y^2 + eps_r^2) - eps_r)/(sqrt(y_C^2 + eps_r^2) - eps_r)
    (valveParameters.geo, aorticLeaflets.geo); trapezoidal rule."""
    y = np.linspace(0.0, g["y_C"], n)
    rho = np.sqrt(y**2 + g["eps_r"]**2)
    s = (rho - g["eps_r"]) / (np.sqrt(g["y_C"]**2 + g["eps_r"]**2) - g["eps_r"])
    dl = np.sqrt(1.0 + (g["k_F"] * y / rho)**2)
    f = g["coapt"] * (1.0 - s) * dl
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(y)))


def coaptation(leafletFile, gmshArgs):
    startGmsh(gmshArgs)
    gmsh.open(os.path.join(HERE, "aorticLeaflets.geo"))
    g = {k: gmsh.onelab.getNumber("valve/" + k)[0]
         for k in ("coapt", "gap", "y_C", "eps_r", "k_F")}
    gmsh.finalize()
    m = readMesh(leafletFile)
    X = m.points * MM
    tris, triTag = physicalCells(m, "triangle")
    faces = {k: tris[triTag == physicalTag(m, "ventricular%d" % k)] for k in (1, 2, 3)}
    # points sampled on each face (barycentric grid, 15 per triangle)
    from scipy.spatial import cKDTree
    bary = np.array([(i, j, 4 - i - j) for i in range(5) for j in range(5 - i)], float) / 4
    trees = {k: cKDTree(np.einsum("pk,tkd->tpd", bary, X[faces[k]]).reshape(-1, 3))
             for k in faces}
    reach = g["gap"] + 0.1
    reference = bandArea(g)
    print("coaptation bands of %s (coapt = %g mm, gap = %g mm): facing area "
          "within gap + 0.1 mm" % (leafletFile, g["coapt"], g["gap"]))
    ok = True
    for a, b in ((1, 2), (2, 3), (3, 1)):
        total = 0.0
        for k, other in ((a, b), (b, a)):
            T = X[faces[k]]
            area = 0.5 * np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]), axis=1)
            d, _ = trees[other].query(T.mean(axis=1))
            total += float(area[d < reach].sum())
        measured = 0.5 * total  # per leaflet of the pair
        if g["coapt"] > 0:
            rel = abs(measured - reference) / reference
            good = rel <= 0.15
            print("  leaflets %d-%d: %.3g mm2 per leaflet, band %.3g mm2, difference "
                  "%.1f %% (tolerance 15 %%)  %s" % (a, b, measured, reference,
                                                    100 * rel, "PASS" if good else "FAIL"))
        else:
            good = measured < 2.0
            print("  leaflets %d-%d: %.3g mm2 per leaflet (no band: below 2 mm2)  %s"
                  % (a, b, measured, "PASS" if good else "FAIL"))
        ok = ok and good
    if not ok:
        fail("the leaflets' facing areas do not match their coaptation bands")
    print("  coaptation bands: PASS")


def main(argv):
    if len(argv) < 3:
        fail("usage: valveMeshCheck.py quality|layers|volumes|coaptation <files> [-setnumber name value ...]")
    what = argv[1]
    files = [a for a in argv[2:4] if a.endswith(".msh")]
    rest = argv[2 + len(files):]
    if what == "quality" and len(files) == 1:
        quality(files[0])
    elif what == "layers" and len(files) == 1:
        layers(files[0], rest)
    elif what == "volumes" and len(files) == 2:
        volumes(files[0], files[1], rest)
    elif what == "coaptation" and len(files) == 1:
        coaptation(files[0], rest)
    else:
        fail("usage: valveMeshCheck.py quality leaflets.msh | layers leaflets.msh "
             "[-setnumber ...] | volumes fluid.msh leaflets.msh [-setnumber ...] | "
             "coaptation leaflets.msh [-setnumber ...]")


if __name__ == "__main__":
    main(sys.argv)
