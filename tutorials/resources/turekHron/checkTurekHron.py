#!/usr/bin/env python3
"""Turek & Hron (2006) FSI benchmarks FSI1 and FSI2, and CFD1 (the flag held
rigid; docs/references.md): measured values beside the references, non-zero
exit if out of tolerance.

    checkTurekHron.py [--benchmark FSI1|FSI2|CFD1] [--short] [options]

Reads (every start-time directory, concatenated by time; a later start
overrides the rows of an earlier one from its start time on):
  postProcessing/solidProbes/<t>/displacement.dat   time A_x A_y A_z ... [m]
  postProcessing/bodyForces/<t>/forces.dat          time Fx Fy Fz ...    [N]
(forces on the slab of depth dz, system/blockMeshDict 'depth': F/dz is per
metre).

FSI1 (steady): at the end of the run u_y(A) within 5 % of 0.8209 mm, drag
within 3 % of 14.295 N/m, and steady: u_y(A) and drag vary by less than 1 %
over the last 10 % of the run (at least its last second); u_x(A) and lift
reported.

CFD1 (steady, the flag rigid; no displacement file needed): at the end of
the run drag within 3 % of 14.29 N/m and lift within 5 % of 1.119 N/m, and
steady: each varies by less than 1 % over the last 10 % of the run (at
least its last second).

FSI2 (periodic): over the last K full periods of u_y(A) (--periods, default
3; periods between upward crossings of the mid level (max+min)/2):
u_y(A) amplitude (max-min)/2 within 5 % of 80.6 mm, frequency within 3 % of
2.0 Hz, drag mean (max+min)/2 and amplitude within 5 % of 208.83 and
73.75 N/m; the amplitude of the K periods within 3 % of their mean (a
limit cycle, not a growing or decaying oscillation); u_x(A), lift, the
drag frequency and the FFT frequency of u_y reported.

FSI2 --short (onset of flapping, for runs too short for the limit cycle;
from --from T0, default 2 s, the end of the inflow ramp): the turning
points of the transverse displacement u_y(A) (a maximum or minimum counts
once u_y has moved back from it by --band, default 5 %, of its range, so
noise does not count) and the swings between them. The flag flaps about a
mean deflection that drifts, so a swing is compared with the one a period
before (the same direction). Checks:
  - the flag flaps: at least --growth + 2 swings (default 5), the last
    above --floor (default 0.1 mm: clear of round-off, 1 to 2 % of a
    fluid cell). A flag bent to one side and held there, or resting on the
    centreline, fails;
  - it grows: each of the last --growth (default 3) swings larger than
    the one a period before (the symmetric state is unstable, as in the
    benchmark), or the limit cycle already reached (last swing at least
    90 % of 2 x 80.6 mm; a coarse mesh whose limit cycle is smaller, as
    N = 24's +-65 mm, fails once saturated: run it only into the growth).
    A decaying oscillation fails;
  - in the benchmark's mode: the frequency (half the inverse of the mean
    time between the turning points used) within --freq-tol (default
    10 %) of 2.0 Hz. A numerical instability of the coupling also flaps
    and grows, but at the time-step scale, and fails here.
The growth factor per period and the growth rate are reported.
"""
import argparse
import glob
import math
import os
import sys

import numpy as np

sys.dont_write_bytecode = True   # no __pycache__ in tutorials/

# tutorials/validation.py: $ISFEM_PROJECT_DIR/tutorials, else the parent
# tutorials/ (validation.py), two levels up from this file
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                "..", ".."))
if "ISFEM_PROJECT_DIR" in os.environ:
    sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"],
                                    "tutorials"))
import validation as v  # noqa: E402

# The benchmark when --benchmark is not given (the tutorials give it)
DEFAULT_BENCHMARK = "FSI1"

REF = {
    "FSI1": {"ux": 0.0227, "uy": 0.8209, "drag": 14.295, "lift": 0.7638},
    "CFD1": {"drag": 14.29, "lift": 1.119},
    "FSI2": {"ux": (-14.58, 12.44, 3.8), "uy": (1.23, 80.6, 2.0),
             "drag": (208.83, 73.75, 3.8), "lift": (0.88, 234.2, 2.0)},
}


