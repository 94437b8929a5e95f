"""The finite-element driver (issue #4, first part): traction patch tests on unstructured tetrahedra
(P1 and P2, a linear-elastic UMAT linked instead of Cam-Clay IX, and Cam-Clay IX in its elastic
range), and a homogeneous triaxial creep box against the material-point driver.

$DRIVER and $DRIVER_ELASTIC are the driver executables (CTest sets them).
"""
import math
from pathlib import Path

import numpy as np
import pytest
from camclay9 import driver_path, read_history, run_driver
from camclay9 import reference as ref

ROOT = Path(__file__).resolve().parents[2]

DRIVER = driver_path(root=ROOT)
DRIVER_ELASTIC = driver_path("driver_elastic", root=ROOT)


def run(exe, scene_text, tmp, name, options=(), ranks=1):
    """The driver `exe` on a scene (DriverError: it failed): its history and stdout."""
    scene = tmp / f"{name}.yaml"
    scene.write_text(scene_text)
    proc = run_driver(scene, tmp / name, options, driver=exe, ranks=ranks, cwd=ROOT, timeout=600)
    return read_history(tmp / name), proc.stdout


BOX = """
scene: fe
mesh: {{geometry: meshes/box.geo, parameters: {{Lx: 2, Ly: 1, Lz: 1.5, size: 0.45}}, order: {order}}}
material: {material}
initial: {initial}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}, {{group: z0, components: [z]}}]
  pressure: [x1, y1, z1]
stages:
{stages}
"""


@pytest.mark.parametrize("order", [1, 2])
def test_patch_linear_elastic_umat(tmp_path, order):
    """Uniform pressures on three faces, rollers on the others: the exact solution is a uniform strain,
    eps = C^-1 sigma with sigma = -diag(px, py, pz); every quadrature point must carry it."""
    E, nu, px, py, pz = 1000.0, 0.25, 3.0, 5.0, 7.0
    h, out = run(DRIVER_ELASTIC, BOX.format(
        order=order, material="{umat: elastic, props: [1000.0, 0.25], nstatv: 0}", initial="{stress: [0, 0, 0, 0, 0, 0]}",
        stages=f"  - {{name: load, duration: 1, pressure: {{x1: {px}, y1: {py}, z1: {pz}}}, steps: {{count: 1}}}}"),
        tmp_path, f"elastic_p{order}")
    s = -np.array([px, py, pz])
    exact = (s - nu * (s.sum() - s)) / E
    got = np.array([h["eps_11"][-1], h["eps_22"][-1], h["eps_33"][-1]])
    print(out.splitlines()[0], f"\nP{order}: strain {got}, exact {exact}, spread {h['eps_spread'][-1]:.2e}")
    assert np.max(np.abs(got - exact)) <= 1e-10 * np.max(np.abs(exact))
    assert h["eps_spread"][-1] <= 1e-10 * np.max(np.abs(exact))


@pytest.mark.parametrize("order", [1, 2])
def test_patch_camclay_elastic_range(tmp_path, order):
    """The same with Cam-Clay IX inside its yield surfaces (pc0 = 500 MPa in both frames), bedding normal
    along x1 (theta = 90: the rollers admit a uniform state only when the material axes are the box
    axes): uniform strain C^-1 (sigma - sigma0) with the transversely isotropic mixture stiffness built
    independently (camclay9.reference, from theory.md §4.2)."""
    n = [1.0, 0.0, 0.0]
    h, _ = run(DRIVER, BOX.format(
        order=order,
        material="{props: woodford, set: {pc0_hard: 500, pc0_soft: 500}, bedding_angle: 90}",
        initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}",
        stages="  - {name: load, duration: 1, pressure: {x1: 38, y1: 41, z1: 50}, steps: {count: 2}}"),
        tmp_path, f"camclay_p{order}")
    props = ref.WOODFORD
    C = 0.5 * ref.stiffness_voigt(*props[1:6], n) + 0.5 * ref.stiffness_voigt(props[13], props[14], props[14], 0, 0, n)
    dsig = -np.array([3.0, 6.0, 15.0, 0, 0, 0])
    exact = np.linalg.solve(C, dsig)
    got = np.array([h[k][-1] for k in ("eps_11", "eps_22", "eps_33", "eps_12", "eps_13", "eps_23")])
    print(f"P{order}: strain {got}\n   exact {exact}, spread {h['eps_spread'][-1]:.2e}")
    assert np.max(np.abs(got - exact)) <= 1e-10 * np.max(np.abs(exact))
    assert h["eps_spread"][-1] <= 1e-10 * np.max(np.abs(exact))


