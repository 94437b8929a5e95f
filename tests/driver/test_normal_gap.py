"""The normal gap against Sneddon (issue 26, item 5; docs/contact.md, "The normal gap against γ").

With `gap: normal` (the default) the contact is frictionless at the deformed surface: the gap is measured at the
node's current position and the pressure acts along the face's normal. Against Sneddon's linearised contact
(`gap: vertical`, the same mesh and block, so that the block's stiffening and the mesh's error cancel in the ratio)
the elastic cone's load is then

    P_normal / P_vertical = 1 + A kappa c - (B_C - C_2 kappa^2) c^2 + O(c^3),   c = cot psi, kappa = (1-2nu)/(2(1-nu)),

A = 0.8253 (derived: 0.6282 from the radial displacement of Sneddon's surface, Hay, Bolshakov & Pharr's term, and
0.1971 from the vertical displacement of the face-normal pressure's shear), B_C = 0.3655 (derived: that shear's
radial displacement), C_2 = 0.33 fitted once to this code's own runs (bench/normal_gap_bench.py, psi >= 65 deg).
The test fails if the measured ratio leaves these values:
- 70.3 deg / nu 0.3 and 65 deg / nu 0.45: the second-order value within 4e-3. Where each part comes from: A and B_C
  derived (independent of this code); the fitted C_2 term is C_2 kappa^2 c^2 = 3.4e-3 at 70.3/0.3 (about the
  tolerance: there the check is partly a regression on the fit) and 6e-4 at 65/0.45 (independent to within it).
- 75 deg, between nu = 0 and 0.45: the first-order slope (A, not Hay's 0.628 alone), within 5 %; B_C cancels and
  the C_2 term is 4 % of the difference: independent to within the tolerance.
- 45 deg / nu 0.3: 0.9006 of the vertical gap's load, within 5e-3. A regression value [reg]: measured by this
  code (bench/normal_gap_bench.py on its 2000 a block; second order says 0.89, c = 1 being outside its range).
The driver runs with a timeout (a broken gap once hung a run for 20 min of CPU).
"""
import math
from pathlib import Path

import numpy as np
import pytest
from camclay9 import read_history, run_driver
from camclay9.normal_gap import A, A_R, QUICK, kappa, scene, theory

ROOT = Path(__file__).resolve().parents[2]



def load_ratio(psi, nu, gap, tmp):
    """Mean P / P_Sneddon over the steps from 0.45 h to h, on the benchmark's quick block (400 x 200, P1)."""
    d = tmp / f"{gap}_{psi}_{nu}"
    d.mkdir()
    (d / "scene.yaml").write_text(scene(psi, nu, gap, QUICK, ROOT))
    run_driver(d / "scene.yaml", d / "out", name="driver_elastic", root=ROOT, timeout=300)  # DriverError: failed
    h = read_history(d / "out", need=("load", "depth"))
    rows = h["depth"] > 0.45 * math.pi / 2 / math.tan(math.radians(psi))
    sneddon = 2 / math.pi * 1000 / (1 - nu * nu) * math.tan(math.radians(psi)) * h["depth"][rows] ** 2
    return h["load"][rows] / sneddon


def ratio(psi, nu, tmp):
    return float(np.mean(load_ratio(psi, nu, "normal", tmp) / load_ratio(psi, nu, "vertical", tmp)))


@pytest.mark.parametrize("psi,nu", [(70.3, 0.3), (65.0, 0.45)])
def test_ratio_is_the_second_order_explanation(tmp_path, psi, nu):
    """70.3 deg / 0.3: 1.040 (Hay's gamma: 1.051 simple, 1.067 full; the first order alone 1.084); 65 deg / 0.45: 0.959
    (gamma 1.021 / 1.027). The second-order value is within 0.3 % of the large-block runs from 65 deg on."""
    r = ratio(psi, nu, tmp_path)
    print(f"psi {psi}, nu {nu}: normal / vertical = {r:.4f}; explained {theory(psi, nu):.4f}; first order "
          f"{theory(psi, nu, order=1):.4f}")
    assert r == pytest.approx(theory(psi, nu), abs=4e-3)


def test_first_order_slope_in_nu(tmp_path):
    """At 75 deg the c^2 term B_C cancels between two Poisson's ratios: the difference is A c (kappa_0 - kappa_1) plus
    a C_2 term of 4 % of it (measured: 2.7 % above both on the large block, the c^3 terms); with Hay's first-order term alone (0.628) it would be 24 % smaller."""
    psi, c = 75.0, 1 / math.tan(math.radians(75.0))
    d = ratio(psi, 0.0, tmp_path) - ratio(psi, 0.45, tmp_path)
    expect = theory(psi, 0.0) - theory(psi, 0.45)
    print(f"75 deg: ratio(nu 0) - ratio(nu 0.45) = {d:.4f}; explained {expect:.4f}; first order {A * c * (kappa(0) - kappa(0.45)):.4f}; "
          f"Hay's term alone {A_R * c * (kappa(0) - kappa(0.45)):.4f}")
    assert d == pytest.approx(expect, rel=0.05)


def test_sharp_cone_is_below_sneddon(tmp_path):
    """45 deg / 0.3: the face-normal pressure's shear moves the surface outward where the cone is higher, a c^2 effect
    larger than the first-order stiffening at c = 1: 0.901 of Sneddon's load on the large block (second order 0.89).
    [reg]: 0.9006 is this code's own measurement (bench/normal_gap_bench.py), not an independent value."""
    r = ratio(45.0, 0.3, tmp_path)
    print(f"45 deg, nu 0.3: normal / vertical = {r:.4f}")
    assert r == pytest.approx(0.9006, abs=5e-3)
