#!/usr/bin/python3
"""Pictures of an aortic valve run (isfemFoam with the three leaflets), after
Yao et al. (Comput Mech 2012), Figs. 5 and 7. No ParaView: numpy and
matplotlib only (Debian's /usr/bin/python3; the VTK files are read by the
small reader below, XML .vtp/.vtu inline ascii/binary, zlib or not, and
legacy .vtk ascii/binary).

Run from the case directory after a run:

    ./valvePictures.py                          (every picture, default times)
    ./valvePictures.py --times 0.005,0.01,0.02 -o pictures

Writes PNGs into ./pictures (or -o DIR) and prints the files written:

  valvePlane_U.png   the plane through the valve axis and a commissure,
                     coloured by |U| (m/s) with the in-plane velocity as
                     arrows, one panel per time (the paper's Fig. 5);
  valvePlane_p.png   the same plane coloured by pressure in mmHg
                     (p_mmHg = p rho / 133.322 with OpenFOAM's kinematic p,
                     rho = --rho, default 1000 kg/m3);
                     on both, the leaflets' cut (their surface triangles,
                     from the solid's VTU of the same time, cut by the
                     plane) in black;
  leaflet1_displacement.png
                     leaflet 1 in 3D, seen from the valve centre and from
                     above, coloured by |displacement| (mm), one panel per
                     time, one colour scale (the paper's Fig. 7);
  orifice.png        the leaflets projected along the valve axis at an open
                     and a closed time, filled, with the annulus circle
                     (r = annulusRadius): the open area is the white part
                     inside the circle (its area, rasterised at 0.05 mm, in
                     the title);
  metrics.png        every column of postProcessing/valveMetrics/<startTime>/
                     valveMetrics.dat against time: the files of a run and
                     its restarts joined, a restart's rows replacing the
                     earlier ones from its first time on (skipped with a
                     message when there is none).

What it reads (paths relative to the case, options to change them):

  postProcessing/valvePlane/<time>/valvePlane.vtp
                     the plane, written by the function object of
                     system/valvePlane (#include "valvePlane" inside the
                     controlDict's functions; OpenFOAM v1912's vtk surface
                     writer: VTK XML polydata, U and p as point data);
  VTK/solid/solid.pvd and solid_<time>.vtu
                     the leaflets (tetrahedra, point data 'displacement';
                     the current positions are the points). The leaflets
                     are told apart as the connected parts of the tet mesh,
                     leaflet k the part whose reference centroid (points -
                     displacement) lies nearest to 120 (k - 1) degrees from
                     the valveFrame's leaflet1 direction about the axis;
  system/valvePlane  the plane (pointAndNormalDict) and the valve's frame
                     (the valveFrame sub-dictionary: origin, axis, leaflet1,
                     annulusRadius); without it the frame of
                     tutorials/resources/geometry: origin (0 0 0), axis
                     (0 0 1), leaflet 1 along +x, plane y = 0, r = 9.10 mm.

Times: --times picks written times (nearest within 1e-6 relative, else
skipped with a message); default: up to --count (6) spread evenly over the
times that have a plane (or, for the leaflets, a solid file). The orifice's
times: --orifice-times, else the times of the largest and (after it) the smallest open
area of the metrics file (a column whose name holds 'area' or 'orifice'),
else the first and last solid times; each taken at the nearest solid time.

After the fact: if a chosen time has an OpenFOAM time directory with U and
p but no plane (the run did not include valvePlane), the script runs
'postProcess -func valvePlane -time <times>' once in the case first. That
needs the OpenFOAM environment (postProcess on PATH), system/valvePlane in
the case, and a serial (reconstructed) case; --no-sample turns it off.
"""
import argparse
import base64
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PolyCollection  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

MMHG = 133.322  # Pa
LEAFLET_COLOURS = np.array([[0.85, 0.33, 0.10], [0.00, 0.45, 0.74], [0.47, 0.67, 0.19]])


def note(msg):
    print("valvePictures.py: " + msg, flush=True)


# ---------------------------------------------------------------------------
# VTK reading (XML inline ascii/binary, legacy ascii/binary)

_XML_TYPES = {
    "Float32": "<f4", "Float64": "<f8", "Int8": "<i1", "UInt8": "<u1",
    "Int16": "<i2", "UInt16": "<u2", "Int32": "<i4", "UInt32": "<u4",
    "Int64": "<i8", "UInt64": "<u8",
}