def test_homogeneous_triaxial_creep_matches_the_point(tmp_path):
    """A box with frictionless ends and uniform phi is homogeneous: with the same steps, its axial
    creep must be the material point's to 1e-6 (here: hold 1e6 s, then sigma_d = 40 MPa for 1 h)."""
    steps_hold = "{count: 60, ratio: 1.2}"
    steps_creep = "{count: 40, ratio: 1.15}"
    fe, _ = run(DRIVER, BOX.format(
        order=1, material="{props: woodford, bedding_angle: 0}",
        initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}",
        stages=f"  - {{name: hold, duration: 1.0e6, pressure: {{x1: 35, y1: 35, z1: 35}}, steps: {steps_hold}}}\n"
               f"  - {{name: creep, duration: 3600, load: instant, pressure: {{x1: 35, y1: 35, z1: 75}}, steps: {steps_creep}}}"),
        tmp_path, "box_creep")
    point_scene = f"""
scene: point
material: {{props: woodford, bedding_angle: 0}}
initial: {{stress: [-35, -35, -35, 0, 0, 0]}}
segments:
  - {{name: hold, duration: 1.0e6, steps: {{count: 60, spacing: geometric, ratio: 1.2}},
     control: {{11: {{stress: -35}}, 22: {{stress: -35}}, 33: {{stress: -35}}, others: {{stress: 0}}}}}}
  - {{name: creep, duration: 3600, load: instant, steps: {{count: 40, spacing: geometric, ratio: 1.15}},
     control: {{11: {{stress: -35}}, 22: {{stress: -35}}, 33: {{stress: -75}}, others: {{stress: 0}}}}}}
"""
    pt, _ = run(DRIVER, point_scene, tmp_path, "point")
    fe_rows = np.where(fe["stage"] == 1)[0]
    pt_rows = np.where(pt["stage"] == 1)[0]
    creep_fe = fe["eps_33"][fe_rows] - fe["eps_33"][fe_rows[0]]
    creep_pt = pt["eps_33"][pt_rows] - pt["eps_33"][pt_rows[0]]
    assert len(creep_fe) == len(creep_pt)
    err = np.max(np.abs(creep_fe - creep_pt)) / np.max(np.abs(creep_pt))
    print(f"homogeneous box vs point: creep at 1 h {creep_fe[-1]:.10e} vs {creep_pt[-1]:.10e}, "
          f"largest relative difference {err:.2e}; strain spread {fe['eps_spread'][-1]:.1e}")
    assert err < 1e-6


def test_one_and_two_ranks_agree(tmp_path):
    """The heterogeneous cylinder (phi drawn per cell from its centroid and the seed) on 1 and 2 MPI
    ranks: the same history to 1e-8 (a coarse mesh, hold and 10 min of creep)."""
    text = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    text = text.replace("size: 6.0", "size: 9.0").replace("duration: 36000", "duration: 600")
    hist = {n: run(DRIVER, text, tmp_path, f"ranks{n}", ranks=n)[0] for n in (1, 2)}
    assert len(hist[1]) == len(hist[2])
    for col in ("time", "eps_33", "eps_11", "evp33_soft_median", "evp33_hard_max"):
        a, b = hist[1][col], hist[2][col]
        err = np.max(np.abs(a - b)) / max(np.max(np.abs(a)), 1e-300)
        print(f"{col}: 1 vs 2 ranks, largest relative difference {err:.2e}")
        assert err < 1e-8, col


def test_newton_converges_quadratically(tmp_path):
    """One large viscoplastic step (axial pressure 35 -> 60 MPa in 1000 s, theta = 30, P2): the residual
    sequence of SNES on the consistent tangent falls quadratically, r_{k+1} ~ C r_k^2."""
    import re
    scene = tmp_path / "newton.yaml"
    scene.write_text(BOX.format(
        order=2, material="{props: woodford, bedding_angle: 30}",
        initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}",
        stages="  - {name: load, duration: 1000, pressure: {x1: 35, y1: 35, z1: 60}, steps: {count: 1}}"))
    proc = run_driver(scene, tmp_path / "o", ["-snes_monitor"], driver=DRIVER, cwd=ROOT, timeout=600)
    r = [float(x) for x in re.findall(r"SNES Function norm ([0-9.eE+-]+)", proc.stdout)]
    print("residual sequence:", ", ".join(f"{x:.3e}" for x in r))
    c = [r[k + 1] / r[k] ** 2 for k in range(1, len(r) - 1)]
    # observed order p_k = log(r_{k+1}/r_k) / log(r_k/r_{k-1}): 2 for Newton on the exact Jacobian, 1 for
    # any fixed wrong one. At least two orders are needed (four residuals), else the test cannot fail.
    p = [math.log(r[k + 1] / r[k]) / math.log(r[k] / r[k - 1]) for k in range(1, len(r) - 1)]
    print("r_{k+1} / r_k^2:", ", ".join(f"{x:.2e}" for x in c), "; observed orders:", ", ".join(f"{x:.2f}" for x in p))
    assert 4 <= len(r) <= 6 and r[-1] < 1e-10 * r[0]
    assert min(p) > 1.8 and max(c) / min(c) < 3     # quadratic convergence


