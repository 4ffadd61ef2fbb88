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

Prints per beat the stroke volume, cardiac output, aortic pressure
(largest/smallest/mean) and the largest flow. The defaults are the
tutorial's (Allrun -heartbeat: system/changeDictionaryDict.heartbeat):

    ./heartbeatLumped.py                       # Rp 0.05, C 1.8, Rd 1.1
    ./heartbeatLumped.py --Rp 0.05 --C 1.5 --Rd 1.2 --beats 6

Units: Rp, Rd in mmHg s/ml, C in ml/mmHg (1 mmHg s/ml = 1.33322e8 Pa s/m3,
1 ml/mmHg = 7.5006e-9 m3/Pa).
"""
import argparse

MMHG = 133.322


def waveform(path):
    """(time, mmHg) rows of a tableFile, '//' comments dropped."""
    rows = []
    for line in open(path):
        line = line.split('//')[0].replace('(', ' ').replace(')', ' ')
        w = line.split()
        if len(w) == 2:
            rows.append((float(w[0]), float(w[1])))
    return rows


def interp(rows, t):
    for (t0, p0), (t1, p1) in zip(rows, rows[1:]):
        if t0 <= t <= t1:
            return p0 + (p1 - p0)*(t - t0)/(t1 - t0)
    return rows[-1][1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--table', default='constant/ventriclePressure')
    ap.add_argument('--scale', type=float, default=1.1)
    ap.add_argument('--Rp', type=float, default=0.05)
    ap.add_argument('--C', type=float, default=1.8)
    ap.add_argument('--Rd', type=float, default=1.1)
    ap.add_argument('--pC', type=float, default=77, help='start [mmHg]')
    ap.add_argument('--eoa', type=float, default=1.6, help='[cm2]')
    ap.add_argument('--L', type=float, default=2.3e5,
                    help='inertance [Pa s2/m3]: rho length/area')
    ap.add_argument('--rho', type=float, default=1060)
    ap.add_argument('--beats', type=int, default=4)
    a = ap.parse_args()

    rows = waveform(a.table)
    T = rows[-1][0]
    Rp, Rd = a.Rp*MMHG*1e6, a.Rd*MMHG*1e6
    C = a.C*1e-6/MMHG
    eoa = a.eoa*1e-4
    dt = 1e-5
    n = int(round(T/dt))
    pC, Q = a.pC*MMHG, 0.0
    for beat in range(a.beats):
        sv, pmax, pmin, psum, qmax = 0.0, -1e9, 1e9, 0.0, 0.0
        for i in range(n):
            pv = a.scale*interp(rows, i*dt)*MMHG
            p = pC + Rp*Q
            if Q > 0 or pv > p:
                dQ = (pv - p - 0.5*a.rho*(Q/eoa)**2)/a.L
                Q = max(Q + dt*dQ, 0.0)
            pC += dt*(Q - pC/Rd)/C
            p = pC + Rp*Q
            sv += Q*dt
            pmax, pmin, psum = max(pmax, p), min(pmin, p), psum + p*dt
            qmax = max(qmax, Q)
        print(f'beat {beat + 1}: SV {sv*1e6:.1f} ml, CO {sv/T*6e4:.2f} '
              f'L/min, aorta {pmax/MMHG:.1f}/{pmin/MMHG:.1f} mmHg, mean '
              f'{psum/T/MMHG:.1f} mmHg, largest flow {qmax*1e6:.0f} ml/s')


if __name__ == '__main__':
    main()
