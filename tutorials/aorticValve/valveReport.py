#!/usr/bin/python3
"""The aortic valve tutorial's numbers beside the paper's (README.md,
"Results"), from the valve metrics written during the run:
postProcessing/valveMetrics/<startTime>/valveMetrics.dat
(src/fsiCoupling/functionObjects/valveMetrics; a restarted run's files are joined).

Opening (forward pressure, dp > 0):
  plateau            the largest orifice area (GOA) while dp > 0
  time to open       the first time GOA is within 5 % of that plateau
                     (Yao et al. 2012, Sect. 5: fully open at 0.019 s)
  peak Re            the largest Re = 2 rho v r_c / mu while dp > 0
                     (paper: about 700)
  peak forward flow  the largest Q_outlet
Closing (back pressure, dp < 0):
  time to close      the first time after dp turns negative that GOA is
                     within 10 % of its value at the start (the closed
                     valve's slits), if it happens; else, once the flow
                     has stopped, the first time after GOA's peak under
                     back pressure that it is within 10 % of its last
                     value (the orifice the closed valve keeps under back
                     pressure)
  flow stopped       the first time after the flow's reversal from which
                     the backward outlet flow, averaged over 2 ms, stays
                     below 5 % of the peak forward flow to the end (the
                     valve seals although, seen along the axis, the slits
                     of two leaflets carried by the same fluid cells stay
                     open)
  regurgitant volume the integral of the outlet flow (backward positive)
                     from the flow's reversal to the time to close, else
                     to the flow's stop, else to the end
  outlet flow        the mean outlet flow over the last 20 ms (backward
                     positive; time-weighted), but not before the back
                     pressure starts
  leak               the flow through the closed valve over that window,
                     between the leaflets' VTU files (VTK/solid/
                     solid_<t>.vtu) nearest its ends: the outlet flow less
                     the volume the leaflets sweep downstream over it
                     (the mean of their aortic and ventricular faces' sweep;
                     a leaflet moving downstream pushes fluid through the
                     outlet without any passing the valve); against 1 % of
                     the peak forward flow (the issue's target). The
                     column's swing behind the closed valve is the
                     leaflets' own, so the leak is steady from window to
                     window where the outlet flow's mean is not (README)
Contact: the smallest leaflet-leaflet and leaflet-wall gaps of all rows
(negative: interpenetration) and the largest contact force.
Curvature (from the leaflets' VTU files, VTK/solid/solid_<time>.vtu, at the
time to open): each leaflet's mid-line, the nodes within 10 degrees of its
centre plane (undeformed positions; the frame of valveParameters.geo: axis
z, leaflet k centred at 120 (k - 1) degrees from x), averaged in 10 bands of undeformed
radius from the attachment to the free edge, in its (radial, axial) plane;
the mean turning of the line over its lower and upper halves. The paper's
opening valve bends one way near the attachment and the other near the
free edge (its curvature reverses from bottom to top): opposite signs,
each at least 0.5 degrees per segment.

    valveReport.py [caseDir]
Prints the table; exits 0 (a report, not a check).
"""
import glob
import os
import sys

import numpy as np

PAPER_OPEN = 0.019   # s, Yao et al. 2012, Sect. 5
PAPER_RE = 700.0
LEAK_WINDOW = 0.020  # s: about one period of the fluid column's oscillation
                     # behind the closed coarse valve (README)


def boundary_faces(tets):
    """The faces of a tet mesh that belong to one tet only, oriented as
    the tet's outward faces for a positively oriented tet (a, b, c, d)."""
    f = np.concatenate([tets[:, [0, 2, 1]], tets[:, [0, 1, 3]],
                        tets[:, [1, 2, 3]], tets[:, [0, 3, 2]]])
    _, first, count = np.unique(np.sort(f, axis=1), axis=0,
                                return_index=True, return_counts=True)
    return f[first[count == 1]]


def solid_tets(vtu, path):
    for conn, off, types in vtu["cells"]:
        if len(off) and np.all(np.diff(np.concatenate(([0], off))) == 4):
            return conn.reshape(-1, 4)
    sys.exit("valveReport.py: %s holds no tetrahedra" % path)


