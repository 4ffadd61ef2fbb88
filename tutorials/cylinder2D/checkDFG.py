#!/usr/bin/env python3
"""DFG benchmark 2D-1 (Schaefer & Turek 1996): compare c_D, Delta p with the
references of docs/references.md; c_L is reported."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

coeffs = v.read_table(os.path.join(
    v.latest_time_dir("postProcessing/forceCoeffs"), "coefficient.dat"))
t, cd, cl = coeffs[-1][0], coeffs[-1][1], coeffs[-1][3]
probe = v.read_table(os.path.join(
    v.latest_time_dir("postProcessing/pressureFrontBack"), "p"))
dp = probe[-1][1] - probe[-1][2]   # rho = 1: kinematic = static pressure

# Steadiness: c_D change over the last 10% of the run
cd_early = [r[1] for r in coeffs if r[0] <= 0.9 * t][-1]
print("DFG 2D-1 at t = %g s" % t)
v.relative("c_D", cd, 5.57953523384, 1.0)
v.relative("Delta p [Pa]", dp, 0.11752016697, 2.0)
v.report("c_L", cl, 0.010618948146)
v.absolute("steadiness |dc_D| (last 10%)", abs(cd - cd_early), 0.0, 1e-3)
v.finish()
