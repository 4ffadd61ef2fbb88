#!/usr/bin/env python3
"""The Windkessel outlet's pressure against the RCR model's periodic solution.

For a flow Q(t) = Q0 + Re(Q1 exp(i w t)) into a three-element Windkessel,
p = p_C + Rp Q, C dp_C/dt = Q - (p_C - p_d)/Rd, the periodic state is
    p(t) = p_d + (Rp + Rd) Q0 + Re(Z(w) Q1 exp(i w t)),
    Z(w) = Rp + Rd/(1 + i w Rd C)
(Westerhof, Lankhaar & Westerhof, Med Biol Eng Comput 47:131, 2009). The
flow is the one measured through the outlet (function object
<patch>Flow), the pressure the outlet's (<patch>Pressure, times rho); both
over the last
period of the run (the start-up transient decays as exp(-t/(Rd C))),
fitted by least squares with a mean and the first harmonic. Checked: the
mean and the amplitude within 1 %, the phase within 2 degrees.

Usage: checkWindkessel.py [caseDir] [--period T] [--patch outlet]
"""
import cmath
import glob
import math
import os
import re
import sys

import numpy as np


def entry(text, name, patch="outlet"):
    """A scalar entry of the patch's dictionary in 0/p"""
    block = re.search(r"\b%s\s*\{(.*?)\n\s*\}" % re.escape(patch), text,
                      re.S)
    if not block:
        raise SystemExit("checkWindkessel: no patch %s in 0/p" % patch)
    m = re.search(r"\b%s\s+(?:constant\s+)?([-+0-9.eE]+)\s*;" % name,
                  block.group(1))
    if not m:
        raise SystemExit("checkWindkessel: no entry %s in 0/p's %s"
                         % (name, patch))
    return float(m.group(1))


def series(case, name):
    """time -> value of a surfaceFieldValue function object, all its start
    times (a restart's later directory overrides)"""
    data = {}
    dirs = sorted(glob.glob(os.path.join(case, "postProcessing", name, "*")),
                  key=lambda d: float(os.path.basename(d)))
    for d in dirs:
        for line in open(os.path.join(d, "surfaceFieldValue.dat")):
            if line.startswith("#") or not line.strip():
                continue
            t, v = line.split()[:2]
            data[float(t)] = float(v)
    if not data:
        raise SystemExit("checkWindkessel: no samples of %s" % name)
    t = np.array(sorted(data))
    return t, np.array([data[k] for k in t])


def harmonic(t, x, w):
    """mean and complex amplitude X1 of x = m + Re(X1 exp(i w t))"""
    A = np.column_stack([np.ones_like(t), np.cos(w*t), np.sin(w*t)])
    (m, a, b), *_ = np.linalg.lstsq(A, x, rcond=None)
    return m, complex(a, -b)


def main():
    args = sys.argv[1:]
    T = 1.0
    if "--period" in args:
        i = args.index("--period")
        T = float(args[i + 1])
        del args[i:i + 2]
    patch = "outlet"
    if "--patch" in args:
        i = args.index("--patch")
        patch = args[i + 1]
        del args[i:i + 2]
    case = args[0] if args else "."
    text = open(os.path.join(case, "0", "p")).read()
    Rp, C, Rd = (entry(text, k, patch) for k in ("Rp", "C", "Rd"))
    pd, rho = entry(text, "pDistal", patch), entry(text, "rho", patch)
    w = 2*math.pi/T

    tq, Q = series(case, patch + "Flow")
    tp, p = series(case, patch + "Pressure")
    if len(tq) != len(tp) or np.any(np.abs(tq - tp) > 1e-9):
        raise SystemExit("checkWindkessel: flow and pressure sampled apart")
    end = tq[-1]
    last = tq > end - T + 1e-9          # the last period, one sample a step
    if end < 2*T or last.sum() < 8:
        raise SystemExit("checkWindkessel: run to at least two periods")
    Q0, Q1 = harmonic(tq[last], Q[last], w)
    p0, p1 = harmonic(tp[last], rho*p[last], w)

    Z = Rp + Rd/(1 + 1j*w*Rd*C)
    ref0 = pd + (Rp + Rd)*Q0
    ref1 = Z*Q1

    print("Windkessel %s (Rp %g, C %g, Rd %g; Rd C = %g s), period %g s,"
          " t in (%g, %g] s, %d samples" % (patch, Rp, C, Rd, Rd*C, T,
                                             end - T, end, last.sum()))
    print("  flow through the outlet: mean %.6g m3/s, amplitude %.6g m3/s"
          % (Q0, abs(Q1)))
    ok = True

    def check(name, measured, reference, error, tol, unit):
        nonlocal ok
        passed = abs(error) <= tol
        ok = ok and passed
        print("%-28s measured %12.6g  reference %12.6g  error %+8.3f %s"
              "  tolerance %g %s  %s" % (name, measured, reference, error,
                                         unit, tol, unit,
                                         "PASS" if passed else "FAIL"))

    check("outlet pressure mean [Pa]", p0, ref0, 100*(p0 - ref0)/ref0, 1, "%")
    check("outlet pressure amplitude", abs(p1), abs(ref1),
          100*(abs(p1) - abs(ref1))/abs(ref1), 1, "%")
    dphase = math.degrees(cmath.phase(p1/ref1))
    check("phase of p against Q [deg]", math.degrees(cmath.phase(p1/Q1)),
          math.degrees(cmath.phase(Z)), dphase, 2, "deg")
    print("PASS" if ok else "FAILED: the outlet pressure is off the RCR"
          " model's periodic solution")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