def swept_downstream(path0, path1, axis=(0.0, 0.0, 1.0)):
    """The volume (m3) the leaflets' surface sweeps along the axis between
    the VTU files path0 and path1 (the same mesh): over each boundary face
    the mean displacement dotted with the face's area vector at the mean
    position, counted positive where the face moves downstream whichever
    side it faces, halved (a thin leaflet's two faces sweep the same
    volume); the outlet flow this motion makes, without any fluid passing
    the valve, is this volume over the time between the files."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from valvePictures import read_vtk
    a, b = read_vtk(path0), read_vtk(path1)
    tets = solid_tets(a, path0)
    if len(a["points"]) != len(b["points"]):
        sys.exit("valveReport.py: %s and %s are not the same mesh"
                 % (path0, path1))
    F = boundary_faces(tets)
    x0, x1 = a["points"], b["points"]
    xm = 0.5 * (x0 + x1)
    area = 0.5 * np.cross(xm[F[:, 1]] - xm[F[:, 0]], xm[F[:, 2]] - xm[F[:, 0]])
    d = (x1 - x0)[F].mean(axis=1)
    side = np.sign(area @ np.asarray(axis))
    return 0.5 * np.sum(side * np.einsum("ij,ij->i", d, area))


def solid_files(case):
    """{time: path} of the leaflets' VTU files, VTK/solid/solid_<t>.vtu"""
    out = {}
    for p in glob.glob(os.path.join(case, "VTK", "solid", "solid_*.vtu")):
        try:
            out[float(os.path.basename(p)[6:-4])] = p
        except ValueError:
            pass
    return out


def leak_through_valve(case, t, q, t0):
    """Print and return the flow through the closed valve (m3/s, backward
    positive) from t0 to the end: the outlet flow less the leaflets'
    sweep, between their VTU files nearest the window's ends; None
    without two such files."""
    files = solid_files(case)
    tv = np.array(sorted(files))
    if len(tv) < 2:
        print("  leak through the valve: no VTK/solid/solid_<t>.vtu files"
              " for the leaflets' sweep")
        return None
    ta = tv[np.argmin(abs(tv - t0))]
    tb = tv[np.argmin(abs(tv - t[-1]))]
    w = (t >= ta) & (t <= tb)
    if tb <= ta or w.sum() < 2:
        print("  leak through the valve: one VTU file in the window")
        return None
    qm = np.trapz(q[w], t[w]) / (t[w][-1] - t[w][0])
    sweep = swept_downstream(files[ta], files[tb]) / (tb - ta)
    leak = sweep - qm
    print("  leak through the closed valve over %.4f-%.4f s: the leaflets'"
          " sweep downstream %.3e m3/s less the outlet flow %.3e m3/s ="
          " %.3e m3/s backward = %.2f %% of the peak forward flow (target"
          " below 1 %%)" % (ta, tb, sweep, qm, leak,
                            100 * leak / max(q.max(), 1e-30)))
    return leak


