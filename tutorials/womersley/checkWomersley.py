#!/usr/bin/env python3
"""Womersley flow (Womersley 1955): -dp/dz = G sin(omega t) in a round pipe.
    u(r, t) = Im{ G/(i omega) [1 - J0(i^(3/2) alpha r/R)/J0(i^(3/2) alpha)]
                  e^(i omega t) },   alpha = R sqrt(omega/nu)
Centreline velocity over the last period: amplitude and phase of a least
squares fit a sin(wt) + b cos(wt) + c against the analytic values."""
import cmath
import math
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

R, nu, omega, G = 1.0, 1.0, 16.0, 16.0
alpha = R * math.sqrt(omega / nu)
T = 2 * math.pi / omega


def J0(z, terms=80):
    """Bessel J0 of a complex argument by its power series."""
    s, term = 0j, 1 + 0j
    for k in range(terms):
        if k:
            term *= -(z * z / 4) / (k * k)
        s += term
    return s


C = G / (1j * omega) * (1 - 1 / J0(1j ** 1.5 * alpha))
amp_ref, phase_ref = abs(C), math.degrees(cmath.phase(C))

rows = v.read_table(os.path.join(
    v.latest_time_dir("postProcessing/centreline"), "U"))
tEnd = rows[-1][0]
last = [(r[0], r[3]) for r in rows if r[0] > tEnd - T - 1e-9]


def fit(samples):
    """Least squares a sin(wt) + b cos(wt) + c (normal equations, numpy-free):
    amplitude, phase [deg] and mean."""
    basis = [lambda t: math.sin(omega * t), lambda t: math.cos(omega * t),
             lambda t: 1.0]
    A = [[sum(f(t) * g(t) for t, _ in samples) for g in basis] for f in basis]
    b = [sum(f(t) * u for t, u in samples) for f in basis]
    n = 3
    for i in range(n):       # Gaussian elimination, partial pivoting
        p = max(range(i, n), key=lambda k: abs(A[k][i]))
        A[i], A[p], b[i], b[p] = A[p], A[i], b[p], b[i]
        for k in range(i + 1, n):
            f = A[k][i] / A[i][i]
            for j in range(i, n):
                A[k][j] -= f * A[i][j]
            b[k] -= f * b[i]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (b[i] - sum(A[i][j] * x[j] for j in range(i + 1, n))) / A[i][i]
    a_s, a_c, c = x
    return math.hypot(a_s, a_c), math.degrees(math.atan2(a_c, a_s)), c


amp, phase, mean = fit(last)
# Negative control: the same samples one time step late (a solver whose
# velocity lags the pressure gradient by a step, omega dt = 1.8 deg at 200
# steps per period) must fail the phase tolerance
dt = rows[-1][0] - rows[-2][0]
_, phase_lag, _ = fit([(t + dt, u) for t, u in last])

print("Womersley flow, alpha = %g, last period t = %.4f..%.4f s (%d samples)"
      % (alpha, tEnd - T, tEnd, len(last)))
v.relative("centreline amplitude", amp, amp_ref, 3.0)
PHASE_TOL = 1.5     # deg: below one step's 1.8 deg, so a one-step lag fails
v.absolute("centreline phase [deg]", phase, phase_ref, PHASE_TOL, "deg")
v.condition("negative control: phase one step late", phase_lag,
            "against %.3f +- %g deg: must fail" % (phase_ref, PHASE_TOL),
            abs(phase_lag - phase_ref) > PHASE_TOL)
v.report("mean over the period", mean, 0.0)
v.finish()
