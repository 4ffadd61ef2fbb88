#!/usr/bin/python3
"""A lumped (0-D) model of the heartbeat, to choose the Windkessel for a
ventricular waveform before the 3-D run: the ventricle's pressure of
constant/ventriclePressure (times --scale), an ideal valve (no flow back;
open while the flow is forward or the ventricle's pressure exceeds the
aorta's) of effective orifice area --eoa with Bernoulli's loss
rho/2 (Q/EOA)^2 and the inertance L of the blood between inlet and
outlet, into the three-element Windkessel p = p_C + Rp Q,
C dp_C/dt = Q - p_C/Rd (explicit Euler, dt 1e-5 s):

    L dQ/dt = p_v - p - rho/2 (Q/EOA)^2

--regurgitation V takes V ml a beat back through the closed valve (the
closing and leakage volumes of a 3-D beat's row in beats.dat), at a
constant rate over the time the valve was closed in the beat before (the
first beat: over the part of the beat the ventricle's pressure is below
--pC). With the EOA and the regurgitant volume a 3-D beat reports, the
model gives that beat's stroke volume and aortic pressure (README,
Heartbeats). --beatsFile takes both from the last row of a run's
postProcessing/valveMetrics/0/beats.dat (EOA[cm2], and V_closing[ml] plus
V_leakage[ml]).

Prints per beat the stroke volume (forward less regurgitant volume),
cardiac output, aortic pressure (largest/smallest/mean) and the largest
flow. The defaults are the tutorial's (Allrun -heartbeat:
system/changeDictionaryDict.heartbeat):

    ./heartbeatLumped.py                       # Rp 0.05, C 1.8, Rd 1.1
    ./heartbeatLumped.py --Rp 0.05 --C 1.5 --Rd 1.2 --beats 6
    ./heartbeatLumped.py --eoa 0.955 --regurgitation 11.4 --pC 61 --beats 8

--fit SV PMAX PMIN finds the ventricle's scale, C and Rd (Rp kept) for
which the periodic beat (the last of --beats) through the valve given has
that stroke volume [ml] and aortic pressures [mmHg], by Gauss-Newton
iterations from the values given, as a pulse duplicator is set for the
valve under test:

    ./heartbeatLumped.py --eoa 0.955 --regurgitation 11.4 --fit 66.7 120 80
    ./heartbeatLumped.py --beatsFile postProcessing/valveMetrics/0/beats.dat \
        --fit 66.7 120 80

Units: Rp, Rd in mmHg s/ml, C in ml/mmHg (1 mmHg s/ml = 1.33322e8 Pa s/m3,
1 ml/mmHg = 7.5006e-9 m3/Pa).
"""
import argparse
import sys

import numpy as np

MMHG = 133.322
DT = 1e-5


def waveform(path):
    """(time, mmHg) rows of a tableFile, '//' comments dropped."""
    rows = []
    for line in open(path):
        line = line.split('//')[0].replace('(', ' ').replace(')', ' ')
        w = line.split()
        if len(w) == 2:
            rows.append((float(w[0]), float(w[1])))
    if len(rows) < 2:
        sys.exit(f'{path}: no (time value) rows; see '
                 'constant/ventriclePressure for the format')
    return rows


def lastBeat(path):
    """EOA [cm2] and closing plus leakage volume [ml] of the last row of a
    valveBeat file (beats.dat), by its header's column names."""
    try:
        lines = open(path).read().splitlines()
    except OSError as e:
        sys.exit(f'{path}: {e.strerror}; --beatsFile takes the beats.dat '
                 'that a heartbeat run writes in postProcessing/valveMetrics/0')
    names = [ln[1:].split() for ln in lines if ln.startswith('# beat')]
    rows = [ln.split() for ln in lines if ln.strip() and ln[0] != '#']
    need = ('EOA[cm2]', 'V_closing[ml]', 'V_leakage[ml]')
    if not names or not rows or any(n not in names[-1] for n in need):
        sys.exit(f'{path}: no beat rows with the columns {", ".join(need)}; '
                 'is it a valveBeat file (beats.dat)?')
    col = {n: names[-1].index(n) for n in need}
    try:
        v = {n: float(rows[-1][col[n]]) for n in need}
    except (IndexError, ValueError):
        sys.exit(f'{path}: its last row ({" ".join(rows[-1][:3])} ...) is '
                 'incomplete')
    return v['EOA[cm2]'], v['V_closing[ml]'] + v['V_leakage[ml]']