def test_fields_for_paraview(tmp_path):
    """fields.h5 + fields.xmf (XDMF3): every DataItem states its Format, every dataset the XDMF names
    exists with the dimensions it states, the displacement is a Vector and the tensors full 3x3 Tensors (9
    components, issue 23), and the last stress field is the applied pressures (its 11 22 33 entries)."""
    import xml.etree.ElementTree as ET
    import h5py
    h, _ = run(DRIVER, BOX.format(
        order=1, material="{props: woodford, set: {pc0_hard: 500, pc0_soft: 500}, bedding_angle: 90}",
        initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}",
        stages="  - {name: load, duration: 1, pressure: {x1: 38, y1: 41, z1: 50}, steps: {count: 2}}"),
        tmp_path, "fields")
    out = tmp_path / "fields"
    tree = ET.parse(out / "fields.xmf")
    assert tree.getroot().get("Version") == "3.0"
    types = {}
    with h5py.File(out / "fields.h5") as f:
        for item in tree.iter("DataItem"):
            assert item.get("Format") == "HDF", item.attrib
            path = item.text.split(":", 1)[1]
            dims = tuple(int(x) for x in item.get("Dimensions").split())
            assert path in f and f[path].shape == dims, (path, dims)
        for att in tree.iter("Attribute"):
            types[att.get("Name")] = att.get("AttributeType")
        stress = f["/fields/stress"][sorted(f["/fields/stress"])[-1]][()]
        times = f["/time"][:, 0]
    assert types == {"displacement": "Vector", "stress": "Tensor", "strain": "Tensor", "evp_hard": "Tensor",
                     "evp_soft": "Tensor", "evp": "Tensor", "pc_hard": "Scalar", "pc_soft": "Scalar", "phi": "Scalar",
                     "error_indicator": "Scalar", "error_indicator_max": "Scalar"}
    assert np.allclose(stress[:, [0, 4, 8]].mean(axis=0), [-38, -41, -50], rtol=1e-10)
    assert [float(t.get("Value")) for t in tree.iter("Time")] == [0.0, 1.0] == list(times)  # start and end of the stage


def test_restart_matches_uninterrupted_run(tmp_path):
    """A run stopped after a checkpoint (-checkpoint_every, -max_steps) and continued with -restart
    gives the uninterrupted history to 1e-10 (here bit for bit), on 2 ranks."""
    text = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/").replace("size: 6.0", "size: 9.0").replace(
        "duration: 36000", "duration: 3600")
    scene = tmp_path / "cyl.yaml"
    scene.write_text(text)

    def go(out, *extra):
        return run_driver(scene, out, extra, driver=DRIVER, ranks=2, cwd=ROOT, timeout=600).stdout

    go(tmp_path / "full")
    assert "stopped after 140 steps" in go(tmp_path / "part", "-checkpoint_every", "20", "-max_steps", "140")
    go(tmp_path / "part", "-restart")
    a, b = read_history(tmp_path / "full"), read_history(tmp_path / "part")
    assert len(a) == len(b)
    for col in ("time", "eps_33", "sig_33", "evp33_soft_mean", "evp33_hard_q3"):
        err = np.max(np.abs(a[col] - b[col])) / np.max(np.abs(a[col]))
        print(f"restart vs uninterrupted, {col}: {err:.1e}")
        assert err <= 1e-10
    assert (tmp_path / "part" / "fields.xmf").read_text().count("<Time") == \
        (tmp_path / "full" / "fields.xmf").read_text().count("<Time")


def test_direct_and_gamg_agree(tmp_path):
    """The default direct solver and GAMG-preconditioned GMRES (rigid-body near null space) give the
    same solution to the solver tolerance (P2, anisotropic, viscoplastic step)."""
    text = BOX.format(order=2, material="{props: woodford, bedding_angle: 90}",
                      initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}",
                      stages="  - {name: load, duration: 100, pressure: {x1: 35, y1: 35, z1: 50}, steps: {count: 2}}")
    res = {}
    for name, opts in (("lu", []), ("gamg", ["-ksp_type", "gmres", "-pc_type", "gamg", "-ksp_rtol", "1e-12"])):
        res[name] = run(DRIVER, text, tmp_path, name, opts)[0]
    err = np.max(np.abs(res["lu"]["eps_33"] - res["gamg"]["eps_33"])) / np.max(np.abs(res["lu"]["eps_33"]))
    print(f"direct vs GAMG: {err:.1e}")
    assert err < 1e-8


