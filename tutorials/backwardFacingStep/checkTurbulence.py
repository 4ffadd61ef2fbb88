#!/usr/bin/python3
"""The backward-facing step by two solvers on the same case: isfemFoam's
run against pimpleFoam's (README.md).

    checkTurbulence.py <case> <reference case> [--tol 0.02]

For each case, at its last write: the reattachment length x_r (where the
velocity of the cells along the lower wall behind the step turns from
backward to forward; m from the step), the pressure drop to the outlet
(the area-averaged kinematic pressure of the inlet, p = 0 at the outlet,
averaged over the last quarter of the run: a time mean for an unsteady
LES) and the eddy viscosity (largest nut/nu and its mean over the cells,
where a nut field is written). Passes ("PASS" on the last line) when x_r,
the inlet pressure and, where the reference has a model, the mean eddy
viscosity are within tol of the reference's, relative; the exit status
is then 0, 1 when one misses (2 when the cases cannot be read).
Needs numpy only; reads ascii fields.
"""
import argparse
import glob
import os
import re
import sys

import numpy as np


def foam_list(path):
    """The body and length of an OpenFOAM ascii list file."""
    text = re.sub(r"//.*", "", open(path).read())
    if "FoamFile" in text:
        text = text[text.index("}") + 1:]
    m = re.search(r"(\d+)\s*\(", text)
    return text[m.end():], int(m.group(1))


def mesh(case):
    body, n = foam_list(os.path.join(case, "constant/polyMesh/points"))
    points = np.array([[float(x) for x in s.split()]
                       for s in re.findall(r"\(([^()]*)\)", body)[:n]])
    body, n = foam_list(os.path.join(case, "constant/polyMesh/faces"))
    faces = [list(map(int, s.split()))
             for s in re.findall(r"\d+\(([^()]*)\)", body)[:n]]
    body, n = foam_list(os.path.join(case, "constant/polyMesh/owner"))
    owner = np.array(body.split(")")[0].split()[:n], dtype=int)
    boundary = open(os.path.join(case, "constant/polyMesh/boundary")).read()
    m = re.search(r"lowerWall\s*\{[^}]*nFaces\s+(\d+);[^}]*startFace\s+(\d+);",
                  boundary)
    n_faces, start = int(m.group(1)), int(m.group(2))
    return points, faces, owner, range(start, start + n_faces)


def internal_field(path):
    text = open(path).read()
    i = text.index("internalField")
    m = re.match(r"internalField\s+uniform\s+([^;]+);", text[i:])
    if m:
        return None
    m = re.search(r"nonuniform\s+List<(\w+)>\s*(\d+)\s*\(", text[i:])
    kind, n = m.group(1), int(m.group(2))
    body = text[i + m.end():]
    if kind == "vector":
        return np.array([[float(x) for x in s.split()]
                         for s in re.findall(r"\(([^()]*)\)", body)[:n]])
    return np.array(body.split(")")[0].split()[:n], dtype=float)


def last_time(case):
    times = [d for d in os.listdir(case)
             if re.fullmatch(r"[0-9.e+-]+", d) and float(d) > 0
             and os.path.isfile(os.path.join(case, d, "U"))]
    if not times:
        print("checkTurbulence.py: no time directory with U in " + case,
              file=sys.stderr)
        sys.exit(2)
    return max(times, key=float)


def reattachment(case, t):
    points, faces, owner, wall = mesh(case)
    U = internal_field(os.path.join(case, t, "U"))
    x, ux = [], []
    for f in wall:
        xf = points[faces[f]].mean(axis=0)[0]
        if xf > 0:                      # behind the step
            x.append(xf)
            ux.append(U[owner[f], 0])
    order = np.argsort(x)
    x, ux = np.array(x)[order], np.array(ux)[order]
    # the first backward-to-forward turn beyond the corner's own eddy
    for i in range(len(x) - 1):
        if x[i] > 0.01 and ux[i] < 0 <= ux[i + 1]:
            return x[i] + (x[i + 1] - x[i])*(-ux[i])/(ux[i + 1] - ux[i])
    return float("nan")


def inlet_pressure(case):
    rows = []
    for f in glob.glob(os.path.join(case, "postProcessing/inletPressure/*/"
                                    "surfaceFieldValue.dat")):
        rows += [list(map(float, line.split()[:2])) for line in open(f)
                 if line.strip() and not line.startswith("#")]
    if not rows:
        print("checkTurbulence.py: no postProcessing/inletPressure in "
              + case, file=sys.stderr)
        sys.exit(2)
    a = np.array(sorted(rows))
    last = a[a[:, 0] >= 0.75*a[-1, 0]]
    # time mean over the last quarter (steps of varying length)
    if len(last) > 1:
        return np.trapz(last[:, 1], last[:, 0])/(last[-1, 0] - last[0, 0])
    return last[-1, 1]


def viscosity(case):
    text = open(os.path.join(case, "constant/transportProperties")).read()
    return float(re.search(r"\bnu\s+([0-9.eE+-]+)\s*;", text).group(1))


def measure(case):
    t = last_time(case)
    out = {"t": float(t), "x_r": reattachment(case, t),
           "dp": inlet_pressure(case)}
    nut_path = os.path.join(case, t, "nut")
    nut = internal_field(nut_path) if os.path.isfile(nut_path) else None
    if nut is not None:
        nu = viscosity(case)
        out["nut_max"] = nut.max()/nu
        out["nut_mean"] = nut.mean()/nu
    return out


def main():
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    parser.add_argument("case")
    parser.add_argument("reference")
    parser.add_argument("--tol", type=float, default=0.02)
    opts = parser.parse_args()
    tol = opts.tol
    args = [opts.case, opts.reference]
    case, ref = measure(args[0]), measure(args[1])
    print("backward-facing step at t = %g s (reference: %s, t = %g s)"
          % (case["t"], args[1], ref["t"]))
    ok = True
    for key, what, unit in (("x_r", "reattachment length", "m"),
                            ("dp", "inlet pressure (the outlet's is 0)",
                             "m2/s2")):
        err = abs(case[key] - ref[key])/abs(ref[key])
        passed = err <= tol
        ok = ok and passed
        print("  %s: %.6g %s against %.6g, %.3g %% (tolerance %g %%) %s"
              % (what, case[key], unit, ref[key], 100*err, 100*tol,
                 "PASS" if passed else "FAIL"))
    if "nut_mean" in ref:
        # the reference has a model: the case's eddy viscosity too
        if "nut_mean" not in case:
            ok = False
            print("  eddy viscosity: none written, against a mean nut/nu of"
                  " %.4g FAIL" % ref["nut_mean"])
        else:
            err = abs(case["nut_mean"] - ref["nut_mean"])/ref["nut_mean"]
            passed = err <= tol
            ok = ok and passed
            print("  eddy viscosity, mean nut/nu over the cells: %.6g against"
                  " %.6g, %.3g %% (tolerance %g %%) %s"
                  % (case["nut_mean"], ref["nut_mean"], 100*err, 100*tol,
                     "PASS" if passed else "FAIL"))
    for c, name in ((case, args[0]), (ref, args[1])):
        if "nut_max" in c:
            print("  %s: eddy viscosity nut/nu largest %.4g, mean %.4g"
                  % (name, c["nut_max"], c["nut_mean"]))
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