# ------------------------------------------------------------------ reading

def _is_time(name):
    try:
        float(name)
        return True
    except ValueError:
        return False


def _read_rows(path):
    """Header tokens (last '#' line) and rows of floats; parentheses
    dropped (vectors become components); short or unreadable rows (a line
    cut by a running writer) skipped."""
    header, rows = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                toks = line[1:].replace("(", " ").replace(")", " ").split()
                if toks:
                    header = toks
                continue
            toks = line.replace("(", " ").replace(")", " ").split()
            if not toks:
                continue
            try:
                rows.append([float(t) for t in toks])
            except ValueError:
                continue
    if rows:
        n = max(len(r) for r in rows)
        rows = [r for r in rows if len(r) == n]
    return header, rows


def read_series(base, filename):
    """All start-time directories of base holding filename, concatenated:
    a later start time overrides the earlier rows from its start on.
    Returns (header, array) or (None, None) when there is none."""
    dirs = [d for d in glob.glob(os.path.join(base, "*"))
            if os.path.isdir(d) and _is_time(os.path.basename(d))
            and os.path.isfile(os.path.join(d, filename))]
    if not dirs:
        return None, None
    dirs.sort(key=lambda d: float(os.path.basename(d)))
    header, rows = [], []
    for d in dirs:
        start = float(os.path.basename(d))
        h, r = _read_rows(os.path.join(d, filename))
        if h:
            header = h
        rows = [x for x in rows if x[0] < start - 1e-12] + r
    if not rows:
        return header, None
    n = min(len(r) for r in rows)
    a = np.array([r[:n] for r in rows])
    # in time order, last entry of a repeated time kept
    a = a[np.argsort(a[:, 0], kind="stable")]
    keep = np.append(a[1:, 0] > a[:-1, 0], True)
    return header, a[keep]


def column(header, names, default):
    """Index of the first of names in header (the time column is 0), else
    default."""
    for name in names:
        if name in header:
            return header.index(name)
    return default


def read_depth(case, given):
    if given:
        return given
    path = os.path.join(case, "system", "blockMeshDict")
    try:
        with open(path) as f:
            for line in f:
                toks = line.replace(";", " ").split()
                if len(toks) == 2 and toks[0] == "depth":
                    return float(toks[1])
    except OSError:
        pass
    sys.exit("slab depth not found ('depth' in %s): give --depth" % path)


def read_displacement(case, probe):
    header, a = read_series(os.path.join(case, "postProcessing",
                                         "solidProbes"), "displacement.dat")
    if a is None:
        sys.exit("FAIL: no postProcessing/solidProbes/<time>/displacement.dat"
                 " (output { probes { %s ...; } } in constant/"
                 "solidProperties)" % probe)
    ix = column(header, [probe + "_x", probe + "x", "ux"], 1)
    iy = column(header, [probe + "_y", probe + "y", "uy"], ix + 1)
    return a[:, 0], a[:, ix], a[:, iy]


def read_forces(case):
    """time, Fx, Fy [N] on cylinder + flag."""
    pp = os.path.join(case, "postProcessing")
    header, a = read_series(os.path.join(pp, "bodyForces"), "forces.dat")
    if a is not None:
        ix = column(header, ["Fx", "total_x"], 1)
        iy = column(header, ["Fy", "total_y"], ix + 1)
        return a[:, 0], a[:, ix], a[:, iy], "postProcessing/bodyForces"
    sys.exit("FAIL: no postProcessing/bodyForces/<time>/forces.dat (the"
             " immersedForces function object in system/controlDict)")


# ---------------------------------------------------------------- analysis

def up_crossings(t, u, level):
    """Times where u crosses level upwards (linear interpolation)."""
    d = u - level
    i = np.nonzero((d[:-1] < 0) & (d[1:] >= 0))[0]
    return t[i] - d[i] * (t[i + 1] - t[i]) / (d[i + 1] - d[i])


