#!/usr/bin/python3
"""thinPlate: the coupled static deflection of the plate's centre against
the structure-only deflection of the same plate under the same uniform
pressure (README.md).

Reads
  postProcessing/solidProbes/<startTime>/displacement.dat   coupled run
      '# time centre_x centre_y centre_z' (isfemFoam, constant/solidProperties
      output.probes); several start times (a restarted run) are joined
  solidOnly/probes.dat                                      structure only
      '# time  centre_ux centre_uy centre_uz' (smoothedSolidRun plate.solid)
  postProcessing/plate/<startTime>/immersedForcing.dat      force on the plate

Checks
  - both runs at rest: over the last REST_WINDOW (20 %) of each run's time
    the centre deflection u_x varies (max - min) by less than REST_TOL (1 %,
    a fifth of the comparison's tolerance) of its mean there
  - coupled u_x within TOLERANCE (5 %) of the structure-only u_x; the
    coupled u_x is the mean over that last 20 % (it jitters by about
    +-0.15 % as the plate's edge cells are covered and uncovered), the
    structure-only u_x its last value (smoothedSolidRun stops on its own
    steadyTolerance)
  - the force of the fluid on the plate at the end, F_x, within FORCE_TOL
    (2 %) of rho_f dp A (the whole pressure difference on the duct's
    section, which the plate closes)
(with Allrun -carried, where the fluid carries the plate, the first two
only) and exits non-zero if any fails.   checkThinPlate.py [caseDir]
"""
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.environ.get(
    "ISFEM_PROJECT_DIR",
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")),
    "tutorials"))
import validation as v  # noqa: E402

PROBE = "centre"
TOLERANCE = 5.0       # % coupled vs structure-only centre deflection
REST_WINDOW = 0.2     # last fraction of each run's time span
REST_TOL = 0.01       # (max - min)/|mean| of u_x over that window
FORCE_TOL = 2.0       # % F_x against rho_f dp A
LEAK_TOL = 1e-3       # m3/s through the carried plate at rest (1 mm/s)
RHO_F = 1000.0        # kg/m3, system/fvOptions rhoFluid
DP = 1.0              # m2/s2, kinematic inlet pressure (0.orig/p), outlet 0
AREA = 1.0            # m2, duct section 1 m x 1 m (system/blockMeshDict)


def probe_history(path, name):
    """(times, u_x) of probe 'name' in a table whose last '#' line names the
    columns ('time <name>_x ...' or '<name>_ux ...'); without names the
    first probe (columns 1-3)."""
    header = []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                header = line[1:].split()
    col = 1
    if header:
        names = [h for h in header]
        for cand in (name + "_x", name + "_ux"):
            if cand in names:
                col = names.index(cand)
                break
        else:
            sys.exit("%s: no column %s_x or %s_ux in the header %s"
                     % (path, name, name, " ".join(header)))
    rows = v.read_table(path)
    return [r[0] for r in rows], [r[col] for r in rows]


def joined(pattern, name):
    """One history from the files of all start-time directories (a
    restart's rows replace the later rows of the run before it)."""
    files = glob.glob(pattern)
    if not files:
        sys.exit("no %s: did the run write it?" % pattern)
    files.sort(key=lambda p: float(os.path.basename(os.path.dirname(p))))
    t, u = [], []
    for p in files:
        tp, up = probe_history(p, name)
        if tp:
            keep = [i for i, ti in enumerate(t) if ti < tp[0]]
            t = [t[i] for i in keep] + tp
            u = [u[i] for i in keep] + up
    return t, u


def rest_window(t, u):
    """The last REST_WINDOW of the run: (t0, values of u_x)."""
    t0 = t[-1] - REST_WINDOW * (t[-1] - t[0])
    return t0, [ui for ti, ui in zip(t, u) if ti >= t0]


def at_rest(label, t, u):
    t0, window = rest_window(t, u)
    mean = sum(window) / len(window)
    spread = (max(window) - min(window)) / abs(mean) if mean else float("inf")
    return v.condition(
        "%s at rest" % label, spread,
        "(max - min)/|mean u_x| over t in [%.4g, %.4g] s, tolerance < %g"
        % (t0, t[-1], REST_TOL), spread < REST_TOL)


def main():
    case = sys.argv[1] if len(sys.argv) > 1 else \
        os.path.dirname(os.path.abspath(__file__))
    os.chdir(case)

    tc, uc = joined("postProcessing/solidProbes/*/displacement.dat", PROBE)
    ts, us = probe_history("solidOnly/probes.dat", PROBE)
    t0, window = rest_window(tc, uc)
    coupled = sum(window) / len(window)
    print("thinPlate: centre deflection u_x [m] of the plate (0.995 m across,"
          " 0.025 m thick)")
    print("  coupled        (isfemFoam)        mean over t in [%.4g, %.4g] s:"
          " u_x = %.6g (last %.6g)" % (t0, tc[-1], coupled, uc[-1]))
    print("  structure only (smoothedSolidRun) at t = %.4g s: u_x = %.6g"
          % (ts[-1], us[-1]))
    at_rest("coupled run", tc, uc)
    at_rest("structure-only run", ts, us)
    v.relative("coupled u_x (vs solid only)", coupled, us[-1], TOLERANCE)

    forces = sorted(glob.glob("postProcessing/plate/*/immersedForcing.dat"),
                    key=lambda p: float(os.path.basename(os.path.dirname(p))))
    if os.path.exists("system/fvOptions.run"):
        # Allrun -carried: the fluid carries the plate (immersedElasticForce);
        # its force is the plate's own elastic force, whose free nodes'
        # share the log reports: the deflection above is the check
        print("force check: not applicable to the carried plate (Allrun"
              " -carried), its load is checked through the deflection")
        # the plate closes the duct: at rest no flow passes (closed form
        # 0); the leak of a carried plate without the balanced face force
        # was 0.0103 m3/s (src/fsiCoupling/README.md)
        q = None
        if os.path.exists("log.postProcess.flowRate"):
            for line in open("log.postProcess.flowRate"):
                if "sum(inlet) of phi" in line:
                    q = float(line.split("=")[-1])
        if q is None:
            sys.exit("no flow rate in log.postProcess.flowRate")
        v.condition("flow through the plate at rest", abs(q),
                    "|Q| [m3/s], closed form 0, tolerance < %g" % LEAK_TOL,
                    abs(q) < LEAK_TOL)
    elif forces:
        last = v.read_table(forces[-1])[-1]
        v.relative("force F_x (rho_f dp A)", last[1], RHO_F * DP * AREA,
                   FORCE_TOL)
    else:
        sys.exit("no postProcessing/plate/*/immersedForcing.dat")
    v.finish()


if __name__ == "__main__":
    main()
