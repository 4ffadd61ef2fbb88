#!/usr/bin/python3
"""annulusTorsion: the first torsional mode of an elastic annulus held
between two cylinders and carried by a viscous fluid (README.md).

    annulusTorsion.py init  [caseDir]   write 0/U: the mode's velocity
    annulusTorsion.py check [caseDir]   the probe's period and decay
                                        against the closed form

The closed form. The annulus (held at r = a' and b', the solid's radii
a + d and b - d of annulus.geo) and the fluid in it move as one
Kelvin-Voigt medium of density rho, shear modulus mu (the solid's) and
viscosity rho nu (the fluid's). A twist u_theta(r, t) is divergence-free
and needs no pressure; both the elastic and the viscous term are mu_eff
(u'' + u'/r - u/r^2), so u_theta = q(t) phi(r) with
    phi(r) = J1(k r) Y1(k a') - Y1(k r) J1(k a'),
    J1(k a') Y1(k b') - J1(k b') Y1(k a') = 0    (k the first root),
    q'' + nu k^2 q' + (mu/rho) k^2 q = 0:
an oscillator of omega0 = k sqrt(mu/rho), decay rate gamma = nu k^2/2 and
period T = 2 pi/sqrt(omega0^2 - gamma^2) (for small strains: the run's
twist is 1.6e-4 m).

The step's own error. Under the Euler scheme the fluid's velocity takes
the force of x^n + theta dt v^{n+1} (implicitForce's theta, 1 by default;
the explicit force: theta = 0) and the nodes move by dt v^{n+1}: for the
oscillator, in units of dt,
    v1 (1 + theta z^2) = v0 - z^2 x0,   x1 = x0 + v1,   z = omega0 dt,
whose amplification lambda solves lambda^2 - tr lambda + 1/c = 0, c = 1 +
theta z^2, tr = 1 + (1 - z^2)/c: |lambda| = c^(-1/2) and arg lambda =
acos(tr sqrt(c)/2), so the decay is gamma + ln(c)/(2 dt) and the period
2 pi dt/arg lambda (theta = 1: backward Euler's 1/(1 + i z), decay
ln(1 + z^2)/(2 dt), period 2 pi dt/atan(z); theta = 0: no damping of
the step's own). Derived; checked on this case at dt = 0.025 and 0.05 s
(docs/2026-11-29-annulus-torsion.md).

The check: the probe's azimuthal displacement (mid-gap, mid-height) is
fitted by A exp(-g t) sin(w t + phi) over the whole run; the period
2 pi/w within PERIOD_TOL (5 %) and the decay g within DECAY_TOL (10 %) of
the closed form with the step's error above; the continuum's values are
reported beside them.
"""
import glob
import math
import os
import re
import sys

import numpy as np
from scipy.optimize import brentq, curve_fit
from scipy.special import j1, y1