def window_stats(t, u, t0, t1):
    m = (t >= t0) & (t <= t1)
    hi, lo = u[m].max(), u[m].min()
    return 0.5 * (hi + lo), 0.5 * (hi - lo)


def fft_frequency(t, u, t0, t1):
    """Peak frequency of u over [t0, t1]: uniform resampling, Hann window,
    8x zero padding, parabolic refinement of the peak."""
    m = (t >= t0) & (t <= t1)
    n = max(64, int(4 * m.sum()))
    tu = np.linspace(t0, t1, n)
    x = np.interp(tu, t[m], u[m])
    x = (x - x.mean()) * np.hanning(n)
    spec = np.abs(np.fft.rfft(x, 8 * n))
    f = np.fft.rfftfreq(8 * n, tu[1] - tu[0])
    k = int(np.argmax(spec[1:])) + 1
    if 0 < k < len(spec) - 1:
        a, b, c = spec[k - 1], spec[k], spec[k + 1]
        den = a - 2 * b + c
        s = 0.5 * (a - c) / den if den != 0 else 0.0
        return f[k] + s * (f[1] - f[0])
    return f[k]


def turning_points(t, u, band):
    """The alternating maxima and minima of u: a candidate extremum is taken
    once u has moved back from it by more than band (so noise smaller than
    band does not count); the first sample is never one. Returns a list of
    (time, value, +1 for a maximum or -1 for a minimum)."""
    ext = []
    ihi = ilo = 0
    state = 0                      # +1 rising (seeking a max), -1 falling
    for i in range(1, len(u)):
        if state >= 0 and u[i] > u[ihi]:
            ihi = i
        if state <= 0 and u[i] < u[ilo]:
            ilo = i
        if state >= 0 and u[i] < u[ihi] - band:
            if ihi > 0:
                ext.append((t[ihi], u[ihi], 1))
            state, ilo = -1, i
        elif state <= 0 and u[i] > u[ilo] + band:
            if ilo > 0:
                ext.append((t[ilo], u[ilo], -1))
            state, ihi = 1, i
    return ext


# ------------------------------------------------------------------ checks

def check_fsi1(t, ux, uy, tf, fx, fy, dz, src):
    ref = REF["FSI1"]
    tend = min(t[-1], tf[-1])
    print("Turek & Hron FSI1 at t = %g s; forces from %s, per unit depth"
          " (depth %g m)" % (tend, src, dz))
    uy_mm, ux_mm = 1e3 * uy, 1e3 * ux
    drag, lift = fx / dz, fy / dz
    v.relative("u_y(A) [mm]", uy_mm[-1], ref["uy"], 5.0)
    v.relative("drag [N/m]", drag[-1], ref["drag"], 3.0)
    v.report("u_x(A) [mm]", ux_mm[-1], ref["ux"])
    v.report("lift [N/m]", lift[-1], ref["lift"])
    # steady: range over the last 10 % of the run, at least the last 1 s
    for name, tt, x in (("u_y(A)", t, uy_mm), ("drag", tf, drag)):
        m = tt >= min(0.9 * tt[-1], tt[-1] - 1.0)
        var = (x[m].max() - x[m].min()) / max(abs(x[-1]), 1e-300)
        v.condition("%s range, last 10%% [%%]" % name, 100 * var,
                    "of the final value, at most 1 %", var <= 0.01)


def check_cfd1(tf, fx, fy, dz, src):
    ref = REF["CFD1"]
    print("Turek & Hron CFD1 (flag rigid) at t = %g s; forces from %s, per"
          " unit depth (depth %g m)" % (tf[-1], src, dz))
    drag, lift = fx / dz, fy / dz
    v.relative("drag [N/m]", drag[-1], ref["drag"], 3.0)
    v.relative("lift [N/m]", lift[-1], ref["lift"], 5.0)
    m = tf >= min(0.9 * tf[-1], tf[-1] - 1.0)
    for name, x in (("drag", drag), ("lift", lift)):
        var = (x[m].max() - x[m].min()) / max(abs(x[-1]), 1e-300)
        v.condition("%s range, last 10%% [%%]" % name, 100 * var,
                    "of the final value, at most 1 %", var <= 0.01)


