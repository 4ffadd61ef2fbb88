#!/usr/bin/python3
"""Picture of the leaflets' last written state of each phase (Debian's
matplotlib, numpy, meshio; no ParaView):

    pictures.py out.png [phase ...]   (default: opening closing openingPaper
                                       closingPaper, those that have results)

One row per phase: a view along the valve axis from the aorta (the
geometric orifice is the white part of the dashed disk r < r_c) and an
oblique view from the side. Each leaflet has its own colour, shaded by the
face's inclination; the root wall is left out.
"""
import math
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import meshio  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from metrics import boundary_faces, orient_out  # noqa: E402

R_C = 9.10  # mm
COLOURS = np.array([[0.85, 0.33, 0.10], [0.00, 0.45, 0.74], [0.47, 0.67, 0.19]])
TITLES = {
    "opening": "opening, 40 mmHg, fibre tissue",
    "closing": "closing, 80 mmHg, fibre tissue",
    "openingPaper": "opening, 40 mmHg, paper's Mooney-Rivlin",
    "closingPaper": "closing, 80 mmHg, paper's Mooney-Rivlin",
    "closingNoContact": "closing, 80 mmHg, fibre tissue, contact off",
}


def last_state(phase):
    pvd = "results.%s/solid.pvd" % phase
    if not os.path.exists(pvd):
        return None
    sets = list(ET.parse(pvd).getroot().iter("DataSet"))
    ds = sets[-1]
    return float(ds.get("timestep")), meshio.read(os.path.join("results." + phase, ds.get("file")))


def leaflet_of_face(x, tets, faces):
    """Leaflet index 0..2 of each face from its centroid's angle (leaflet k
    centred at 120 (k - 1) degrees in the reference configuration)."""
    c = x[faces].mean(axis=1)
    ang = np.degrees(np.arctan2(c[:, 1], c[:, 0])) % 360
    return (((ang + 60) % 360) // 120).astype(int)


def shade(faces, x, base):
    n = np.cross(x[faces[:, 1]] - x[faces[:, 0]], x[faces[:, 2]] - x[faces[:, 0]])
    n /= np.linalg.norm(n, axis=1)[:, None]
    light = np.array([0.3, -0.5, 0.8])
    light /= np.linalg.norm(light)
    k = 0.45 + 0.55 * np.abs(n @ light)
    return np.clip(base * k[:, None], 0, 1)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    phases = sys.argv[2:] or ["opening", "closing", "openingPaper", "closingPaper"]
    states = [(p, last_state(p)) for p in phases]
    states = [(p, s) for p, s in states if s is not None]
    if not states:
        sys.exit("pictures.py: no results of %s" % " ".join(phases))
    fig = plt.figure(figsize=(10, 4.6 * len(states)))
    for row, (phase, (t, m)) in enumerate(states):
        x = m.points * 1e3
        X = x - m.point_data["displacement"] * 1e3
        tets = m.cells_dict["tetra"]
        faces, opp = boundary_faces(tets)
        faces = orient_out(X, faces, opp)
        leaf = leaflet_of_face(X, tets, faces)
        colours = shade(faces, x, COLOURS[leaf])
        label = "%s\nt = %.1f ms" % (TITLES.get(phase, phase), t * 1e3)
        if os.path.exists("results.%s/stopped" % phase):
            label += " (last state before it stopped)"
        # top view (from the aorta, along -z): draw lower faces first
        ax = fig.add_subplot(len(states), 2, 2 * row + 1)
        order = np.argsort(x[faces].mean(axis=1)[:, 2])
        ax.add_collection(PolyCollection(x[faces[order]][:, :, :2], facecolors=colours[order],
                                         edgecolors="none"))
        phi = np.linspace(0, 2 * math.pi, 200)
        ax.plot(R_C * np.cos(phi), R_C * np.sin(phi), "k--", linewidth=0.8)
        ax.set_aspect("equal")
        ax.set_xlim(-14, 14)
        ax.set_ylim(-14, 14)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_title(label + "\nview along the axis, dashed: r = r_c", fontsize=9)
        # oblique view
        ax = fig.add_subplot(len(states), 2, 2 * row + 2, projection="3d")
        poly = Poly3DCollection(x[faces], facecolors=colours, edgecolors="none")
        ax.add_collection3d(poly)
        ax.set_xlim(-13, 13)
        ax.set_ylim(-13, 13)
        ax.set_zlim(-8, 18)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=25, azim=-60)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_zlabel("z (mm)")
        ax.set_title("oblique view (z: flow direction)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=72)
    print("pictures.py: wrote %s (%s)" % (out, ", ".join(p for p, _ in states)))


if __name__ == "__main__":
    main()