sys.path.insert(0, os.path.join(os.environ.get(
    "ISFEM_PROJECT_DIR",
    os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")),
    "tutorials"))
import validation as v  # noqa: E402

V0 = 1e-3          # m/s: the initial velocity's largest value
PERIOD_TOL = 5.0   # %
DECAY_TOL = 10.0   # %
PROBE = "mid"


def entry(path, name, text=None):
    """The number of the first 'name value;' in a dictionary file."""
    text = open(path).read() if text is None else text
    m = re.search(r"(?m)^\s*%s\s+([-+0-9.eE]+)\s*;" % name, text)
    if not m:
        sys.exit("annulusTorsion.py: no entry '%s' in %s" % (name, path))
    return float(m.group(1))


def geometry(case):
    """a', b' (the solid's held radii) from annulus.geo's DefineConstant."""
    path = os.path.join(case, "annulus.geo")
    m = re.search(r"DefineConstant\[(.*?)\]", open(path).read(), re.S)
    if not m:
        sys.exit("annulusTorsion.py: no DefineConstant in %s" % path)
    c = dict((k.strip(), float(x)) for k, x in
             (p.split("=") for p in m.group(1).split(",")))
    return c["a"] + c["d"], c["b"] - c["d"]


def first_root(a, b):
    f = lambda k: j1(k * a) * y1(k * b) - j1(k * b) * y1(k * a)
    ks = np.linspace(0.5 / (b - a), 1.5 * math.pi / (b - a), 400)
    fs = f(ks)
    i = np.nonzero(fs[:-1] * fs[1:] < 0)[0][0]
    return brentq(f, ks[i], ks[i + 1], xtol=1e-14)


def mode(case):
    a, b = geometry(case)
    k = first_root(a, b)
    props = os.path.join(case, "constant", "solidProperties")
    text = open(props).read()
    mat = text[text.index("material"):]
    mu, rho = entry(props, "mu", mat), entry(props, "rho", mat)
    nu = entry(os.path.join(case, "constant", "transportProperties"), "nu")
    return a, b, k, math.sqrt(mu / rho) * k, 0.5 * nu * k * k


def init(case):
    """0/U: u_theta = V0 phi(r)/max|phi| at the cell centres (0/C, from
    postProcess -func writeCellCentres)."""
    a, b, k, _, _ = mode(case)
    phi = lambda r: j1(k * r) * y1(k * a) - y1(k * r) * j1(k * a)
    scale = V0 / np.abs(phi(np.linspace(a, b, 2001))).max()
    s = open(os.path.join(case, "0", "C")).read()
    i = s.index("internalField")
    j = s.index("(", i)
    n = int(s[i:j].split()[-1])
    C = np.array(re.findall(r"\(([-+0-9.eE]+) ([-+0-9.eE]+) ([-+0-9.eE]+)\)",
                            s[j:])[:n], float)
    if len(C) != n:
        sys.exit("annulusTorsion.py: 0/C holds %d of %d cell centres"
                 % (len(C), n))
    r = np.hypot(C[:, 0], C[:, 1])
    u = np.where((r > a) & (r < b), scale * phi(np.clip(r, a, b)), 0.0)
    path = os.path.join(case, "0", "U")
    t = open(path).read()
    body = "nonuniform List<vector>\n%d\n(\n%s\n)" % (n, "\n".join(
        "(%.10g %.10g 0)" % (-ui * y / ri, ui * x / ri)
        for ui, x, y, ri in zip(u, C[:, 0], C[:, 1], r)))
    t, count = re.subn(r"internalField\s+uniform\s*\([^)]*\)",
                       lambda m: "internalField   " + body, t)
    if count != 1:
        sys.exit("annulusTorsion.py: %s has no uniform internalField to"
                 " replace (run from a fresh 0.orig)" % path)
    open(path, "w").write(t)
    print("0/U: the first torsional mode, k = %.6f 1/m (held radii %.4f,"
          " %.4f m), largest velocity %g m/s, %d cells" % (k, a, b, V0, n))


def probe(case):
    files = glob.glob(os.path.join(case, "postProcessing", "solidProbes",
                                   "*", "displacement.dat"))
    if not files:
        sys.exit("annulusTorsion.py: no postProcessing/solidProbes/*/"
                 "displacement.dat in %s: did isfemFoam run?" % case)
    rows = {}
    for f in sorted(files, key=lambda p: float(p.split(os.sep)[-2])):
        for r in v.read_table(f):
            rows[r[0]] = r
    t = np.array(sorted(rows))
    # azimuthal at (0, 0.75, z): -u_x
    return t, np.array([-rows[x][1] for x in t])


def check(case):
    a, b, k, w0, gamma = mode(case)
    t, s = probe(case)
    dt = float(np.median(np.diff(t)))
    theta = 0.0            # the explicit force: the force of x^n
    run = os.path.join(case, "system", "fvOptions.run")
    if os.path.isfile(run):
        text = open(run).read()
        if "implicitForce" in text:
            m = re.search(r"theta\s+([-+0-9.eE]+)", text)
            theta = float(m.group(1)) if m else 1.0
    T_cont = 2 * math.pi / math.sqrt(w0 * w0 - gamma * gamma)
    z = w0 * dt
    c = 1 + theta * z * z
    tr = 1 + (1 - z * z) / c
    T_ref = 2 * math.pi * dt / math.acos(tr * math.sqrt(c) / 2)
    g_ref = gamma + math.log(c) / (2 * dt)
    print("closed form: k = %.6f 1/m, omega0 = %.6f 1/s, gamma = %.6f 1/s,"
          " period %.6f s; %s, dt = %g s (z = omega0 dt = %.4f): with the"
          " step's own error period %.6f s, decay %.6f 1/s"
          % (k, w0, gamma, T_cont,
             "implicit force, theta %g" % theta if theta > 0
             else "explicit force", dt, z, T_ref, g_ref))
    # first guesses: zero crossings and the largest value
    zc = [t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])
          for i in range(len(s) - 1) if s[i] * s[i + 1] < 0]
    if len(zc) < 3:
        v.condition("zero crossings", len(zc), "at least 3 expected", False)
        v.finish()
    w = math.pi / np.mean(np.diff(zc))
    f = lambda x, A, g, w_, p: A * np.exp(-g * x) * np.sin(w_ * x + p)
    p0 = [np.abs(s).max() * math.exp(1), max(g_ref, 1e-3), w, 0.0]
    (A, g, wf, ph), _ = curve_fit(f, t, s, p0=p0, maxfev=20000)
    rms = math.sqrt(np.mean((f(t, A, g, wf, ph) - s) ** 2))
    v.report("period, continuum [s]", 2 * math.pi / wf, T_cont)
    v.report("decay, continuum [1/s]", g, gamma)
    v.relative("period [s]", 2 * math.pi / wf, T_ref, PERIOD_TOL)
    v.relative("decay [1/s]", g, g_ref, DECAY_TOL)
    v.condition("fit residual / amplitude", rms / abs(A),
                "below 0.02 (one damped mode)", rms / abs(A) < 0.02)
    v.finish()


if __name__ == "__main__":
    if len(sys.argv) < 2 or sys.argv[1] not in ("init", "check"):
        sys.exit("usage: annulusTorsion.py init|check [caseDir]")
    case = sys.argv[2] if len(sys.argv) > 2 else "."
    (init if sys.argv[1] == "init" else check)(case)
