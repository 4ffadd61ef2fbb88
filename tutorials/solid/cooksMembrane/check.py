#!/usr/bin/env python3
"""Cook's membrane (docs/references.md): tip deflection of the selective FS/NS-FEM
within 3% of the converged 6.89 mm; FEM-T4 on the same mesh below 75% of it
(volumetric locking, which the selective scheme removes)."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

ref = 6.89
sel = v.read_table("results/probes.dat")[-1][2]
fem = v.read_table("resultsFEM-T4/probes.dat")[-1][2]
print("Cook's membrane, tip (48, 60) vertical displacement [mm]")
v.relative("selective FS/NS-FEM u_y", sel, ref, 3.0)
v.condition("FEM-T4 u_y", fem, "= %.1f %% of the reference (locking: below 75 %%)"
            % (100 * fem / ref), fem < 0.75 * ref)
v.finish()
