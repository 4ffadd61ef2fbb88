#!/usr/bin/python3
"""The valve's heartbeats (./Allrun -heartbeat): the metrics per beat beside
the normal native aortic valve's and ISO 5840's requirements, and the
pulse duplicator's picture. numpy and matplotlib only (Debian's
/usr/bin/python3).

Run from the case directory after a run:

    ./heartbeatReport.py [-o pictures]

Reads postProcessing/valveMetrics/<start>/valveMetrics.dat (every start
directory of a run that was restarted, in time order) and beats.dat, and
writes:

  heartbeat.png   against time over all beats: the ventricular
                  (p_upstream) and aortic (p_downstream) pressure [mmHg],
                  the flow through the valve (Q_inlet) [ml/s], and the
                  geometric orifice area [mm2]; the beats' boundaries
                  dashed.

Prints each beat's row and the last beat's metrics beside the references
(docs/references.md: Baumgartner et al. 2009 for the normal native valve;
ISO 5840:2005's minimum performance of a 23 mm aortic valve, the nearest
size to this root's base diameter 2 r_b = 23.5 mm), and the periodicity:
the stroke volume and mean aortic pressure of the last beat against the
beat before (target 2 %).
"""
import argparse
import glob
import math
import os
import sys

import numpy as np

# the references (docs/references.md)
V_JET_NORMAL = 2.5          # m/s: above, aortic sclerosis or stenosis
                            # (Baumgartner et al. 2009, Table 4)
DP_MEAN_MILD = 20.0         # mmHg: mild stenosis below (same)
EOA_NORMAL = (3.0, 4.0)     # cm2: the normal aortic valve area (same)
EOA_ISO_23 = 1.00           # cm2: ISO 5840:2005 minimum EOA, aortic 23 mm
RF_ISO_23 = 10.0            # %: ISO 5840:2005 largest RF, aortic 23 mm
PERIODIC = 2.0              # %: SV and mean aortic pressure, beat to beat


def read_table(path):
    """The numeric rows and the names of the last '#' line before them."""
    names, rows = None, []
    with open(path) as f:
        for line in f:
            if line.startswith('#'):
                if not rows:
                    names = line.lstrip('#').split()
                continue
            if line.strip():
                rows.append([float(x) for x in line.split()])
    return names, np.array(rows) if rows else np.zeros((0, len(names or [])))


def series(case):
    """valveMetrics.dat of every start directory, in time order."""
    files = sorted(glob.glob(os.path.join(
        case, 'postProcessing', 'valveMetrics', '*', 'valveMetrics.dat')),
        key=lambda p: float(os.path.basename(os.path.dirname(p))))
    if not files:
        sys.exit('heartbeatReport: no postProcessing/valveMetrics/*/'
                 'valveMetrics.dat: run ./Allrun -heartbeat first')
    names, data = None, []
    for path in files:
        n, d = read_table(path)
        names = n
        data.append(d)
    data = np.vstack(data)
    if data.ndim != 2 or data.shape[0] == 0 or data.shape[1] == 0:
        sys.exit('heartbeatReport: ' + ', '.join(files) + ' hold no rows:'
                 ' the run ended before the first row (writeInterval of'
                 ' system/valveMetrics.run); run longer')
    data = data[np.argsort(data[:, 0], kind='stable')]
    keep = np.append(np.diff(data[:, 0]) > 0, True)     # restarts overlap
    return {name: data[keep, i] for i, name in enumerate(names)}


