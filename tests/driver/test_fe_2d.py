"""2D kinematics of the FE driver (issue #4): patch tests in plane strain and axisymmetry (P1, P2), and
the Lame thick-walled cylinder under internal and external pressure against its closed form, with the
L2 error of P1 falling at second order under refinement."""
from pathlib import Path

import h5py
import numpy as np
import pytest
from camclay9 import read_history, run_driver

ROOT = Path(__file__).resolve().parents[2]
E, NU = 1000.0, 0.3
MATERIAL = "{umat: elastic, props: [1000.0, 0.3], nstatv: 0}"


def run(text, out):
    scene = out.with_suffix(".yaml")
    scene.write_text(text)
    run_driver(scene, out, name="driver_elastic", root=ROOT, cwd=ROOT, timeout=600)  # DriverError: it failed
    return read_history(out)


def compliance(s):
    """Isotropic strains (engineering shear) of the stresses s = (11, 22, 33, 12)."""
    tr = s[0] + s[1] + s[2]
    e = [((1 + NU) * s[k] - NU * tr) / E for k in range(3)]
    return np.array(e + [2 * (1 + NU) * s[3] / E])


@pytest.mark.parametrize("kin", ["plane_strain", "axisymmetric"])
@pytest.mark.parametrize("order", [1, 2])
def test_patch_2d(tmp_path, kin, order):
    """Pressures px on x1 and py on y1, rollers on x0 and y0 (x0 is the axis r = 0 in axisymmetry):
    the exact strain is uniform; plane strain: sigma_33 = nu (sigma_11 + sigma_22); axisymmetric:
    sigma_33 (hoop) = sigma_11 (radial)."""
    px, py = 3.0, 5.0
    h = run(f"""scene: fe
mesh: {{geometry: meshes/rectangle.geo, parameters: {{Lx: 2, Ly: 1, size: 0.3}}, order: {order}, kinematics: {kin}}}
material: {MATERIAL}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}]
  pressure: [x1, y1]
stages:
  - {{name: load, duration: 1, pressure: {{x1: {px}, y1: {py}}}, steps: {{count: 1}}}}
""", tmp_path / f"{kin}{order}")
    s33 = NU * (-px - py) if kin == "plane_strain" else -px
    exact = compliance([-px, -py, s33, 0.0])
    if kin == "plane_strain":
        exact[2] = 0.0
    got = np.array([h["eps_11"][-1], h["eps_22"][-1], h["eps_33"][-1], h["eps_12"][-1]])
    print(f"{kin} P{order}: strain {got}, exact {exact}, spread {h['eps_spread'][-1]:.1e}")
    assert np.max(np.abs(got - exact)) <= 1e-10 * np.max(np.abs(exact))
    assert h["eps_spread"][-1] <= 1e-10 * np.max(np.abs(exact))


RI, RO, PI_, PO = 1.0, 2.0, 10.0, 2.0


def lame_ur(r):
    """Radial displacement of the thick-walled cylinder in plane strain (eps_zz = 0)."""
    A = (PI_ * RI**2 - PO * RO**2) / (RO**2 - RI**2)
    B = (PI_ - PO) * RI**2 * RO**2 / (RO**2 - RI**2)
    return (1 + NU) / E * ((1 - 2 * NU) * A * r + B / r)