def read(case):
    """The metrics series of a run and its restarts, joined by
    valvePictures.py (a restart's rows replace the earlier rows from its
    first time on), as {name without its [unit]: column}."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from valvePictures import metrics_files, read_metrics_series
    files = metrics_files(case)
    if not files:
        sys.exit("valveReport.py: no postProcessing/valveMetrics/<startTime>/"
                 "valveMetrics.dat in %s: run isfemFoam with the valveMetrics "
                 "function object first" % case)
    names, data = read_metrics_series(files)
    if not len(data):
        sys.exit("valveReport.py: no data rows in %s" % ", ".join(files))
    return {n.split("[")[0]: data[:, i] for i, n in enumerate(names)}


def midline_turning(path, leaflet, bands=10, halfAngle=10.0):
    """Mean turning (degrees per segment, sign: counter-clockwise in the
    leaflet's (radial, axial) plane) of leaflet k's mid-line over its lower
    (attachment) and upper (free edge) halves, from the VTU at path."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from valvePictures import read_vtk  # its VTU reader (needs matplotlib)
    vtu = read_vtk(path)
    x = vtu["points"]
    x0 = x - vtu["point_data"]["displacement"].reshape(-1, 3)
    centre = np.radians(120.0 * leaflet)
    theta0 = np.angle(np.exp(1j * (np.arctan2(x0[:, 1], x0[:, 0]) - centre)))
    r0 = np.hypot(x0[:, 0], x0[:, 1])
    near = np.abs(np.degrees(theta0)) < halfAngle
    if near.sum() < 2 * bands:
        return None
    edges = np.linspace(r0[near].min(), r0[near].max(), bands + 1)
    radial = x[:, 0] * np.cos(centre) + x[:, 1] * np.sin(centre)
    line = []
    for b in range(bands, 0, -1):         # attachment (large r0) first
        sel = near & (r0 >= edges[b - 1]) & (r0 <= edges[b])
        if sel.any():
            line.append((radial[sel].mean(), x[sel, 2].mean()))
    p = np.array(line)
    d = np.diff(p, axis=0)
    turn = np.degrees(np.arctan2(d[:-1, 0] * d[1:, 1] - d[:-1, 1] * d[1:, 0],
                                 (d[:-1] * d[1:]).sum(axis=1)))
    half = len(turn) // 2
    return turn[:half].mean(), turn[half:].mean()


def curvature_shape(lower, upper, straight=0.5):
    """The mid-line's shape from its mean turning over the lower and upper
    halves (degrees per segment, midline_turning): 'flat' (both below
    1e-9), 'a half nearly straight' (one below `straight`), 'reverses'
    (opposite signs: the curvature reversal of an open leaflet) or 'one
    way'."""
    if max(abs(lower), abs(upper)) < 1e-9:
        return "flat"
    if min(abs(lower), abs(upper)) < straight:
        return "a half nearly straight"
    return "reverses" if lower * upper < 0 else "one way"


def curvature_report(case, t_open):
    files = glob.glob(os.path.join(case, "VTK", "solid", "solid_*.vtu"))
    times = {}
    for f in files:
        try:
            times[float(os.path.basename(f)[6:-4])] = f
        except ValueError:
            pass
    if not times:
        print("  curvature: no VTK/solid/solid_<time>.vtu")
        return
    t = min(times, key=lambda s: abs(s - t_open))
    out = []
    for k in range(3):
        try:
            r = midline_turning(times[t], k)
        except ImportError as err:
            print("  curvature: not measured (%s)" % err)
            return
        if r is None:
            out.append("leaflet %d: too few nodes" % (k + 1))
            continue
        lower, upper = r
        shape = curvature_shape(lower, upper)
        out.append("leaflet %d %+.1f / %+.1f deg (%s)"
                   % (k + 1, lower, upper, shape))
    print("  curvature of the mid-lines at %.4f s, mean turning per segment"
          " lower / upper half: %s" % (t, "; ".join(out)))


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else "."
    m = read(case)
    t, goa, dp, re_ = m["Time"], m["GOA"], m["dp"], m["Re"]
    q = m["Q_outlet"]
    fwd = dp > 0
    print("aortic valve: %d rows, t = %.4g .. %.4g s" % (len(t), t[0], t[-1]))
    if fwd.any():
        plateau = goa[fwd].max()
        t_open = t[fwd][np.argmax(goa[fwd] >= 0.95 * plateau)]
        print("  opening: orifice area %.1f -> %.1f mm2 (plateau); within 5 %%"
              " of it at %.4f s (paper: fully open at %.3f s)"
              % (goa[0], plateau, t_open, PAPER_OPEN))
        print("  peak Re %.0f (paper: about %.0f); peak forward flow %.3e m3/s"
              % (re_[fwd].max(), PAPER_RE, q.max()))
        curvature_report(case, t_open)
    back = dp < 0
    if back.any():
        t_back = t[back][0]
        closed = back & (goa <= 1.10 * goa[0])
        rev = back & (q < 0)
        t_rev = t[rev][0] if rev.any() else None
        if closed.any():
            t_close = t[closed][0]
            print("  closing: back pressure from %.4f s; orifice within 10 %% of"
                  " the closed valve's (%.1f mm2) at %.4f s" % (t_back, goa[0],
                                                              t_close))
        else:
            t_close = t[-1]
            print("  closing: back pressure from %.4f s; the orifice does not"
                  " come within 10 %% of the closed valve's %.1f mm2 (last"
                  " %.1f mm2)" % (t_back, goa[0], goa[-1]))
        t_stop = None
        if t_rev is not None:
            # the backflow's 2 ms running mean below 5 % of the peak
            # forward flow from some time after the reversal to the end
            after = t >= t_rev
            tt, qq = t[after], -q[after]
            # running mean by cumulative sums (trapezoid rule)
            cum = np.concatenate(([0.0], np.cumsum(
                0.5 * (qq[1:] + qq[:-1]) * np.diff(tt))))
            j = np.searchsorted(tt, tt - 0.002)
            span = tt - tt[j]
            mean2 = np.where(span > 0, (cum - cum[j]) / np.maximum(span, 1e-300),
                             qq)
            low = (mean2 < 0.05 * q.max()) & (tt >= tt[0] + 0.002)
            if tt[-1] - tt[0] < 0.002:
                print("  less than 2 ms after the flow's reversal: no time"
                      " for the flow to stop")
            elif low.any() and low[-1]:
                k = len(low) - 1
                while k > 0 and low[k - 1]:
                    k -= 1
                t_stop = tt[k]
                print("  flow stopped (backflow's 2 ms mean below 5 %% of the"
                      " peak forward flow to the end) from %.4f s" % t_stop)
            else:
                print("  the backflow's 2 ms mean does not stay below 5 % of"
                      " the peak forward flow")
            t_end = (t_close if closed.any()
                     else (t_stop if t_stop is not None else t[-1]))
            w = (t >= t_rev) & (t <= t_end)
            vol = -np.trapz(q[w], t[w]) if w.sum() > 1 else 0.0
            print("  regurgitant volume from the flow's reversal (%.4f s) to"
                  " %.4f s: %.3e m3 (%.2f ml)" % (t_rev, t_end, vol, vol * 1e6))
        if not closed.any() and t_stop is not None:
            # the orifice the closed valve keeps (under back pressure the
            # slits stand wider than at rest): after the area's peak under
            # back pressure, the first time it is within 10 % of its last
            # value (as the time to open: the first time near the plateau)
            gb, tb = goa[back], t[back]
            after = np.arange(len(gb)) >= np.argmax(gb)
            near = after & (gb <= 1.10 * gb[-1])
            k = np.argmax(near)
            print("  closed: the orifice within 10 %% of the %.1f mm2 it keeps"
                  " at the end at %.4f s, %.1f ms after the back pressure"
                  % (gb[-1], tb[k], (tb[k] - t_back) * 1e3))
        # the window: the last LEAK_WINDOW, but not before the back
        # pressure (a run stopped early would count forward flow)
        t0 = max(t[-1] - LEAK_WINDOW, t_back)
        last = t >= t0
        if last.sum() > 1 and t[-1] > t0:
            leak = -np.trapz(q[last], t[last]) / (t[last][-1] - t[last][0])
            short = (" (only %.1f ms of back pressure)" % ((t[-1] - t0) * 1e3)
                     if t[-1] - t0 < LEAK_WINDOW - 1e-9 else "")
            print("  outlet flow over the last %.1f ms%s (mean backward) %.3e"
                  " m3/s = %.2f %% of the peak forward flow"
                  % ((t[-1] - t0) * 1e3, short, leak,
                     100 * leak / max(q.max(), 1e-30)))
            leak_through_valve(case, t, q, t0)
        else:
            print("  leak: no rows after the back pressure starts")
    print("  smallest gaps: leaflet-leaflet %.3f mm, leaflet-wall %.3f mm;"
          " largest contact force %.3g N; largest displacement %.2f mm"
          % (m["gapLeaflets"].min(), m["gapWall"].min(),
             m["contactForce"].max(), m["maxDisplacement"].max()))


if __name__ == "__main__":
    main()
