#!/usr/bin/env python3
"""Turek & Hron CSM1 (docs/references.md): static tip displacement of the flag
under gravity: u_y(A) within 2% of -66.10 mm, u_x(A) within 3% of -7.187 mm."""
import os
import sys
sys.path.insert(0, os.path.join(os.environ["ISFEM_PROJECT_DIR"], "tutorials"))
import validation as v  # noqa: E402

t, ux, uy, uz = v.read_table("results/probes.dat")[-1]
print("CSM1 at t = %g s (damped to rest), point A, displacements in mm" % t)
v.relative("u_y(A)", 1e3 * uy, -66.10, 2.0)
v.relative("u_x(A)", 1e3 * ux, -7.187, 3.0)
v.finish()
