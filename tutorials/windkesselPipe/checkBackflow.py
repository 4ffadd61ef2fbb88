#!/usr/bin/env python3
"""The swirling pipe flow (./Allrun -swirl) with backflow at its outlet.

A steady flow Q0 enters with a solid-body swirl; the outlet's pressure, the
Windkessel's, is uniform over the patch, while the swirl needs a pressure
that rises from the axis to the wall, so fluid is drawn back in around the
axis (backflow). Checked at the end of the run:
  - the run reached its endTime (backflow without stabilisation feeds
    kinetic energy into the pipe and the run blows up on the way);
  - the outlet takes flow in: at least 5 % of its faces (else the case
    does not exercise the stabilisation);
  - the flow stays bounded: the largest speed in the pipe at most twice
    the inlet's largest (a diverging run grows without bound; the stable
    one keeps about 1.3 times it, from its first second on);
  - the outlet pressure's mean over the last second on the Windkessel's
    steady state p_d + (Rp + Rd) Q for the measured flow (1 %; the
    stabilisation acts on the velocity only).

Usage: checkBackflow.py [caseDir]
"""
import os
import re
import sys

import numpy as np

from checkWindkessel import entry, series


def patch_values(path, patch, vector):
    """the values of a patch's 'value' entry (nonuniform or uniform)"""
    text = open(path).read()
    body = text[text.index("boundaryField"):]
    body = body[re.search(r"\b%s\s*\{" % patch, body).end():]
    m = re.search(r"\bvalue\s+(uniform|nonuniform\s+List<\w+>)\s*", body)
    rest = body[m.end():]
    if m.group(1) == "uniform":
        v = rest[:rest.index(";")].strip("() \n").split()
        return np.array([[float(x) for x in v]] if vector else [float(v[0])])
    n = int(re.match(r"(\d+)", rest).group(1))
    rest = rest[rest.index("(") + 1:]
    if vector:
        rows = re.findall(r"\(([^()]*)\)", rest)[:n]
        return np.array([[float(x) for x in r.split()] for r in rows])
    return np.array(rest.split(")")[0].split()[:n], dtype=float)


def internal_vectors(path):
    text = open(path).read()
    i = text.index("internalField")
    m = re.search(r"nonuniform\s+List<vector>\s*(\d+)\s*\(", text[i:])
    n = int(m.group(1))
    rows = re.findall(r"\(([^()]*)\)", text[i + m.end():])[:n]
    return np.array([[float(x) for x in r.split()] for r in rows])


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "."
    control = open(os.path.join(case, "system", "controlDict")).read()
    end = float(re.search(r"^endTime\s+([-+0-9.eE]+)\s*;", control,
                          re.M).group(1))
    times = []
    for d in os.listdir(case):
        try:
            times.append((float(d), d))
        except ValueError:
            pass
    last, lastDir = max(times)
    ok = True

    def check(name, passed, text):
        nonlocal ok
        ok = ok and passed
        print("%-30s %s  %s" % (name, text, "PASS" if passed else "FAIL"))

    check("run to its end", abs(last - end) <= 1e-9*max(1, end),
          "last time %g s, endTime %g s" % (last, end))
    if not ok:
        print("FAILED: the run stopped before its end (blew up?)")
        return 1

    phi = patch_values(os.path.join(case, lastDir, "phi"), "outlet", False)
    back = phi < 0
    check("backflow at the outlet", back.mean() >= 0.05,
          "%d of %d faces take flow in (%.1f %%; at least 5 %%), %.4g m3/s"
          " in against %.4g out" % (back.sum(), len(phi), 100*back.mean(),
                                    -phi[back].sum(), phi[~back].sum()))

    U = internal_vectors(os.path.join(case, lastDir, "U"))
    Uin = patch_values(os.path.join(case, lastDir, "U"), "inlet", True)
    umax, uin = np.linalg.norm(U, axis=1).max(), \
        np.linalg.norm(Uin, axis=1).max()
    check("largest speed [m/s]", umax <= 2*uin,
          "measured %.4g, the inlet's largest %.4g (ratio %.3f; at most 2)"
          % (umax, uin, umax/uin))

    text = open(os.path.join(case, "0", "p")).read()
    Rp, Rd = entry(text, "Rp"), entry(text, "Rd")
    pd, rho = entry(text, "pDistal"), entry(text, "rho")
    tq, Q = series(case, "outletFlow")
    tp, p = series(case, "outletPressure")
    sel, selp = tq > end - 1 + 1e-9, tp > end - 1 + 1e-9
    Qm, pm = Q[sel].mean(), rho*p[selp].mean()
    ref = pd + (Rp + Rd)*Qm
    err = 100*(pm - ref)/ref
    check("outlet pressure mean [Pa]", abs(err) <= 1,
          "measured %.6g, reference %.6g (p_d + (Rp + Rd) Q, Q %.6g m3/s),"
          " error %+.3f %%, tolerance 1 %%" % (pm, ref, Qm, err))
    print("PASS" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