def check_fsi2(t, ux, uy, tf, fx, fy, dz, src, K):
    ref = REF["FSI2"]
    uy_mm, ux_mm = 1e3 * uy, 1e3 * ux
    drag, lift = fx / dz, fy / dz
    # mid level from the last fifth, then from the periods found
    m = t >= t[0] + 0.8 * (t[-1] - t[0])
    level = 0.5 * (uy_mm[m].max() + uy_mm[m].min())
    for _ in range(2):
        c = up_crossings(t, uy_mm, level)
        if len(c) < K + 1:
            print("Turek & Hron FSI2: %d full periods of u_y(A) found up to"
                  " t = %g s, %d needed" % (max(len(c) - 1, 0), t[-1], K))
            v.condition("full periods of u_y(A)", max(len(c) - 1, 0),
                        "at least %d" % K, False)
            return
        t0, t1 = c[-K - 1], c[-1]
        level = window_stats(t, uy_mm, t0, t1)[0]
    print("Turek & Hron FSI2: last %d periods of u_y(A), t = %.4f..%.4f s;"
          " forces from %s, per unit depth (depth %g m)"
          % (K, t0, t1, src, dz))
    amps = [window_stats(t, uy_mm, a, b)[1] for a, b in zip(c[-K - 1:-1],
                                                             c[-K:])]
    my = window_stats(t, uy_mm, t0, t1)[0]
    ay = float(np.mean(amps))
    f = K / (t1 - t0)
    v.relative("u_y(A) amplitude [mm]", ay, ref["uy"][1], 5.0)
    v.relative("u_y(A) frequency [Hz]", f, ref["uy"][2], 3.0)
    spread = (max(amps) - min(amps)) / ay
    v.condition("u_y(A) ampl. spread [%]", 100 * spread,
                "of the mean of %d periods, at most 3 %%" % K,
                spread <= 0.03)
    if tf[-1] < t1 or tf[0] > t0:
        v.condition("forces cover the window", tf[-1], "until t >= %g" % t1,
                    False)
        return
    md, ad = window_stats(tf, drag, t0, t1)
    v.relative("drag mean [N/m]", md, ref["drag"][0], 5.0)
    v.relative("drag amplitude [N/m]", ad, ref["drag"][1], 5.0)
    v.report("u_y(A) mean [mm]", my, ref["uy"][0])
    v.report("u_y(A) last period ampl [mm]", amps[-1], ref["uy"][1])
    v.report("u_y(A) FFT frequency [Hz]", fft_frequency(t, uy_mm, t0, t1),
             ref["uy"][2])
    mx, ax = window_stats(t, ux_mm, t0, t1)
    v.report("u_x(A) mean [mm]", mx, ref["ux"][0])
    v.report("u_x(A) amplitude [mm]", ax, ref["ux"][1])
    v.report("drag frequency [Hz]", fft_frequency(tf, drag, t0, t1),
             ref["drag"][2])
    ml, al = window_stats(tf, lift, t0, t1)
    v.report("lift mean [N/m]", ml, ref["lift"][0])
    v.report("lift amplitude [N/m]", al, ref["lift"][1])


