#!/usr/bin/python3
"""Checks of the leaflet phases from results.<phase>/metrics.dat, summary and
log.<phase> (written by Allrun); prints measured against reference and
tolerance, exits 1 if a check fails.

    check.py phase ...

  closing           fibre tissue under 80 mmHg: every pair of leaflets in
                    contact, leaflet penetration below 5 % of the smallest
                    element height, nothing behind the wall (beyond the same
                    5 %), the orifice shut, at rest
  opening           fibre tissue under 40 mmHg: orifice area from near zero
                    to a plateau, nothing behind the wall (5 % of the
                    smallest element height), at rest
  closingNoContact  negative control, contact off: the leaflets pass into
                    each other (penetration above half the smallest element
                    height)
  openingPaper, closingPaper   the paper's material: reported, not checked
"""
import math
import os
import re
import sys

import numpy as np

failed = []
R_C = 9.10e-3  # orifice disk radius (m), as metrics.py


def check(name, ok, measured, reference):
    print("  %-44s %-28s %-34s %s" % (name, measured, reference, "PASS" if ok else "FAIL"))
    if not ok:
        failed.append(name)


def load(phase):
    d = "results." + phase
    if not os.path.exists(d + "/metrics.dat"):
        print("%s: no results (%s/metrics.dat): run ./Allrun first" % (phase, d))
        failed.append(phase)
        return None
    with open(d + "/metrics.dat") as fh:
        keys = fh.readline().split()[1:]
    data = np.loadtxt(d + "/metrics.dat", ndmin=2)
    table = {k: data[:, i] for i, k in enumerate(keys)}
    summary = {}
    with open(d + "/summary") as fh:
        for line in fh:
            k, v = line.split()
            summary[k] = float(v)
    ke = []
    if os.path.exists("log." + phase):
        ke = [float(x) for x in re.findall(r"kinetic energy ([0-9.eE+-]+)", open("log." + phase).read())]
    stopped = open(d + "/stopped").read().strip() if os.path.exists(d + "/stopped") else ""
    return table, summary, np.array(ke), stopped


def at_rest(table, ke):
    """Kinetic energy fallen below 1e-4 of its peak (the rms speed below 1 %
    of its peak), largest displacement changed by less than 0.5 % over the
    last 5 output intervals"""
    ratio = ke[-1] / ke.max() if len(ke) and ke.max() > 0 else float("nan")
    check("at rest: final/peak kinetic energy", ratio < 1e-4, "%.2e" % ratio, "< 1e-4")
    u = table["maxDisplacement_mm"]
    change = abs(u[-1] - u[-6]) / u[-1] if len(u) > 6 else float("nan")
    check("at rest: max displacement change, last 5 ms", change < 5e-3, "%.2e" % change, "< 0.5 %")


def ran_through(stopped):
    check("ran to its end time", not stopped, stopped or "yes", "no inverted element")


def closing(phase="closing"):
    r = load(phase)
    if not r:
        return
    t, s, ke, stopped = r
    h = s["hMin_mm"]
    print("%s: smallest element height %.4f mm" % (phase, h))
    ran_through(stopped)
    for pair in ("12", "13", "23"):
        a = s["contactArea%s_mm2" % pair]
        check("leaflets %s-%s in contact: contact area" % (pair[0], pair[1]), a > 1.0,
              "%.2f mm2" % a, "> 1 mm2")
    pen = t["maxLeafletPenetration_mm"].max()
    check("leaflet penetration (largest, all times)", pen < 0.05 * h, "%.5f mm" % pen,
          "< 5%% of h_min = %.5f mm" % (0.05 * h))
    wall = t["minWallGap_mm"].min()
    check("leaflet-wall gap (smallest, all times)", wall > -0.05 * h, "%.5f mm" % wall,
          "> -5%% of h_min = %.5f mm" % (-0.05 * h))
    a0, a1 = t["orificeArea_mm2"][0], t["orificeArea_mm2"][-1]
    check("orifice shut: final/initial orifice area", a1 < 0.1 * a0, "%.3f/%.2f mm2" % (a1, a0), "< 0.1")
    at_rest(t, ke)


def opening(phase="opening"):
    r = load(phase)
    if not r:
        return
    t, s, ke, stopped = r
    h = s["hMin_mm"]
    disk = math.pi * (R_C * 1e3) ** 2
    print("%s: smallest element height %.4f mm, orifice disk %.1f mm2" % (phase, h, disk))
    ran_through(stopped)
    A = t["orificeArea_mm2"]
    check("orifice area at start (near zero)", A[0] < 0.1 * disk, "%.2f mm2" % A[0],
          "< 10%% of disk = %.1f mm2" % (0.1 * disk))
    check("orifice area at the end (open)", A[-1] > 0.8 * disk, "%.2f mm2" % A[-1],
          "> 80%% of disk = %.1f mm2" % (0.8 * disk))
    plateau = abs(A[-1] - A[-6]) / A[-1] if len(A) > 6 else float("nan")
    check("orifice area plateau: change, last 5 ms", plateau < 0.01, "%.2e" % plateau, "< 1 %")
    wall = t["minWallGap_mm"].min()
    check("leaflet-wall gap (smallest, all times)", wall > -0.05 * h, "%.5f mm" % wall,
          "> -5%% of h_min = %.5f mm" % (-0.05 * h))
    print("  leaflet nodes touching the wall at the end: %d" % s["nodesBehindWall"])
    at_rest(t, ke)


def closingNoContact(phase="closingNoContact"):
    r = load(phase)
    if not r:
        return
    t, s, ke, stopped = r
    h = s["hMin_mm"]
    pen = t["maxLeafletPenetration_mm"].max()
    print("%s (contact off): smallest element height %.4f mm" % (phase, h))
    check("leaflets pass into each other: penetration", pen > 0.5 * h, "%.4f mm" % pen,
          "> 50%% of h_min = %.4f mm" % (0.5 * h))


def report(phase):
    r = load(phase)
    if not r:
        return
    t, s, ke, stopped = r
    print("%s (reported, not checked): %s" % (phase, stopped or "ran to its end time"))
    print("  last written state t = %.1f ms: orifice %.1f mm2, max displacement %.2f mm, "
          "min J %.3f, leaflet gap %.4f mm, wall gap %.4f mm, %d nodes behind the wall"
          % (t["time_ms"][-1], t["orificeArea_mm2"][-1], t["maxDisplacement_mm"][-1],
             t["minJ"][-1], t["minLeafletGap_mm"][-1], t["minWallGap_mm"][-1],
             t["nodesBehindWall"][-1]))


def main():
    phases = sys.argv[1:] or ["opening", "closing", "openingPaper", "closingPaper"]
    for p in phases:
        if p == "closing":
            closing()
        elif p == "opening":
            opening()
        elif p == "closingNoContact":
            closingNoContact()
        elif p in ("openingPaper", "closingPaper"):
            report(p)
        else:
            sys.exit("check.py: unknown phase '%s'" % p)
    if failed:
        print("check.py: FAILED: " + ", ".join(failed))
        sys.exit(1)
    print("check.py: all checks PASS")


if __name__ == "__main__":
    main()