def lame(tmp_path, kin, order, size):
    if kin == "plane_strain":
        text = f"""scene: fe
mesh: {{geometry: meshes/annulus.geo, parameters: {{ri: {RI}, ro: {RO}, size: {size}}}, order: {order}, kinematics: plane_strain}}
material: {MATERIAL}
boundary:
  fixed: [{{group: xaxis, components: [y]}}, {{group: yaxis, components: [x]}}]
  pressure: [inner, outer]
stages:
  - {{name: load, duration: 1, pressure: {{inner: {PI_}, outer: {PO}}}, steps: {{count: 1}}}}
"""
    else:
        text = f"""scene: fe
mesh: {{geometry: meshes/rectangle.geo, parameters: {{X0: {RI}, Lx: {RO - RI}, Ly: 0.5, size: {size}}}, order: {order}, kinematics: axisymmetric}}
material: {MATERIAL}
boundary:
  fixed: [{{group: y0, components: [y]}}, {{group: y1, components: [y]}}]
  pressure: [x0, x1]
stages:
  - {{name: load, duration: 1, pressure: {{x0: {PI_}, x1: {PO}}}, steps: {{count: 1}}}}
"""
    out = tmp_path / f"lame_{kin}_{order}_{size}"
    run(text, out)
    with h5py.File(out / "fields.h5") as f:
        x = f["/mesh/coordinates"][:]
        last = sorted(f["/fields/displacement"])[-1]
        u = f["/fields/displacement"][last][:, :2]      # 2D: the third component is the zero padding
        cells = f["/mesh/cells"][:]
    r = np.hypot(x[:, 0], x[:, 1]) if kin == "plane_strain" else x[:, 0]
    ur = (u[:, 0] * x[:, 0] + u[:, 1] * x[:, 1]) / r if kin == "plane_strain" else u[:, 0]
    vertex_err = np.max(np.abs(ur - lame_ur(r))) / np.max(np.abs(lame_ur(r)))
    # L2 norm of u - u_h over the section, edge-midpoint rule on each triangle (P1: u_h linear);
    # the exact field is u = u_r(r) e_r (and u_z = 0).
    num = den = 0.0
    for tri in cells:
        p = x[tri]
        d1, d2 = p[1] - p[0], p[2] - p[0]
        area = 0.5 * abs(d1[0] * d2[1] - d1[1] * d2[0])
        for i, j in ((0, 1), (1, 2), (2, 0)):
            m = 0.5 * (p[i] + p[j])
            uh = 0.5 * (u[tri[i]] + u[tri[j]])
            rm = np.hypot(*m) if kin == "plane_strain" else m[0]
            ue = lame_ur(rm) * (m / rm if kin == "plane_strain" else np.array([1.0, 0.0]))
            w = area / 3 * (2 * np.pi * m[0] if kin == "axisymmetric" else 1.0)
            num += w * np.sum((uh - ue) ** 2)
            den += w * np.sum(ue ** 2)
    return vertex_err, np.sqrt(num / den)


@pytest.mark.parametrize("kin", ["plane_strain", "axisymmetric"])
def test_lame_cylinder(tmp_path, kin):
    sizes = [0.2, 0.1, 0.05] if kin == "plane_strain" else [0.1, 0.05, 0.025]
    res = {order: [lame(tmp_path, kin, order, s) for s in sizes] for order in (1, 2)}
    for order in (1, 2):
        print(f"{kin} P{order}: vertex error of u_r " + ", ".join(f"{v:.2e}" for v, _ in res[order]))
    l2 = [e for _, e in res[1]]
    rates = [np.log2(l2[k] / l2[k + 1]) for k in range(len(l2) - 1)]
    print(f"{kin} P1: L2 error " + ", ".join(f"{e:.2e}" for e in l2) + "; rates " + ", ".join(f"{r:.2f}" for r in rates))
    assert res[1][-1][0] < 5e-3 and res[2][-1][0] < 5e-3        # within 0.5 % at the finest test mesh
    assert res[2][-1][0] < res[1][-1][0]                        # P2 is more accurate than P1
    assert all(1.7 < r < 2.3 for r in rates), rates             # second-order L2 convergence of P1
    if kin == "axisymmetric":                                   # exact geometry: P2 converges faster
        v2 = [v for v, _ in res[2]]
        r2 = np.log2(v2[-2] / v2[-1])
        print(f"axisymmetric P2: vertex-error rate {r2:.2f}")
        assert r2 > 2.5