def check_fsi2_short(t, uy, tf, fx, dz, args):
    ref = REF["FSI2"]
    m = t >= args.from_time
    t, u = t[m], 1e3 * uy[m]
    if len(t) < 3:
        sys.exit("FAIL: no u_y(A) data after t = %g s" % args.from_time)
    band = max(args.band * (u.max() - u.min()), 1e-9)
    ext = turning_points(t, u, band)
    # swings between successive turning points (down, up, down, ...); a
    # swing and the one a period earlier go the same way, so their ratio
    # is the growth per period whatever the mean deflection (the flag
    # flaps about a slowly drifting offset)
    swings = [abs(b[1] - a[1]) for a, b in zip(ext[:-1], ext[1:])]
    print("Turek & Hron FSI2, onset of flapping, t = %g..%g s: %d turning"
          " points of u_y(A) (band %.3g mm), %d swings"
          % (t[0], t[-1], len(ext), band, len(swings)))
    for (ta, ua, sa), (tb, ub, _) in list(zip(ext[:-1], ext[1:]))[-8:]:
        print("    %.4f s %s %8.3f mm -> %.4f s %8.3f mm  swing %.4g mm"
              % (ta, "max" if sa > 0 else "min", ua, tb, ub, abs(ub - ua)))
    n = args.growth
    ok = v.condition("swings of u_y(A)", len(swings),
                     "at least %d (%d growth ratios)" % (n + 2, n),
                     len(swings) >= n + 2)
    if not swings:
        return
    v.condition("last swing [mm]", swings[-1],
                "above %g mm" % args.floor, swings[-1] > args.floor)
    if not ok:
        return
    ratios = [swings[j] / swings[j - 2]
              for j in range(len(swings) - n, len(swings))]
    saturated = swings[-1] >= 0.9 * 2 * ref["uy"][1]
    g = math.exp(sum(math.log(x) for x in ratios) / n)
    # period: twice the mean time between the turning points used
    te = [e[0] for e in ext[-(n + 3):]]
    period = 2 * (te[-1] - te[0]) / (len(te) - 1)
    v.condition("growth per period", g,
                "each of the last %d > 1 (%s)%s"
                % (n, " ".join("%.3f" % x for x in ratios),
                   ", or saturated" if saturated else ""),
                all(x > 1 for x in ratios) or saturated)
    v.report("growth rate [1/s]", math.log(g) / period)
    v.relative("flapping frequency [Hz]", 1.0 / period, ref["uy"][2],
               args.freq_tol)
    mt = (tf >= te[-3]) & (tf <= te[-1])
    if mt.any():
        v.report("drag mean last period [N/m]", float(np.mean(fx[mt])) / dz,
                 ref["drag"][0])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--benchmark", choices=("FSI1", "FSI2", "CFD1"),
                   default=DEFAULT_BENCHMARK)
    p.add_argument("--case", default=".", help="case directory")
    p.add_argument("--depth", type=float, default=None,
                   help="slab depth [m] (default: system/blockMeshDict)")
    p.add_argument("--probe", default="A", help="solid probe name")
    p.add_argument("--periods", type=int, default=3,
                   help="FSI2: full periods analysed (default 3)")
    p.add_argument("--short", action="store_true",
                   help="FSI2: check the onset of flapping only")
    p.add_argument("--from", dest="from_time", type=float, default=2.0,
                   help="--short: start of the analysis [s] (default 2)")
    p.add_argument("--growth", type=int, default=3,
                   help="--short: last swings each larger than the one a"
                        " period before (3)")
    p.add_argument("--band", type=float, default=0.05,
                   help="--short: a turning point counts when u_y moves"
                        " back by this fraction of its range (0.05)")
    p.add_argument("--freq-tol", dest="freq_tol", type=float, default=10.0,
                   help="--short: frequency tolerance [%%] (10)")
    p.add_argument("--floor", type=float, default=0.1,
                   help="--short: last swing at least this [mm] (0.1)")
    args = p.parse_args()
    if args.growth < 1:
        p.error("--growth must be at least 1")

    dz = read_depth(args.case, args.depth)
    tf, fx, fy, src = read_forces(args.case)
    if args.benchmark == "CFD1":
        if args.short:
            sys.exit("--short is for FSI2")
        check_cfd1(tf, fx, fy, dz, src)
        v.finish()
        return
    t, ux, uy = read_displacement(args.case, args.probe)
    if args.benchmark == "FSI1":
        if args.short:
            sys.exit("--short is for FSI2")
        check_fsi1(t, ux, uy, tf, fx, fy, dz, src)
    elif args.short:
        check_fsi2_short(t, uy, tf, fx, dz, args)
    else:
        check_fsi2(t, ux, uy, tf, fx, fy, dz, src, args.periods)
    v.finish()


if __name__ == "__main__":
    main()
