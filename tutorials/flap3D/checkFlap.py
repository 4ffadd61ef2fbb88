#!/usr/bin/env python3
"""Tip displacement and drag of tutorial flap3D at the end of the run.

    checkFlap.py [label]

Reads postProcessing/solidProbes/*/displacement.dat (probe 'tip') and
postProcessing/flapForce/*/forces.dat (force of the fluid on the flap), all
start-time directories joined (a restart's lines replace the later ones of
the run before). Prints the final tip displacement and drag and their change
over the last 0.5 s (the run should have settled: < 2 %). Fails if a value
is not finite, the flap did not bend downstream, the drag is not positive,
or the run has not settled. There is no published reference for this case:
the README's table compares the coarse and medium meshes.
"""
import glob
import math
import os
import sys


def series(pattern):
    rows = {}
    for d in sorted(glob.glob(pattern), key=lambda f: float(f.split(os.sep)[-2])):
        for line in open(d):
            if line.startswith("#") or not line.strip():
                continue
            v = [float(x) for x in line.split()]
            # a restart replaces what the earlier run wrote after it
            for t in [t for t in rows if t >= v[0] - 1e-12 and d != rows[t][1]]:
                del rows[t]
            rows[v[0]] = (v, d)
    return [rows[t][0] for t in sorted(rows)]


label = sys.argv[1] if len(sys.argv) > 1 else ""
probe = series("postProcessing/solidProbes/*/displacement.dat")
force = series("postProcessing/flapForce/*/forces.dat")
if not probe or not force:
    print("FAIL: no probe or force output under postProcessing/")
    sys.exit(1)

def at(rows, t, col):
    best = min(rows, key=lambda r: abs(r[0] - t))
    return best[col]

tEnd = probe[-1][0]
ux, uy = probe[-1][1], probe[-1][2]
drag = force[-1][1]
ux0 = at(probe, tEnd - 0.5, 1)
drag0 = at(force, tEnd - 0.5, 1)
dux = abs(ux - ux0) / max(abs(ux), 1e-30)
ddrag = abs(drag - drag0) / max(abs(drag), 1e-30)

print("flap3D %s at t = %g s" % (label, tEnd))
print("  tip displacement x: %.5g mm (y: %.4g mm); change over the last 0.5 s %.2g %%"
      % (1e3 * ux, 1e3 * uy, 100 * dux))
print("  drag on the flap:   %.5g N; change over the last 0.5 s %.2g %%" % (drag, 100 * ddrag))
ok = True
for name, v in (("tip displacement", ux), ("drag", drag)):
    if not math.isfinite(v):
        print("FAIL: %s is not finite" % name)
        ok = False
if ux <= 0:
    print("FAIL: the flap did not bend downstream (tip u_x = %g)" % ux)
    ok = False
if drag <= 0:
    print("FAIL: the drag is not positive (%g N)" % drag)
    ok = False
settled = tEnd >= 3.0
if settled and (dux > 0.02 or ddrag > 0.02):
    print("FAIL: not settled over the last 0.5 s (tolerance 2 %)")
    ok = False
print("PASS" if ok else "FAILED")
sys.exit(0 if ok else 1)