def _xml_array(el, header, compressed, big_endian):
    dtype = np.dtype(_XML_TYPES[el.get("type")])
    if big_endian:
        dtype = dtype.newbyteorder(">")
    fmt = el.get("format", "ascii")
    ncomp = int(el.get("NumberOfComponents", 1))
    text = (el.text or "").strip()
    if fmt == "ascii":
        a = np.array(text.split(), dtype=float).astype(dtype.newbyteorder("="))
    elif fmt == "binary":
        hdt = np.dtype(header).newbyteorder(">" if big_endian else "<")
        hs = hdt.itemsize
        if not compressed:
            raw = base64.b64decode(text)
            n = int(np.frombuffer(raw[:hs], hdt)[0])
            a = np.frombuffer(raw[hs:hs + n], dtype)
        else:
            # header: nBlocks, blockSize, lastBlockSize, compressed sizes
            # (base64 encoded on its own, then the blocks)
            first = base64.b64decode(text[:((3 * hs + 2) // 3) * 4])
            nb = int(np.frombuffer(first[:hs], hdt)[0])
            hlen = ((hs * (3 + nb) + 2) // 3) * 4
            head = np.frombuffer(base64.b64decode(text[:hlen]), hdt)
            data = base64.b64decode(text[hlen:])
            out, pos = [], 0
            for size in head[3:3 + nb]:
                out.append(zlib.decompress(data[pos:pos + int(size)]))
                pos += int(size)
            a = np.frombuffer(b"".join(out), dtype)
    else:
        raise ValueError("VTK format '%s' (appended data) is not supported" % fmt)
    a = np.asarray(a, dtype=dtype.newbyteorder("="))
    return a.reshape(-1, ncomp) if ncomp > 1 else a


def read_vtk_xml(path):
    root = ET.parse(path).getroot()
    header = _XML_TYPES[root.get("header_type", "UInt32")]
    compressed = root.get("compressor") is not None
    big = root.get("byte_order", "LittleEndian") == "BigEndian"
    piece = root.find(".//Piece")
    if piece is None:
        raise ValueError("%s: no Piece" % path)

    def arrays(tag):
        out = {}
        el = piece.find(tag)
        if el is not None:
            for da in el.findall("DataArray"):
                out[da.get("Name")] = _xml_array(da, header, compressed, big)
        return out

    pts = piece.find("Points/DataArray")
    points = _xml_array(pts, header, compressed, big).reshape(-1, 3).astype(float)
    cells = []  # list of (connectivity, offsets, types or None)
    for tag in ("Polys", "Cells"):
        c = arrays(tag)
        if "connectivity" in c:
            cells.append((c["connectivity"].astype(np.int64), c["offsets"].astype(np.int64),
                          c.get("types")))
    return {
        "points": points,
        "cells": cells,
        "point_data": arrays("PointData"),
        "cell_data": arrays("CellData"),
    }


def read_vtk_legacy(path):
    with open(path, "rb") as f:
        data = f.read()
    lines = data.split(b"\n", 4)
    binary = lines[2].strip().upper() == b"BINARY"
    pos = len(b"\n".join(lines[:3])) + 1
    out = {"points": None, "cells": [], "point_data": {}, "cell_data": {}, "field_data": {}}
    target = out["field_data"]

    def token():
        nonlocal pos
        while pos < len(data) and data[pos:pos + 1].isspace():
            pos += 1
        start = pos
        while pos < len(data) and not data[pos:pos + 1].isspace():
            pos += 1
        return data[start:pos].decode(errors="replace")

    types = {"float": ">f4", "double": ">f8", "int": ">i4", "vtktypeint32": ">i4",
             "vtktypeint64": ">i8", "long": ">i8", "unsigned_char": ">u1"}

    def values(n, typ):
        nonlocal pos
        if not binary:
            return np.array([float(token()) for _ in range(n)])
        pos += 1  # the newline after the keyword line
        dt = np.dtype(types[typ.lower()])
        a = np.frombuffer(data[pos:pos + n * dt.itemsize], dt)
        pos += n * dt.itemsize
        return a.astype(dt.newbyteorder("="))

    while True:
        key = token().upper()
        if not key:
            break
        if key == "DATASET":
            token()
        elif key == "POINTS":
            n, typ = int(token()), token()
            out["points"] = values(3 * n, typ).astype(float).reshape(-1, 3)
        elif key in ("POLYGONS", "CELLS", "TRIANGLE_STRIPS", "LINES", "VERTICES"):
            n, size = int(token()), int(token())
            nl = data.find(b"\n", pos)
            if key in ("POLYGONS", "CELLS") and data[nl + 1:nl + 8].upper() == b"OFFSETS":
                token()  # VTK 5.1 layout: offsets (n + 1), then connectivity
                off = values(n, token()).astype(np.int64)
                token()
                conn = values(size, token()).astype(np.int64)
                out["cells"].append((conn, off[1:], None))
                continue
            raw = values(size, "int").astype(np.int64)
            if key in ("POLYGONS", "CELLS"):
                conn, off, i = [], [], 0
                for _ in range(n):
                    k = raw[i]
                    conn.extend(raw[i + 1:i + 1 + k])
                    off.append(len(conn))
                    i += k + 1
                out["cells"].append((np.array(conn, np.int64), np.array(off, np.int64), None))
        elif key == "CELL_TYPES":
            n = int(token())
            t = values(n, "int").astype(np.int64)
            if out["cells"]:
                c = out["cells"][-1]
                out["cells"][-1] = (c[0], c[1], t)
        elif key in ("POINT_DATA", "CELL_DATA"):
            token()
            target = out["point_data" if key == "POINT_DATA" else "cell_data"]
        elif key == "FIELD":
            token()
            for _ in range(int(token())):
                name, nc, nt, typ = token(), int(token()), int(token()), token()
                a = values(nc * nt, typ).astype(float)
                target[name] = a.reshape(nt, nc) if nc > 1 else a
        elif key in ("SCALARS", "VECTORS", "NORMALS"):
            name, typ = token(), token()
            nc = 3 if key != "SCALARS" else 1
            if key == "SCALARS":
                save = pos
                maybe = token()
                if maybe.isdigit():
                    nc = int(maybe)
                else:
                    pos = save
                save = pos
                if token().upper() == "LOOKUP_TABLE":
                    token()
                else:
                    pos = save
            nt = len(out["points"]) if target is out["point_data"] else \
                sum(len(c[1]) for c in out["cells"])
            a = values(nc * nt, typ).astype(float)
            target[name] = a.reshape(nt, nc) if nc > 1 else a
        elif key == "METADATA":
            # skip to the blank line that ends it
            end = data.find(b"\n\n", pos)
            pos = len(data) if end < 0 else end + 2
        # anything else (a stray token) is skipped
    return out


def read_vtk(path):
    with open(path, "rb") as f:
        start = f.read(64)
    if start.lstrip().startswith(b"<"):
        return read_vtk_xml(path)
    if start.startswith(b"# vtk DataFile"):
        return read_vtk_legacy(path)
    raise ValueError("%s is not a VTK file" % path)


def triangles_of(cells):
    """Triangles (fan) of every polygon of a polydata's cells."""
    tris, owner, base = [], [], 0
    for conn, off, _ in cells:
        start = np.concatenate([[0], off[:-1]])
        size = off - start
        for k in np.unique(size):
            if k < 3:
                continue
            idx = np.nonzero(size == k)[0]
            s = start[idx]
            for j in range(1, k - 1):
                tris.append(np.column_stack([conn[s], conn[s + j], conn[s + j + 1]]))
                owner.append(idx + base)
        base += len(off)
    if not tris:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    return np.concatenate(tris), np.concatenate(owner)


def tets_of(cells):
    for conn, off, types in cells:
        start = np.concatenate([[0], off[:-1]])
        keep = (off - start) == 4
        if types is not None:
            keep &= np.asarray(types) == 10
        if np.any(keep):
            return conn[start[keep][:, None] + np.arange(4)]
    return np.zeros((0, 4), np.int64)


# ---------------------------------------------------------------------------
# The case: frame, plane and solid files, metrics

def _vector(text):
    return np.array([float(v) for v in text.split()])


def read_frame(case, args):
    """The valve frame and the plane, in metres, from system/valvePlane
    (valveFrame, pointAndNormalDict) and the options."""
    frame = {
        "origin": np.zeros(3), "axis": np.array([0.0, 0.0, 1.0]),
        "leaflet1": np.array([1.0, 0.0, 0.0]), "annulusRadius": 9.10e-3,
        "point": np.zeros(3), "normal": np.array([0.0, 1.0, 0.0]),
    }
    path = os.path.join(case, "system", args.plane_name)
    if os.path.exists(path):
        text = re.sub(r"//[^\n]*", "", open(path).read())
        text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
        for key in ("origin", "axis", "leaflet1", "point", "normal"):
            m = re.search(r"\b%s\s+\(([^)]*)\)\s*;" % key, text)
            if m:
                frame[key] = _vector(m.group(1))
        m = re.search(r"\bannulusRadius\s+([-+.eE0-9]+)\s*;", text)
        if m:
            frame["annulusRadius"] = float(m.group(1))
    for key in ("origin", "axis", "leaflet1", "normal"):
        v = getattr(args, key)
        if v:
            frame[key] = _vector(v.replace(",", " "))
    if args.annulus_radius:
        frame["annulusRadius"] = args.annulus_radius * 1e-3
    a = frame["axis"] / np.linalg.norm(frame["axis"])
    e1 = frame["leaflet1"] - (frame["leaflet1"] @ a) * a
    e1 /= np.linalg.norm(e1)
    frame["axis"], frame["e1"], frame["e2"] = a, e1, np.cross(a, e1)
    n = frame["normal"] / np.linalg.norm(frame["normal"])
    h = np.cross(n, a)  # the plane's horizontal direction
    if np.linalg.norm(h) < 1e-6:
        h = e1 - (e1 @ n) * n
    frame["normal"], frame["h"] = n, h / np.linalg.norm(h)
    return frame


def time_name_value(name):
    try:
        return float(name)
    except ValueError:
        return None


def plane_files(case, args):
    """{time: path} of the plane's VTK files."""
    out = {}
    for d in glob.glob(os.path.join(case, "postProcessing", args.plane_name, "*")):
        t = time_name_value(os.path.basename(d))
        if t is None:
            continue
        for ext in ("vtp", "vtk", "vtu"):
            f = os.path.join(d, "%s.%s" % (args.surface_name, ext))
            if os.path.exists(f):
                out[t] = f
                break
    return out


def solid_files(case, args):
    """{time: path} of the solid's VTU files (solid.pvd, else solid_<time>.vtu)."""
    d = os.path.join(case, args.solid_dir)
    pvd = os.path.join(d, "solid.pvd")
    out = {}
    if os.path.exists(pvd):
        for ds in ET.parse(pvd).getroot().iter("DataSet"):
            f = os.path.join(d, ds.get("file"))
            if os.path.exists(f):
                out[float(ds.get("timestep"))] = f
    if not out:
        for f in glob.glob(os.path.join(d, "solid_*.vtu")):
            t = time_name_value(os.path.basename(f)[6:-4])
            if t is not None:
                out[t] = f
    return out


def foam_times(case):
    out = {}
    for d in glob.glob(os.path.join(case, "*")):
        t = time_name_value(os.path.basename(d))
        if t is not None and os.path.isdir(d) and os.path.exists(os.path.join(d, "U")) \
                and os.path.exists(os.path.join(d, "p")):
            out[t] = os.path.basename(d)
    return out


def nearest(t, times, tol=True):
    if not times:
        return None
    best = min(times, key=lambda s: abs(s - t))
    if tol and abs(best - t) > 1e-6 * max(abs(t), abs(best)) + 1e-12:
        return None
    return best


def spread(times, count):
    times = sorted(times)
    if len(times) <= count:
        return times
    idx = np.unique(np.round(np.linspace(0, len(times) - 1, count)).astype(int))
    return [times[i] for i in idx]


def read_metrics(path):
    """(names, table) of a whitespace table whose header is a '#' line: the
    last comment line before the data with as many names as the data has
    columns (else the last comment line)."""
    comments, rows = [], []
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s:
                continue
            if s.startswith("#"):
                if not rows:
                    comments.append(s.lstrip("#").split())
                continue
            try:
                rows.append([float(v) for v in s.split()])
            except ValueError:
                continue
    if not rows:
        return [], np.zeros((0, 0))
    width = min(len(r) for r in rows)
    table = np.array([r[:width] for r in rows])
    names = next((c for c in reversed(comments) if len(c) == width),
                 comments[-1] if comments else [])
    names = list(names[:width]) + ["column%d" % (i + 1) for i in range(len(names), width)]
    return names, table


def metrics_files(case, name="valveMetrics"):
    """The metrics files of a run and its restarts, oldest first.

    OpenFOAM's writeFile puts a run's file in postProcessing/<name>/<start
    time>/<name>.dat; a run restarted from the same time finds that file
    there and writes <name>_<its time>.dat beside it instead. The files are
    ordered by start directory, then the plain name before the suffixed one,
    then the suffix's time."""
    d = os.path.join(case, "postProcessing", name)
    found = []
    if os.path.isdir(d):
        for t in os.listdir(d):
            try:
                start = float(t)
            except ValueError:
                continue
            for path in glob.glob(os.path.join(d, t, name + "*.dat")):
                stem = os.path.basename(path)[:-len(".dat")]
                if stem == name:
                    found.append((start, 0, 0.0, path))
                    continue
                try:
                    found.append((start, 1, float(stem[len(name) + 1:]), path))
                except ValueError:
                    continue  # another function object's <name>Foo.dat
    return [f[-1] for f in sorted(found)]


def read_metrics_series(paths):
    """(names, table) of the metrics files of a run and its restarts, in
    the order of their start times: each file's rows replace the earlier
    files' rows from its own first time on (a restart from an earlier
    write repeats the times after it)."""
    names, table = [], np.zeros((0, 0))
    for path in paths:
        n, t = read_metrics(path)
        if not len(t):
            continue
        if len(table):
            width = min(table.shape[1], t.shape[1])
            table = np.vstack([table[table[:, 0] < t[0, 0], :width], t[:, :width]])
            names = names[:width]
        else:
            names, table = n, t
    return names, table


# ---------------------------------------------------------------------------
# The leaflets

def boundary_faces(tets):
    """Boundary triangles of a tet mesh."""
    local = [(1, 2, 3), (0, 3, 2), (0, 1, 3), (0, 2, 1)]
    faces = np.concatenate([tets[:, list(f)] for f in local])
    key = np.sort(faces, axis=1)
    _, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return faces[counts[inverse.ravel()] == 1]


def node_parts(n, tets):
    """Connected parts of the tet mesh: a label per node (label propagation)."""
    label = np.arange(n)
    while True:
        m = label[tets].min(axis=1)
        new = label.copy()
        np.minimum.at(new, tets.ravel(), np.repeat(m, 4))
        new = new[new]  # pointer jumping
        if np.array_equal(new, label):
            return label
        label = new


class Solid:
    def __init__(self, path, frame):
        vtk = read_vtk(path)
        self.x = vtk["points"]
        self.u = vtk["point_data"].get("displacement")
        if self.u is None:
            self.u = np.zeros_like(self.x)
        self.u = np.asarray(self.u, float).reshape(-1, 3)
        self.tets = tets_of(vtk["cells"])
        if not len(self.tets):
            raise ValueError("%s: no tetrahedra" % path)
        self.faces = boundary_faces(self.tets)
        X = self.x - self.u
        # leaflet of each node: its part's reference centroid's angle
        part = node_parts(len(self.x), self.tets)
        used = np.unique(self.tets)
        self.leaflet = np.zeros(len(self.x), int)
        for p in np.unique(part[used]):
            c = X[part == p].mean(axis=0) - frame["origin"]
            ang = math.degrees(math.atan2(c @ frame["e2"], c @ frame["e1"])) % 360
            self.leaflet[part == p] = int(((ang + 60) % 360) // 120) + 1
        self.face_leaflet = self.leaflet[self.faces[:, 0]]

    def local(self, frame, x=None):
        """Points in the valve frame (mm): along leaflet 1, e2, axis."""
        x = self.x if x is None else x
        d = x - frame["origin"]
        return 1e3 * np.column_stack([d @ frame["e1"], d @ frame["e2"], d @ frame["axis"]])

    def cut(self, frame):
        """The surface triangles cut by the plane: segments in plane
        coordinates (mm): (horizontal, along the axis)."""
        d = (self.x - frame["point"]) @ frame["normal"]
        f = self.faces
        s = d[f]
        pos = s > 0
        mixed = pos.any(axis=1) & ~pos.all(axis=1)
        segs = []
        for tri, sd in zip(f[mixed], s[mixed]):
            pts = []
            for a, b in ((0, 1), (1, 2), (2, 0)):
                if (sd[a] > 0) != (sd[b] > 0):
                    w = sd[a] / (sd[a] - sd[b])
                    pts.append(self.x[tri[a]] + w * (self.x[tri[b]] - self.x[tri[a]]))
            if len(pts) == 2:
                segs.append(pts)
        if not segs:
            return np.zeros((0, 2, 2))
        segs = np.array(segs) - frame["origin"]
        return 1e3 * np.stack([segs @ frame["h"], segs @ frame["axis"]], axis=-1)


def open_area(P, faces, r, h=0.05):
    """Area (mm2) of the disk of radius r not covered by the projected
    triangles P[faces] (mm), rasterised at h."""
    n = int(math.ceil(2 * r / h))
    g = (np.arange(n) + 0.5) * h - r
    gx, gy = np.meshgrid(g, g, indexing="ij")
    disk = gx**2 + gy**2 < r * r
    covered = np.zeros_like(disk)
    for f in faces:
        a, b, c = P[f[0]], P[f[1]], P[f[2]]
        lo = np.minimum(np.minimum(a, b), c)
        hi = np.maximum(np.maximum(a, b), c)
        i0, i1 = max(int((lo[0] + r) / h), 0), min(int((hi[0] + r) / h) + 1, n)
        j0, j1 = max(int((lo[1] + r) / h), 0), min(int((hi[1] + r) / h) + 1, n)
        if i0 >= i1 or j0 >= j1:
            continue
        det = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
        if abs(det) < 1e-14:
            continue
        X, Y = gx[i0:i1, j0:j1], gy[i0:i1, j0:j1]
        l1 = ((X - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (Y - a[1])) / det
        l2 = ((b[0] - a[0]) * (Y - a[1]) - (X - a[0]) * (b[1] - a[1])) / det
        covered[i0:i1, j0:j1] |= (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
    return float(np.sum(disk & ~covered)) * h * h


# ---------------------------------------------------------------------------
# Pictures

PANELS = {}  # picture -> its data axes' pixel boxes (--panels)


def save(fig, path, axes, args):
    """Save the figure at args.dpi; note where its data axes are, in pixels
    of the PNG (x0, y0, x1, y1 from the top left), for --panels."""
    fig.set_dpi(args.dpi)
    fig.canvas.draw()
    height = fig.bbox.height
    boxes = []
    for ax in axes:
        b = ax.get_window_extent()
        boxes.append([int(math.ceil(b.x0)), int(math.ceil(height - b.y1)),
                      int(math.floor(b.x1)), int(math.floor(height - b.y0))])
    fig.savefig(path, dpi=args.dpi)
    plt.close(fig)
    PANELS[os.path.basename(path)] = boxes


def grid(n, maxcols):
    cols = min(n, maxcols)
    return int(math.ceil(n / cols)), cols


def fmt_time(t):
    return "t = %.4g s" % t


class Plane:
    def __init__(self, path, frame):
        vtk = read_vtk(path)
        d = vtk["points"] - frame["origin"]
        self.xy = 1e3 * np.column_stack([d @ frame["h"], d @ frame["axis"]])
        self.tris, owner = triangles_of(vtk["cells"])
        self.fields = {}
        self.on_points = {}
        for name in ("U", "p"):
            if name in vtk["point_data"]:
                self.fields[name] = np.asarray(vtk["point_data"][name], float)
                self.on_points[name] = True
            elif name in vtk["cell_data"]:
                self.fields[name] = np.asarray(vtk["cell_data"][name], float)[owner]
                self.on_points[name] = False
        self.frame = frame

    def scalar(self, name, rho):
        if name == "U":
            return np.linalg.norm(self.fields["U"].reshape(len(self.fields["U"]), -1), axis=1)
        return self.fields["p"].ravel() * rho / MMHG

    def in_plane_velocity(self):
        """(feet, in-plane velocity) of the arrows: at the points, or at the
        triangles' centroids for face values."""
        U = self.fields["U"].reshape(-1, 3)
        uv = np.column_stack([U @ self.frame["h"], U @ self.frame["axis"]])
        if self.on_points["U"]:
            return self.xy, uv
        return self.xy[self.tris].mean(axis=1), uv


def arrow_points(xy, x0, x1, z0, z1, n):
    """One point of xy per cell of an n-wide grid over the window: the one
    nearest to the cell's centre (the arrows' feet)."""
    h = (x1 - x0) / n
    inside = (xy[:, 0] >= x0) & (xy[:, 0] <= x1) & (xy[:, 1] >= z0) & (xy[:, 1] <= z1)
    idx = np.nonzero(inside)[0]
    if not len(idx):
        return idx
    i = np.minimum(((xy[idx, 0] - x0) / h).astype(int), n - 1)
    j = ((xy[idx, 1] - z0) / h).astype(int)
    cx, cz = x0 + (i + 0.5) * h, z0 + (j + 0.5) * h
    d = (xy[idx, 0] - cx) ** 2 + (xy[idx, 1] - cz) ** 2
    key = j * n + i
    order = np.lexsort((d, key))
    first = np.ones(len(order), bool)
    first[1:] = key[order][1:] != key[order][:-1]
    return idx[order[first]]


def plane_pictures(planes, solids, frame, args, outdir):
    """valvePlane_U.png and valvePlane_p.png; planes: [(t, Plane)]."""
    written = []
    window = None
    if args.zrange:
        window = [float(v) for v in args.zrange.split(",")]
    elif solids:
        z = np.concatenate([s.local(frame)[:, 2] for s in solids.values() if s is not None])
        window = [z.min() - 10.0, z.max() + 20.0]
    specs = [("U", "|U| (m/s)", "viridis", "valvePlane_U.png"),
             ("p", "p (mmHg, rho = %g kg/m3)" % args.rho, "coolwarm", "valvePlane_p.png")]
    for name, label, cmap, fname in specs:
        have = [(t, pl) for t, pl in planes if name in pl.fields]
        if not have:
            note("no field %s on the plane: %s not drawn" % (name, fname))
            continue
        vals = np.concatenate([pl.scalar(name, args.rho) for _, pl in have])
        vmin, vmax = float(np.min(vals)), float(np.max(vals))
        if vmax - vmin <= 1e-9 * max(abs(vmin), abs(vmax), 1e-30):
            # a uniform field: a range about its value
            pad = max(1e-3 * abs(vmin), 1e-9)
            vmin, vmax = vmin - pad, vmax + pad
        xy_all = np.concatenate([pl.xy for _, pl in have])
        x0, x1 = xy_all[:, 0].min(), xy_all[:, 0].max()
        z0, z1 = xy_all[:, 1].min(), xy_all[:, 1].max()
        if window:
            z0, z1 = max(z0, window[0]), min(z1, window[1])
        rows, cols = grid(len(have), args.columns)
        aspect = (z1 - z0) / max(x1 - x0, 1e-9)
        w = 2.4
        fig, axes = plt.subplots(rows, cols,
                                 figsize=(max(w * cols + 1.3, 6.0), w * aspect * rows + 1.0),
                                 squeeze=False, sharex=True, sharey=True,
                                 constrained_layout=True)
        # one arrow scale for every panel: the largest in-plane speed is
        # 1.2 arrow spacings long
        h_arrow = (x1 - x0) / 12
        speed = max(float(np.max(np.linalg.norm(pl.in_plane_velocity()[1], axis=1)))
                    for _, pl in have) if name == "U" else 0.0
        for k, (t, pl) in enumerate(have):
            ax = axes[k // cols][k % cols]
            tri = mtri.Triangulation(pl.xy[:, 0], pl.xy[:, 1], pl.tris)
            v = pl.scalar(name, args.rho)
            if pl.on_points[name]:
                im = ax.tripcolor(tri, v, shading="gouraud", cmap=cmap, vmin=vmin, vmax=vmax)
            else:
                im = ax.tripcolor(tri, facecolors=v, cmap=cmap, vmin=vmin, vmax=vmax)
            if name == "U" and not args.no_arrows:
                feet, uv = pl.in_plane_velocity()
                idx = arrow_points(feet, x0, x1, z0, z1, 12)
                if len(idx):
                    ax.quiver(feet[idx, 0], feet[idx, 1], uv[idx, 0], uv[idx, 1],
                              angles="xy", scale_units="xy",
                              scale=max(speed, 1e-30) / (1.2 * h_arrow), color="white",
                              edgecolor="k", linewidth=0.3, width=0.008)
            s = solids.get(t)
            if s is not None:
                segs = s.cut(frame)
                ax.add_collection(LineCollection(segs, colors="k", linewidths=1.2))
            ax.set_xlim(x0, x1)
            ax.set_ylim(z0, z1)
            ax.set_aspect("equal")
            ax.set_title(fmt_time(t) + ("" if s is not None else "\n(no leaflets)"), fontsize=9)
            ax.tick_params(labelsize=7)
        for k in range(len(have), rows * cols):
            axes[k // cols][k % cols].axis("off")
        fig.colorbar(im, ax=axes.ravel().tolist(), shrink=0.9, label=label)
        fig.supylabel("along the valve axis (mm)", fontsize=9)
        fig.supxlabel("(mm)  commissure on the left, leaflet 1 on the right", fontsize=9)
        fig.suptitle("plane through the valve axis and a commissure:\n%s%s"
                     % (label.split(" (")[0], ", arrows: in-plane velocity" if name == "U"
                        and not args.no_arrows else ""), fontsize=10)
        path = os.path.join(outdir, fname)
        save(fig, path, [axes[k // cols][k % cols] for k in range(len(have))], args)
        written.append(path)
    return written


def leaflet_picture(solids, frame, args, outdir):
    have = [(t, s) for t, s in sorted(solids.items()) if s is not None]
    if not have:
        return []
    umax = 0.0
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    parts = []
    for t, s in have:
        mask = s.face_leaflet == 1
        if not np.any(mask):
            note("no leaflet 1 in the solid at %s" % fmt_time(t))
            continue
        f = s.faces[mask]
        x = s.local(frame)
        um = 1e3 * np.linalg.norm(s.u, axis=1)
        c = um[f].mean(axis=1)
        umax = max(umax, float(um[np.unique(f)].max()))
        lo = np.minimum(lo, x[np.unique(f)].min(axis=0))
        hi = np.maximum(hi, x[np.unique(f)].max(axis=0))
        parts.append((t, x[f], c))
    if not parts:
        return []
    umax = umax if umax > 0 else 1.0
    norm = matplotlib.colors.Normalize(0.0, umax)
    cmap = plt.get_cmap("jet")
    rows, cols = grid(len(parts), min(args.columns, 3))
    fig = plt.figure(figsize=(3.6 * cols + 1.2, 3.6 * rows + 0.6))
    centre, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo)) * 1.02
    light = np.array([-0.6, 0.3, 0.75])
    light /= np.linalg.norm(light)
    panels = []
    for k, (t, tri, c) in enumerate(parts):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        panels.append(ax)
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1), 1e-30)[:, None]
        rgb = cmap(norm(c))[:, :3] * (0.55 + 0.45 * np.abs(n @ light))[:, None]
        ax.add_collection3d(Poly3DCollection(tri, facecolors=rgb, edgecolors="none"))
        for i, setlim in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
            setlim(centre[i] - half, centre[i] + half)
        ax.set_box_aspect((1, 1, 1), zoom=1.15)
        ax.view_init(elev=args.elev, azim=args.azim)
        ax.set_title(fmt_time(t), fontsize=9)
        ax.tick_params(labelsize=6)
        ax.set_xlabel("x1 (mm)", fontsize=7)
        ax.set_ylabel("x2 (mm)", fontsize=7)
        ax.set_zlabel("axis (mm)", fontsize=7)
    fig.subplots_adjust(left=0.02, right=0.86, bottom=0.04, top=0.9, wspace=0.1, hspace=0.32)
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, cax=fig.add_axes([0.89, 0.2, 0.02, 0.6]), label="|displacement| (mm)")
    fig.suptitle("leaflet 1, seen from the valve centre (x1: towards leaflet 1)", fontsize=10)
    path = os.path.join(outdir, "leaflet1_displacement.png")
    save(fig, path, panels, args)
    return [path]


def orifice_picture(states, frame, args, outdir):
    """states: [(label, t, Solid)]."""
    r = 1e3 * frame["annulusRadius"]
    fig, axes = plt.subplots(1, len(states), figsize=(4.2 * len(states), 4.6), squeeze=False)
    for ax, (label, t, s) in zip(axes[0], states):
        x = s.local(frame)
        f = s.faces
        order = np.argsort(x[f].mean(axis=1)[:, 2])
        colours = LEAFLET_COLOURS[(s.face_leaflet - 1) % 3]
        ax.add_collection(PolyCollection(x[f[order]][:, :, :2], facecolors=colours[order],
                                         edgecolors=colours[order], linewidths=0.2))
        phi = np.linspace(0, 2 * math.pi, 361)
        ax.plot(r * np.cos(phi), r * np.sin(phi), "k--", linewidth=1.0)
        area = open_area(x[:, :2], f, r)
        lim = 1.45 * r
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_aspect("equal")
        ax.set_xlabel("x1 (mm), towards leaflet 1", fontsize=8)
        ax.set_ylabel("x2 (mm)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.set_title("%s, %s\nopen area %.1f mm2 of %.1f (r = %.2f mm)"
                     % (label, fmt_time(t), area, math.pi * r * r, r), fontsize=9)
    fig.suptitle("orifice seen along the valve axis (from the aorta)", fontsize=10)
    fig.tight_layout()
    path = os.path.join(outdir, "orifice.png")
    save(fig, path, list(axes[0]), args)
    return [path]


def metrics_picture(names, table, outdir, args):
    cols = [i for i in range(1, len(names))]
    if not cols or len(table) == 0:
        return []
    rows, ncols = grid(len(cols), 3)
    fig, axes = plt.subplots(rows, ncols, figsize=(3.6 * ncols, 2.5 * rows), squeeze=False)
    tname = names[0]
    for k, i in enumerate(cols):
        ax = axes[k // ncols][k % ncols]
        ax.plot(table[:, 0], table[:, i], "-", linewidth=1.2, marker="." if len(table) < 60
                else None)
        m = re.match(r"^(.*?)\[(.*)\]$", names[i])
        ax.set_title(m.group(1) if m else names[i], fontsize=9)
        if m:
            ax.set_ylabel(m.group(2), fontsize=8)
        ax.set_xlabel(tname if "[" in tname else tname + " (s)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(alpha=0.3)
    for k in range(len(cols), rows * ncols):
        axes[k // ncols][k % ncols].axis("off")
    fig.tight_layout()
    path = os.path.join(outdir, "metrics.png")
    save(fig, path, [axes[k // ncols][k % ncols] for k in range(len(cols))], args)
    return [path]


# ---------------------------------------------------------------------------

def sample_plane(case, args, times):
    """postProcess -func <plane> on the OpenFOAM times without a plane."""
    if args.no_sample or not times:
        return False
    if not os.path.exists(os.path.join(case, "system", args.plane_name)):
        note("no system/%s: cannot sample the plane afterwards" % args.plane_name)
        return False
    exe = shutil.which("postProcess")
    if exe is None:
        note("postProcess not on PATH (source OpenFOAM's bashrc): plane not sampled")
        return False
    names = ",".join(times)
    note("sampling the plane afterwards: postProcess -func %s -time %s" % (args.plane_name, names))
    with open(os.path.join(case, "log.postProcess.valvePlane"), "w") as log:
        rc = subprocess.call([exe, "-func", args.plane_name, "-time", names], cwd=case,
                             stdout=log, stderr=subprocess.STDOUT)
    if rc != 0:
        note("postProcess failed (log.postProcess.valvePlane)")
    return rc == 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter,
                                epilog=__doc__.split("\n", 2)[2])
    p.add_argument("-o", "--output", default="pictures", help="output directory (pictures)")
    p.add_argument("-case", "--case", default=".", help="case directory (.)")
    p.add_argument("--times", help="comma-separated times (default: --count spread)")
    p.add_argument("--count", type=int, default=6, help="default number of times (6)")
    p.add_argument("--orifice-times", help="open,closed times of the orifice picture")
    p.add_argument("--plane-name", default="valvePlane",
                   help="function object (postProcessing/<name>, system/<name>)")
    p.add_argument("--surface-name", default="valvePlane", help="surface file name")
    p.add_argument("--solid-dir", default=os.path.join("VTK", "solid"),
                   help="solid VTU directory (VTK/solid)")
    p.add_argument("--metrics",
                   help="one metrics file (default: postProcessing/valveMetrics/"
                        "<startTime>/valveMetrics.dat of the run and its restarts, joined)")
    p.add_argument("--rho", type=float, default=1000.0, help="density for p (1000 kg/m3)")
    p.add_argument("--origin", help="valve origin 'x y z' (m), else system/valvePlane")
    p.add_argument("--axis", help="valve axis 'x y z'")
    p.add_argument("--leaflet1", help="direction of leaflet 1's centre 'x y z'")
    p.add_argument("--normal", help="plane normal 'x y z' (the plane holds the origin)")
    p.add_argument("--annulus-radius", type=float, help="annulus radius (mm)")
    p.add_argument("--zrange", help="'zmin,zmax' (mm along the axis) of the plane pictures")
    p.add_argument("--columns", type=int, default=6, help="panels per row (6)")
    p.add_argument("--elev", type=float, default=25.0, help="3D view elevation (25)")
    p.add_argument("--azim", type=float, default=180.0,
                   help="3D view azimuth (180: from the valve centre)")
    p.add_argument("--dpi", type=int, default=110)
    p.add_argument("--no-arrows", action="store_true", help="no velocity arrows")
    p.add_argument("--no-sample", action="store_true",
                   help="never run postProcess for missing planes")
    p.add_argument("--panels", metavar="FILE",
                   help="write each picture's panels (data axes) as pixel boxes, JSON "
                        "(for tests)")
    args = p.parse_args()

    case = args.case
    outdir = args.output if os.path.isabs(args.output) else os.path.join(case, args.output)
    os.makedirs(outdir, exist_ok=True)
    frame = read_frame(case, args)
    if args.normal:
        frame["point"] = frame["origin"]

    planes = plane_files(case, args)
    solids = solid_files(case, args)
    foam = foam_times(case)
    requested = None
    if args.times:
        requested = [float(v) for v in args.times.replace(" ", "").split(",") if v]

    # the plane afterwards: OpenFOAM times with U and p but no plane
    wanted = requested if requested is not None else sorted(set(foam) | set(planes))
    missing = [foam[nearest(t, foam)] for t in wanted
               if nearest(t, foam) is not None and nearest(t, planes) is None]
    if requested is None and planes:
        missing = []  # sampled during the run: take what is there
    if missing and sample_plane(case, args, missing):
        planes = plane_files(case, args)

    if requested is not None:
        ptimes, stimes = [], []
        for t in requested:
            tp, ts = nearest(t, planes), nearest(t, solids)
            if tp is None and ts is None:
                note("no plane and no solid at t = %g: skipped" % t)
            ptimes += [tp] if tp is not None else []
            stimes += [ts] if ts is not None else []
    else:
        ptimes = spread(planes, args.count)
        stimes = [nearest(t, solids) for t in ptimes if nearest(t, solids) is not None] \
            if ptimes else spread(solids, args.count)
        if not stimes:
            stimes = spread(solids, args.count)

    written = []
    solid_cache = {}

    def solid_at(t):
        if t not in solid_cache:
            try:
                solid_cache[t] = Solid(solids[t], frame)
            except (ValueError, OSError, ET.ParseError) as e:
                note("cannot read %s: %s" % (solids[t], e))
                solid_cache[t] = None
        return solid_cache[t]

    # 1. the plane
    if ptimes:
        pl = [(t, Plane(planes[t], frame)) for t in ptimes]
        sol = {}
        for t in ptimes:
            ts = nearest(t, solids)
            if ts is None:
                note("no solid file at t = %g: the plane without the leaflets' cut" % t)
            else:
                sol[t] = solid_at(ts)
        written += plane_pictures(pl, sol, frame, args, outdir)
    else:
        note("no plane files (postProcessing/%s/<time>/%s.vtp): plane pictures skipped"
             % (args.plane_name, args.surface_name))

    # 2. leaflet 1
    if stimes:
        written += leaflet_picture({t: solid_at(t) for t in stimes}, frame, args, outdir)
    else:
        note("no solid files (%s): leaflet pictures skipped" % os.path.join(case, args.solid_dir))

    # 4. metrics (read before the orifice: its times)
    if args.metrics:
        mpaths = [os.path.join(case, args.metrics)]
    else:
        mpaths = metrics_files(case)
    mpath = ", ".join(mpaths) if mpaths else os.path.join(
        case, "postProcessing", "valveMetrics", "<startTime>", "valveMetrics.dat")
    names, table = [], None
    if mpaths and all(os.path.exists(m) for m in mpaths):
        names, table = read_metrics_series(mpaths)
        if len(table):
            written += metrics_picture(names, table, outdir, args)
        else:
            note("%s has no data rows: metrics picture skipped" % mpath)
    else:
        note("no metrics file %s: metrics picture skipped" % mpath)

    # 3. the orifice
    if solids:
        chosen = None
        if args.orifice_times:
            chosen = [float(v) for v in args.orifice_times.split(",")][:2]
        elif table is not None and len(table):
            col = [i for i, n in enumerate(names)
                   if i and re.search("GOA|area|orifice", n, re.I)]
            if col:
                # the most open, and the most closed after it (the valve
                # starts closed)
                a = table[:, col[0]]
                i_open = int(np.argmax(a))
                i_closed = i_open + int(np.argmin(a[i_open:]))
                if i_closed == i_open:
                    i_closed = int(np.argmin(a))
                chosen = [table[i_open, 0], table[i_closed, 0]]
        if chosen is None:
            chosen = [min(solids), max(solids)]
        states = []
        for label, t in zip(("open", "closed"), chosen):
            ts = nearest(t, solids, tol=False)
            s = solid_at(ts)
            if s is not None:
                states.append((label, ts, s))
        if states:
            written += orifice_picture(states, frame, args, outdir)
    if args.panels:
        with open(args.panels, "w") as f:
            json.dump(PANELS, f, indent=1)
    for w in written:
        print(w)
    if not written:
        note("nothing written")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
