#!/usr/bin/env python3
"""Immersed DFG benchmark 2D-1 (Schaefer & Turek 1996): c_D of the force of
the fluid on the immersed cylinder (postProcessing/cylinder/0/
immersedForcing.dat, written by the immersedForcing fvOption) against the
reference of docs/references.md (2 %); c_L reported; the force and
the fluid's momentum source balance (action and reaction, 1 %)."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

rho, Umean, D, depth = 1.0, 0.2, 0.1, 0.01
rows = v.read_table(os.path.join(
    v.latest_time_dir("postProcessing/cylinder"), "immersedForcing.dat"))
q = 0.5 * rho * Umean**2 * D * depth
t = rows[-1][0]
cd, cl = rows[-1][1] / q, rows[-1][2] / q
imbalance = rows[-1][7]
cd_early = [r[1] / q for r in rows if r[0] <= 0.9 * t][-1]
print("immersed DFG 2D-1 at t = %g s, %d covered cells" % (t, rows[-1][9]))
v.relative("c_D", cd, 5.57953523384, 2.0)
v.report("c_L", cl, 0.010618948146)
v.absolute("action-reaction |F + S|/|F|", imbalance, 0.0, 0.01)
v.absolute("steadiness |dc_D| (last 10%)", abs(cd - cd_early), 0.0, 1e-3)
v.finish()
