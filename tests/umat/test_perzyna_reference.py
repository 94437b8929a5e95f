"""Perzyna creep at one point under constant stress (issue #2): the UMAT's backward-Euler creep strain
converges at first order in the time step, and the finest run agrees with an independent Radau
integration of the same ODEs (python/camclay9/reference.py, written from theory.md) to 1e-6.

The point is run by the Fortran program creep_point (path in $CREEP_POINT): both frames at -35 MPa,
an elastic jump (DTIME = 0) to diag(-35, -35, -75) MPa, then held for T = 3600 s.
"""
import os
import subprocess

import numpy as np
from camclay9 import reference as ref

THETA_DEG = 30.0
T_END = 3600.0
STEPS = [100, 1000, 10000, 100000]


def run_point(nsteps):
    exe = os.environ.get("CREEP_POINT", "build/tests/umat/creep_point")
    out = subprocess.run([exe, str(THETA_DEG), str(T_END), str(nsteps)], check=True,
                         capture_output=True, text=True, timeout=600).stdout.split()
    return float(out[2]), float(out[3]), float(out[4])


def reference():
    th = np.radians(THETA_DEG)
    sol = ref.creep_mixture(ref.WOODFORD, [np.sin(th), 0.0, np.cos(th)], -35.0 * np.eye(3),
                            np.diag([-35.0, -35.0, -75.0]), [T_END], rtol=1e-10)
    return sol["strain"][-1][2] - sol["strain0"][2], sol["pc_hard"][-1], sol["pc_soft"][-1]


def test_first_order_convergence_to_radau_reference():
    creep_ref, pch_ref, pcs_ref = reference()
    errors = []
    for n in STEPS:
        creep, pch, pcs = run_point(n)
        errors.append(abs(creep - creep_ref) / abs(creep_ref))
        print(f"N = {n:7d}  creep = {creep:.12e}  relative error = {errors[-1]:.3e}  "
              f"pc_hard error = {abs(pch - pch_ref) / pch_ref:.2e}")
    print(f"Radau reference creep strain at {T_END:g} s: {creep_ref:.12e}")
    orders = [np.log10(errors[k] / errors[k + 1]) for k in range(len(errors) - 1)]
    print("observed orders:", ", ".join(f"{p:.3f}" for p in orders))
    # First order in dt: each tenfold refinement divides the error by ten.
    assert all(0.9 < p < 1.1 for p in orders[1:]), orders
    assert errors[-1] < 1e-6, errors[-1]
    assert abs(pch - pch_ref) / pch_ref < 1e-6 and abs(pcs - pcs_ref) / pcs_ref < 1e-6