def beats(rows, a, scale, C, Rd):
    """The model's beats: a list of (SV, pmax, pmin, mean, qmax) [ml,
    mmHg, ml/s]."""
    t, p = zip(*rows)
    T = t[-1]
    n = int(round(T/DT))
    pv = scale*np.interp(np.arange(n)*DT, t, p)*MMHG
    Rp, Rd = a.Rp*MMHG*1e6, Rd*MMHG*1e6
    C = C*1e-6/MMHG
    eoa = a.eoa*1e-4
    V = a.regurgitation*1e-6
    pC, Q = a.pC*MMHG, 0.0
    closed = DT*np.count_nonzero(pv < pC)
    out = []
    for beat in range(a.beats):
        qBack = V/max(closed, DT)
        closed = 0.0
        sv, pmax, pmin, psum, qmax = 0.0, -1e9, 1e9, 0.0, 0.0
        for i in range(n):
            p = pC + Rp*Q
            if Q > 0 or pv[i] > p:
                dQ = (pv[i] - p - 0.5*a.rho*(Q/eoa)**2)/a.L
                Q = max(Q + DT*dQ, 0.0)
                q = Q
            else:
                q = -qBack
                closed += DT
            pC += DT*(q - pC/Rd)/C
            p = pC + Rp*q
            sv += q*DT
            pmax, pmin, psum = max(pmax, p), min(pmin, p), psum + p*DT
            qmax = max(qmax, q)
        out.append((sv*1e6, pmax/MMHG, pmin/MMHG, psum/T/MMHG, qmax*1e6))
    return out, T


def fit(rows, a):
    """Gauss-Newton on (scale, C, Rd) for the last beat's (SV, pmax,
    pmin), each residual relative to its target."""
    target = np.array(a.fit)
    x = np.array([a.scale, a.C, a.Rd])

    def r(x):
        return np.array(beats(rows, a, *x)[0][-1][:3])/target - 1

    rx = r(x)
    for it in range(20):
        print(f'fit {it}: scale {x[0]:.4f}, C {x[1]:.4f}, Rd {x[2]:.4f}: '
              f'|residual| {np.linalg.norm(rx):.2e}')
        if np.linalg.norm(rx) < 1e-3:
            return x
        J = np.empty((3, 3))
        for j in range(3):
            h = 1e-3*x[j]
            xh = x.copy()
            xh[j] += h
            J[:, j] = (r(xh) - rx)/h
        dx = np.linalg.solve(J, -rx)
        step = 1.0
        while step > 1e-3:
            xn = x + step*dx
            if np.all(xn > 0):
                rn = r(xn)
                if np.linalg.norm(rn) < np.linalg.norm(rx):
                    break
            step /= 2
        else:
            sys.exit('fit: no step lowers the residual; try other start '
                     'values (--scale, --C, --Rd) or targets')
        x, rx = xn, rn
    sys.exit('fit: not within 1e-3 of the targets in 20 iterations')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--table', default='constant/ventriclePressure')
    ap.add_argument('--scale', type=float, default=1.1)
    ap.add_argument('--Rp', type=float, default=0.05)
    ap.add_argument('--C', type=float, default=1.8)
    ap.add_argument('--Rd', type=float, default=1.1)
    ap.add_argument('--pC', type=float, default=77, help='start [mmHg]')
    ap.add_argument('--eoa', type=float, default=1.6, help='[cm2]')
    ap.add_argument('--regurgitation', type=float, default=0.0,
                    help='closing and leakage volume a beat [ml]')
    ap.add_argument('--beatsFile', metavar='FILE',
                    help='--eoa and --regurgitation from the last row of a '
                    'beats.dat')
    ap.add_argument('--L', type=float, default=2.3e5,
                    help='inertance [Pa s2/m3]: rho length/area')
    ap.add_argument('--rho', type=float, default=1060)
    ap.add_argument('--beats', type=int, default=4)
    ap.add_argument('--fit', type=float, nargs=3,
                    metavar=('SV', 'PMAX', 'PMIN'),
                    help='find scale, C, Rd for this periodic beat')
    a = ap.parse_args()
    if a.beatsFile:
        a.eoa, a.regurgitation = lastBeat(a.beatsFile)
        print(f'{a.beatsFile}: EOA {a.eoa:.4g} cm2, closing and leakage '
              f'volume {a.regurgitation:.4g} ml')
    if min(a.eoa, a.C, a.Rd, a.scale, a.L, a.rho) <= 0 or a.Rp < 0 \
            or a.regurgitation < 0 or a.beats < 1:
        sys.exit('--eoa, --C, --Rd, --scale, --L, --rho and --beats must be'
                 ' positive, --Rp and --regurgitation not negative')

    rows = waveform(a.table)
    scale, C, Rd = a.scale, a.C, a.Rd
    if a.fit:
        if a.beats < 6:
            a.beats = 6
        scale, C, Rd = fit(rows, a)
        print(f'scale {scale:.4f} (peak {scale*max(p for _, p in rows):.0f}'
              f' mmHg), Rp {a.Rp}, C {C:.4f}, Rd {Rd:.4f}')
    out, T = beats(rows, a, scale, C, Rd)
    for beat, (sv, pmax, pmin, pmean, qmax) in enumerate(out):
        print(f'beat {beat + 1}: SV {sv:.1f} ml, CO {sv*1e-3/T*60:.2f} '
              f'L/min, aorta {pmax:.1f}/{pmin:.1f} mmHg, mean '
              f'{pmean:.1f} mmHg, largest flow {qmax:.0f} ml/s')


if __name__ == '__main__':
    main()
