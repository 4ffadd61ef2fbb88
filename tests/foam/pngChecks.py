"""PNG checks shared by tests/foam/valvePictures and aorticValveShort:
is a picture non-trivial inside each of its data axes? (The measures and
thresholds are described in tests/foam/valvePictures.)"""
import os

import matplotlib.image as mpimg
import numpy as np


def measure(png, box):
    """(colours, chromatic share, std) inside box: see the docstring."""
    img = mpimg.imread(png)[..., :3].astype(float)
    x0, y0, x1, y1 = box
    a = img[y0 + 3:y1 - 3, x0 + 3:x1 - 3]
    chroma = a.max(axis=2) - a.min(axis=2) > 0.08
    jump = np.zeros(a.shape[:2])
    for axis in (0, 1):
        d = np.abs(np.diff(a, axis=axis)).max(axis=2)
        pad = [(0, 0), (0, 0)]
        pad[axis] = (1, 0)
        jump = np.maximum(jump, np.pad(d, pad))
        pad[axis] = (0, 1)
        jump = np.maximum(jump, np.pad(d, pad))
    smooth = chroma & (jump <= 0.1)
    q = np.minimum((a[smooth] * 16).astype(int), 15)
    counts = np.bincount(q[:, 0] * 256 + q[:, 1] * 16 + q[:, 2], minlength=4096)
    return int(np.sum(counts >= 20)), float(chroma.mean()), float(a.std())


CHECKS = {  # kind: minimum (colours, chromatic share, std)
    "colourMap": (10, 0.0, 0.0),
    "orifice": (3, 0.0, 0.10),
    "metrics": (0, 0.002, 0.02),
}
KIND = {"valvePlane_U.png": "colourMap", "valvePlane_p.png": "colourMap",
        "leaflet1_displacement.png": "colourMap", "orifice.png": "orifice",
        "metrics.png": "metrics"}


def check(label, png, boxes, kind):
    """True if every panel passes the kind's thresholds; prints each."""
    cmin, fmin, smin = CHECKS[kind]
    if not os.path.exists(png) or os.path.getsize(png) == 0 or not boxes:
        print("  %-36s missing or no panels  FAIL" % label)
        return False
    ok = True
    for i, b in enumerate(boxes):
        n, f, s = measure(png, b)
        good = n >= cmin and f >= fmin and s >= smin
        ok &= good
        print("  %-36s panel %d: colours %3d (>= %d), chromatic %.4f (>= %.3f), "
              "std %.3f (>= %.2f)  %s"
              % (label, i + 1, n, cmin, f, fmin, s, smin, "pass" if good else "FAIL"))
    return ok