def test_pressure_time_functions(tmp_path):
    """Stage pressures as functions of the stage time: P0 exp(k t), a table (linear interpolation) and a
    linear unload; the volume-mean stress follows them exactly (linear-elastic UMAT)."""
    table = tmp_path / "p.csv"
    table.write_text("# seconds, MPa\nt,p\n0,2\n5,6\n10,4\n")
    h, _ = run(DRIVER_ELASTIC, BOX.format(
        order=1, material="{umat: elastic, props: [1000.0, 0.25], nstatv: 0}", initial="{stress: [0, 0, 0, 0, 0, 0]}",
        stages=f"  - {{name: exp, duration: 10, pressure: {{z1: {{exp: {{P0: 1.5, k: 0.1}}}}}}, steps: {{count: 4}}}}\n"
               f"  - {{name: table, duration: 10, pressure: {{z1: {{table: {{file: {table}, time: t, value: p}}}}}}, steps: {{count: 4}}}}\n"
               f"  - {{name: unload, duration: 10, pressure: {{z1: 0}}, steps: {{count: 4}}}}"),
        tmp_path, "functions")
    h = h[h["step"] > 0]  # row 0 is the initial state, before the first stage's load
    t = h["time"]
    expected = np.where(t <= 10, 1.5 * np.exp(0.1 * t), np.where(t <= 20, np.interp(t - 10, [0, 5, 10], [2, 6, 4]),
                                                                  4 * (30 - t) / 10))
    print("sigma_33:", -h["sig_33"], "expected", expected)
    assert np.max(np.abs(-h["sig_33"] - expected)) <= 1e-10 * np.max(expected)


def test_phi_field_rank_independent_and_correlated(tmp_path):
    """phi per cell: the same values on 1 and 2 ranks (a function of centroids and the seed), within
    [min, max]; with a correlation length, neighbouring cells are strongly correlated, without it not."""
    import h5py
    base = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/").replace("size: 6.0", "size: 4.0")
    base = base[:base.index("stages:")] + "stages:\n  - {name: hold, duration: 1, pressure: {top: 35, side: 35}, steps: {count: 1}}\n" + \
        base[base.index("output:"):]

    def phi(text, ranks, name):
        run(DRIVER, text, tmp_path, name, ranks=ranks)
        with h5py.File(tmp_path / name / "fields.h5") as f:
            x = f["/mesh/coordinates"][:][f["/mesh/cells"][:]].mean(axis=1)
            return x, f["/fields/phi"][sorted(f["/fields/phi"])[-1]][()]

    def neighbour_correlation(x, v, radius):
        d = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2)
        i, j = np.where((d > 0) & (d < radius))
        return np.corrcoef(v[i], v[j])[0, 1]

    corr = base.replace("seed: 2021}", "seed: 2021, correlation_length: 8.0}")
    for name, text in (("white", base), ("correlated", corr)):
        x1, p1 = phi(text, 1, name + "1")
        x2, p2 = phi(text, 2, name + "2")
        k1, k2 = np.lexsort(x1.T), np.lexsort(x2.T)
        assert np.max(np.abs(p1[k1] - p2[k2])) < 1e-12, name
        assert p1.min() >= 0.4 and p1.max() <= 0.6
        c = neighbour_correlation(x1, p1, 4.0)
        print(f"{name}: phi mean {p1.mean():.3f}, std {p1.std():.3f}, neighbour correlation {c:.2f}")
        assert (c > 0.7) if name == "correlated" else (abs(c) < 0.2)


def test_traction_equals_pressure(tmp_path):
    """A uniform traction (0, 0, -p) on a face loads it as a pressure p does (Cam-Clay IX, P2,
    viscoplastic): the same history."""
    stages = "  - {name: load, duration: 100, %s, steps: {count: 2}}"
    common = dict(order=2, material="{props: woodford, bedding_angle: 90}",
                  initial="{stress: [-35, -35, -35, 0, 0, 0], pressure: {x1: 35, y1: 35, z1: 35}}")
    hp, _ = run(DRIVER, BOX.format(stages=stages % "pressure: {x1: 35, y1: 35, z1: 50}", **common), tmp_path, "p")
    text = BOX.format(stages=stages % "pressure: {x1: 35, y1: 35, z1: 35}, traction: {z1: [0, 0, -15]}", **common)
    text = text.replace("  pressure: [x1, y1, z1]", "  pressure: [x1, y1, z1]\n  traction: [z1]")
    ht, _ = run(DRIVER, text, tmp_path, "t")
    err = np.max(np.abs(hp["eps_33"] - ht["eps_33"])) / np.max(np.abs(hp["eps_33"]))
    print(f"traction vs pressure: {err:.1e}")
    assert err < 1e-12
