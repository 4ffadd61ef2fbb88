#!/usr/bin/env python3
"""Modal model of one coupled IS-FEM time step (fv::immersedForcing).

A design tool, not part of the solver: it predicts whether a way of
coupling the sub-cycled explicit solid to the fluid is stable, before it is
built. Measured on the Turek-Hron flag (immersedForcing.H): the coupling as
built grows 1.5-2 times per step in a period-2 mode; this model gives 1.4-1.5
for it.

Model (unit-mass dry modes of the solid, frequencies w, time step dt = 1):
  solid   the step integrated exactly under a load held over the step, as
          the sub-cycled solid does: (I + Ma) x'' + K x = g, g constant;
  fluid   sees s = (x1 - x0)/dt + theta dt/2 * F  (the mean velocity, plus
          theta times the coupling force's share of the end velocity) and
          answers F = -(A + S)/dt * (c0 s + c1 s_old + c2 s_oldold),
          A symmetric positive (added mass), S skew (the discrete
          operator's non-symmetric part), c the BDF2 (or Euler) weights;
  coupling converged (the fixed point of the coupling iterations), with
          g = F + Ma * correction, the correction one of
            none : no added mass in the solid (Ma = 0),
            mean : Ma (vbar^{n+1} - vbar^n)/dt, the step-mean velocities
                   (the scheme as built, fv::immersedForcing::fluidForce),
            end  : Ma (v^{n+1} - v^n)/dt, the end velocities.
The largest |eigenvalue| of the step's transfer matrix is the growth per
step; 1.0 is neutral. Random modes and operators, the worst of the trials.

Run: python3 couplingModel.py   (numpy and scipy: Debian's python3-numpy,
python3-scipy). Prints the table in immersedForcing.H.
"""

import numpy as np
from scipy.linalg import expm


def growth(w, A, Ma, S, theta, correction, c=(1.5, -2.0, 0.5), dt=1.0):
    n = len(w)
    I = np.eye(n)
    Aeff = A + S
    Px, Pv, Pg, Qx, Qv, Qg = solidPropagator(w, dt, I + Ma)

    # state: x, v, s_old, s_oldold, vbar_old
    T = np.zeros((5*n, 5*n))
    for j in range(5*n):
        e = np.zeros(5*n)
        e[j] = 1
        x0, v0, so, soo, vbo = np.split(e, 5)

        def residual(g):
            x1 = Px @ x0 + Pv @ v0 + Pg @ g
            v1 = Qx @ x0 + Qv @ v0 + Qg @ g
            vb = (x1 - x0)/dt
            F = np.linalg.solve(
                I + Aeff*c[0]*theta/2,
                -Aeff/dt @ (c[0]*vb + c[1]*so + c[2]*soo))
            s = vb + theta*dt/2*F
            if correction == 'mean':
                corr = Ma @ (vb - vbo)/dt
            elif correction == 'end':
                corr = Ma @ (v1 - v0)/dt
            else:
                corr = 0*g
            return g - F - corr, x1, v1, s, vb

        r0 = residual(np.zeros(n))[0]
        J = np.column_stack([residual(I[k])[0] - r0 for k in range(n)])
        g = np.linalg.solve(J, -r0)
        _, x1, v1, s, vb = residual(g)
        T[:, j] = np.concatenate([x1, v1, s, so, vb])
    return max(abs(np.linalg.eigvals(T)))


def solidPropagator(w, dt=1.0, M=None):
    """Exact step of the modes (dry frequencies w, unit mass, or mass
    matrix M) under a held load g: x1 = Px x0 + Pv v0 + Pg g,
    v1 = Qx x0 + Qv v0 + Qg g"""
    n = len(w)
    I = np.eye(n)
    Minv = I if M is None else np.linalg.inv(M)
    L = np.zeros((3*n, 3*n))
    L[:n, n:2*n] = I
    L[n:2*n, :n] = -Minv @ np.diag(w**2)
    L[n:2*n, 2*n:] = Minv
    E = expm(L*dt)
    return [E[:n, :n], E[:n, n:2*n], E[:n, 2*n:],
            E[n:2*n, :n], E[n:2*n, n:2*n], E[n:2*n, 2*n:]]


def randomOperators(mu, skew, trials, n, seed):
    """Random dry frequencies w, added mass A (norm mu), a lumped guess of
    its diagonal for the solid's added mass, and a skew part of relative
    size skew"""
    rng = np.random.default_rng(seed)
    for _ in range(trials):
        w = np.exp(rng.uniform(np.log(0.05), np.log(30), n))
        Q = rng.standard_normal((n, n))
        A = Q @ Q.T
        A *= mu/np.linalg.norm(A, 2)
        Ma = np.diag(np.diag(A))*np.exp(rng.uniform(-0.5, 0.5, n))
        Sk = rng.standard_normal((n, n))
        Sk = (Sk - Sk.T)*skew*np.linalg.norm(A)/np.linalg.norm(Sk)
        yield w, A, Ma, Sk


def worst(correction, theta, skew):
    return max(
        growth(w, A, 0*Ma if correction == 'none' else Ma, Sk, theta,
               correction)
        for w, A, Ma, Sk in randomOperators(100, skew, 60, 5, 2))


if __name__ == '__main__':
    print('added mass 100 x the solid, BDF2 fluid, dry modes w dt 0.05-30')
    print('%-6s %-6s %12s %12s' % ('Ma', 'theta', 'skew 0', 'skew 5 %'))
    for correction in ('none', 'mean', 'end'):
        for theta in (0, 1):
            print('%-6s %-6g %12.4f %12.4f' % (
                correction, theta,
                worst(correction, theta, 0), worst(correction, theta, 0.05)))