def beats(case):
    rows, names = [], None
    for path in sorted(glob.glob(os.path.join(
            case, 'postProcessing', 'valveMetrics', '*', 'beats.dat')),
            key=lambda p: float(os.path.basename(os.path.dirname(p)))):
        n, d = read_table(path)
        names = n
        rows.extend(d.tolist())
    return names, rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('-o', default='pictures', help='output directory')
    ap.add_argument('--case', default='.')
    args = ap.parse_args()

    s = series(args.case)
    names, rows = beats(args.case)
    if 'p_upstream[mmHg]' not in s:
        sys.exit('heartbeatReport: valveMetrics.dat has no p_upstream: '
                 'the run had no beats entry (./Allrun -heartbeat)')

    # the rows
    print('Valve metrics per beat (postProcessing/valveMetrics/*/beats.dat)')
    if rows:
        print('  ' + '  '.join(names))
        for r in rows:
            print('  ' + '  '.join(f'{v:.4g}' for v in r))
    else:
        print('  no beat completed')

    # the last beat beside the references
    if rows:
        last = dict(zip(names, rows[-1]))
        print(f"\nBeat {int(last['beat'])} (from {last['start[s]']:g} s) "
              'beside the references (docs/references.md):')
        table = [
            ('stroke volume', f"{last['SV[ml]']:.1f} ml", 'about 70 ml'),
            ('cardiac output', f"{last['CO[L/min]']:.2f} L/min",
             'about 5 L/min'),
            ('aortic pressure', f"{last['p_aorta_max[mmHg]']:.0f}/"
             f"{last['p_aorta_min[mmHg]']:.0f} mmHg", '120/80 mmHg'),
            ('peak jet velocity', f"{last['v_jet_peak[m/s]']:.2f} m/s",
             f'normal below {V_JET_NORMAL} m/s'),
            ('mean gradient', f"{last['dp_mean[mmHg]']:.1f} mmHg",
             f'mild stenosis below {DP_MEAN_MILD:.0f} mmHg'),
            ('EOA', f"{last['EOA[cm2]']:.2f} cm2",
             f'normal {EOA_NORMAL[0]}-{EOA_NORMAL[1]} cm2; ISO 5840 23 mm: '
             f'at least {EOA_ISO_23} cm2'),
            ('regurgitant fraction', f"{last['RF[%]']:.1f} %",
             f'ISO 5840 23 mm: at most {RF_ISO_23:.0f} %'),
            ('GOA max', f"{last['GOA_max[mm2]']:.0f} mm2", ''),
            ('open, close', f"{last['t_open[ms]']:.0f}, "
             f"{last['t_close[ms]']:.0f} ms", ''),
            ('peak leaflet stress', f"{last['stress_peak[kPa]']:.0f} kPa",
             ''),
        ]
        for what, value, ref in table:
            print(f'  {what:22s} {value:22s} {ref}')
        if len(rows) > 1:
            dsv, dpa = last['dSV[%]'], last['dp_aorta_mean[%]']
            ok = abs(dsv) <= PERIODIC and abs(dpa) <= PERIODIC
            print(f'  periodic: stroke volume {dsv:+.2f} %, mean aortic '
                  f'pressure {dpa:+.2f} % against the beat before (target '
                  f'{PERIODIC:g} %): {"met" if ok else "not yet"}')

    # the pulse duplicator's picture
    os.environ.setdefault('MPLCONFIGDIR', os.path.abspath('.mplconfig'))
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    t = s['Time']
    fig, ax = plt.subplots(3, 1, sharex=True, figsize=(9, 8))
    ax[0].plot(t, s['p_upstream[mmHg]'], label='ventricle (p_upstream)')
    ax[0].plot(t, s['p_downstream[mmHg]'], label='aorta (p_downstream)')
    ax[0].set_ylabel('pressure [mmHg]')
    ax[0].legend(loc='upper right')
    ax[1].plot(t, 1e6*s['Q_inlet[m3/s]'], color='C2')
    ax[1].axhline(0, color='k', lw=0.5)
    ax[1].set_ylabel('flow through the valve [ml/s]')
    ax[2].plot(t, s['GOA[mm2]'], color='C3')
    ax[2].set_ylabel('orifice area GOA [mm2]')
    ax[2].set_xlabel('time [s]')
    for r in rows:
        for a in ax:
            a.axvline(r[names.index('start[s]')], color='k', ls='--', lw=0.6)
    fig.suptitle('Aortic valve: heartbeats (isfemFoam)')
    fig.tight_layout()
    os.makedirs(args.o, exist_ok=True)
    out = os.path.join(args.o, 'heartbeat.png')
    fig.savefig(out, dpi=110)
    print(f'\nwrote {out}')
    return 0


if __name__ == '__main__':
    sys.exit(main())
