#!/usr/bin/python3
"""The aortic valve tutorial's numbers beside the paper's (README.md,
"Results"), from the valve metrics written during the run:
postProcessing/valveMetrics/<startTime>/valveMetrics.dat
(src/fsiCoupling/valveMetrics; a restarted run's files are joined).

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
                     valve's slits), if it happens
  regurgitant volume the integral of the backward outlet flow from the
                     flow's reversal to that time (or to the end)
  leak               the mean backward outlet flow over the last 5 ms,
                     against 1 % of the peak forward flow (the issue's
                     target)
Contact: the smallest leaflet-leaflet and leaflet-wall gaps of all rows
(negative: interpenetration) and the largest contact force.

    valveReport.py [caseDir]
Prints the table; exits 0 (a report, not a check).
"""
import glob
import os
import sys

import numpy as np

PAPER_OPEN = 0.019   # s, Yao et al. 2012, Sect. 5
PAPER_RE = 700.0


def read(case):
    files = glob.glob(os.path.join(case, "postProcessing", "valveMetrics",
                                   "*", "valveMetrics*.dat"))
    if not files:
        sys.exit("valveReport.py: no postProcessing/valveMetrics/*/"
                 "valveMetrics.dat in %s" % case)
    files.sort(key=lambda p: float(os.path.basename(os.path.dirname(p))))
    names, rows = None, []
    for path in files:
        with open(path) as f:
            for line in f:
                if line.startswith("#"):
                    names = [n.split("[")[0] for n in line[1:].split()]
                elif line.strip():
                    r = [float(x) for x in line.split()]
                    rows = [q for q in rows if q[0] < r[0]] + [r]
    data = np.array(rows)
    return {n: data[:, i] for i, n in enumerate(names)}


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
        if t_rev is not None:
            w = (t >= t_rev) & (t <= t_close)
            vol = -np.trapz(np.minimum(q[w], 0), t[w]) if w.sum() > 1 else 0.0
            print("  regurgitant volume from the flow's reversal (%.4f s) to"
                  " %.4f s: %.3e m3 (%.2f ml)" % (t_rev, t_close, vol, vol * 1e6))
        last = t >= t[-1] - 0.005
        leak = -np.mean(np.minimum(q[last], 0))
        print("  leak over the last 5 ms %.3e m3/s = %.2f %% of the peak forward"
              " flow (target below 1 %%)" % (leak, 100 * leak / max(q.max(), 1e-30)))
    print("  smallest gaps: leaflet-leaflet %.3f mm, leaflet-wall %.3f mm;"
          " largest contact force %.3g N; largest displacement %.2f mm"
          % (m["gapLeaflets"].min(), m["gapWall"].min(),
             m["contactForce"].max(), m["maxDisplacement"].max()))


if __name__ == "__main__":
    main()
