#!/usr/bin/env python3
"""Steady laminar flow in a round pipe (R = 1, U_mean = 1), sampled on the
axis at z = 2, 3.5, 5 (developed flow): the centreline velocity and the
pressure drop against the closed forms.

    checkPoiseuille.py                  Newtonian, nu = 1 (Hagen-Poiseuille):
                                        u_c = 2 U_mean, dp/dz = -8 nu U_mean/R^2
    checkPoiseuille.py -powerLaw k n    power law, nu = k gammaDot^(n - 1):
        u(r) = U_mean (3n + 1)/(n + 1) (1 - (r/R)^((n + 1)/n)), so
        u_c = U_mean (3n + 1)/(n + 1) and, from the wall stress
        tau_w = (-dp/dz) R/2 = k gammaDot_w^n with
        gammaDot_w = (3n + 1)/n U_mean/R,
        -dp/dz = 2 k ((3n + 1) U_mean/(n R))^n / R
    (Chhabra & Richardson 2008, Sect. 3.2; docs/references.md). A power-law
    run is also held against the Newtonian values at nu = k, which it must
    miss (the viscosity model acts)."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

R, Umean = 1.0, 1.0
args = sys.argv[1:]
if args and args[0] == "-powerLaw" and len(args) == 3:
    k, n = float(args[1]), float(args[2])
elif not args:
    k, n = 1.0, 1.0
else:
    sys.exit("usage: checkPoiseuille.py [-powerLaw k n]")

d = v.latest_time_dir("postProcessing/axis")
U = v.read_table(os.path.join(d, "axis_U.xy"))   # x y z Ux Uy Uz
p = v.read_table(os.path.join(d, "axis_p.xy"))   # x y z p
z = [r[2] for r in p]
uc = U[1][5]
dp = p[0][3] - p[2][3]
L = z[2] - z[0]

uRef = Umean * (3 * n + 1) / (n + 1)
dpRef = 2 * k * ((3 * n + 1) * Umean / (n * R))**n / R * L
if n == 1:
    print("Poiseuille flow at t = %s (tet mesh), nu = %g" % (os.path.basename(d), k))
else:
    print("Power-law pipe flow at t = %s (tet mesh), k = %g, n = %g"
          % (os.path.basename(d), k, n))
v.relative("centreline u_z (z = 3.5)", uc, uRef, 2.0)
v.relative("pressure drop z = 2..5", dp, dpRef, 2.0)
if n != 1:
    # negative control: the Newtonian closed form (nu = k) must be missed
    # by more than the tolerance
    uN, dpN = 2 * Umean, 8 * k * Umean / R**2 * L
    for name, value, ref in (("centreline u_z", uc, uN),
                             ("pressure drop", dp, dpN)):
        err = 100.0 * (value - ref) / ref
        v.condition("negative control, Newtonian " + name, value,
                    "Newtonian %.6g, differs by %+.3f %%: must be more than"
                    " 2 %%" % (ref, err), abs(err) > 2.0)
v.finish()
