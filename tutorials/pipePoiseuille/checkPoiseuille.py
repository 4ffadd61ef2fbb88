#!/usr/bin/env python3
"""Steady Poiseuille flow in a round pipe (R = 1, nu = 1, U_mean = 1):
centreline velocity u_c = 2 U_mean and pressure drop dp/dz = -8 nu U_mean/R^2
(Hagen-Poiseuille), sampled on the axis at z = 2, 3.5, 5 (developed flow)."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

R, nu, Umean = 1.0, 1.0, 1.0
d = v.latest_time_dir("postProcessing/axis")
U = v.read_table(os.path.join(d, "axis_U.xy"))   # x y z Ux Uy Uz
p = v.read_table(os.path.join(d, "axis_p.xy"))   # x y z p
z = [r[2] for r in p]
print("Poiseuille flow at t = %s (tet mesh)" % os.path.basename(d))
v.relative("centreline u_z (z = 3.5)", U[1][5], 2.0 * Umean, 2.0)
v.relative("pressure drop z = 2..5", p[0][3] - p[2][3],
           8.0 * nu * Umean / R**2 * (z[2] - z[0]), 2.0)
v.finish()
