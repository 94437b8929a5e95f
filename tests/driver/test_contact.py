"""Rigid-indenter contact (issue #5), on a linear-elastic UMAT (E = 1000, nu = 0.3) where closed forms
exist: Sneddon's cone, Hertz's sphere, the flat punch, each on a large axisymmetric block graded toward
the tip, with the error falling under refinement; at every converged step of a load-hold-unload run the
supports' reaction (element forces on the fixed components) equal to the load, the gaps of the surface
recomputed from the written fields against the analytic cone (no penetration), the release to zero depth and
an empty active set, 1 vs 2 ranks, direct vs field-split solvers, 3D Berkovich vs its equivalent cone (a regression check),
a Cam-Clay IX indentation whose creep scales with t/eta, and bad indenter input."""
import math
import re
from pathlib import Path

import numpy as np
import pytest
from camclay9 import read_history, run_driver

ROOT = Path(__file__).resolve().parents[2]
E, NU = 1000.0, 0.3
ESTAR = E / (1 - NU**2)
ELASTIC = "{umat: elastic, props: [1000.0, 0.3], nstatv: 0}"
ROLLERS = "[{group: bottom, components: [x, y]}, {group: left, components: [x]}, {group: right, components: [x]}]"


def run(text, out, exe="driver_elastic", args=(), np_=1, check=True):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    proc = run_driver(scene, out, args, name=exe, root=ROOT, ranks=np_, cwd=ROOT, timeout=600, check=check)
    return read_history(out) if check else proc  # check: DriverError when it fails


def tangent_checks(text, out, exe="driver_elastic"):
    """Run a scene with -indent_check_tangent: the relative differences |J d - FD| / |J d| of the whole system at
    every Newton iterate, and the driver's output."""
    proc = run(text, out, exe=exe, args=["-indent_check_tangent"], check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return [float(m) for m in re.findall(r"whole system\): \|J d - FD\| / \|J d\| = ([0-9.eE+-]+)", proc.stdout)], proc.stdout


def axi_scene(indenter, stages, W=40, H=20, h_tip=0.01, h_far=2, r_fine=0.5, r_contact=1.0, x_mark=0):
    return f"""scene: fe
mesh:
  geometry: meshes/indent_block2d.geo
  parameters: {{W: {W}, H: {H}, half: 1, h_tip: {h_tip}, h_far: {h_far}, r_fine: {r_fine}, r_contact: {r_contact}, x_mark: {x_mark}}}
  kinematics: axisymmetric
material: {ELASTIC}
boundary:
  fixed: {ROLLERS}
indenter: {indenter}
stages:
{stages}
"""


def cube_scene(h_tip, h_far, stages):
    """The elastic Berkovich half model (mirror plane x = 0) on meshes/indent_cube.geo, rollers on the sides."""
    return f"""scene: fe
mesh:
  geometry: meshes/indent_cube.geo
  parameters: {{L: 2, half: 1, h_tip: {h_tip}, h_far: {h_far}, r_fine: 0.4, r_contact: 0.6}}
material: {ELASTIC}
boundary:
  fixed: [{{group: bottom, components: [x, y, z]}}, {{group: x0, components: [x]}}, {{group: x1, components: [x]}},
          {{group: y0, components: [y]}}, {{group: y1, components: [y]}}]
indenter: {{shape: berkovich, half_angle: 65.27, contact: contact}}
stages:
{stages}
"""


PUSH = "  - {name: push, duration: 1, indenter: {depth: %g}, steps: {count: 2}}"
PSI = math.radians(70.3)


def sneddon(h):
    """Sneddon (1965): a rigid cone of half-angle psi on an elastic half-space, P = (2/pi) E* tan(psi) h^2."""
    return 2 / math.pi * ESTAR * math.tan(PSI) * h**2


def test_sneddon_cone(tmp_path):
    """Sneddon's linearised contact is the vertical gap at the reference position: within 2 % at the test
    mesh, and closer on the finer one. With the gap normal to the cone (the default) the response is
    stiffer by the radial-displacement correction of Hay, Bolshakov & Pharr (J. Mater. Res. 1999),
    gamma ~ 1 + (1 - 2 nu) / (4 (1 - nu) tan psi) = 1.051 here."""
    err = {}
    for h_tip in (0.02, 0.01):
        hist = run(axi_scene("{shape: cone, half_angle: 70.3, contact: contact, gap: vertical}", PUSH % 0.1, h_tip=h_tip),
                   tmp_path / f"v{h_tip}")
        err[h_tip] = hist["load"][-1] / sneddon(hist["depth"][-1]) - 1
        print(f"cone, vertical gap, h_tip {h_tip}: P = {hist['load'][-1]:.5g}, Sneddon {sneddon(0.1):.5g}, error {err[h_tip]:+.2%}")
    assert abs(err[0.01]) < 0.02 and abs(err[0.01]) < abs(err[0.02])
    hist = run(axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", PUSH % 0.1), tmp_path / "normal")
    check_invariants(hist)
    g = gaps_from_fields(tmp_path / "normal", hist["depth"][-1], PSI)
    print(f"cone, normal gap: smallest vertical gap of the top surface from the fields {g.min():+.3e} "
          f"(of {np.sum(g < 1e-9 * 0.1)} nodes in contact)")
    assert g.min() >= -1e-8 * 0.1 and np.sum(g < 1e-6 * 0.1) >= 3   # no penetration, and nodes in contact
    gamma = 1 + (1 - 2 * NU) / (4 * (1 - NU) * math.tan(PSI))
    ratio = hist["load"][-1] / sneddon(0.1)
    print(f"cone, normal gap: P / Sneddon = {ratio:.4f}; Hay et al. gamma = {gamma:.4f}")
    assert abs(ratio - gamma) < 0.01


def test_hertz_sphere(tmp_path):
    """Hertz: P = (4/3) E* sqrt(R) h^(3/2) for a << R (R = 1, h = 0.01: a = 0.1), within 2 %. The error here is
    the finite block's (the mesh is fine enough): it falls as the block grows (40 and 160 contact radii)."""
    err = {}
    for W in (20, 80):
        hist = run(axi_scene("{shape: sphere, radius: 1, contact: contact, gap: vertical}", PUSH % 0.01, W=W, H=W / 2,
                             h_tip=0.008, h_far=W / 20, r_fine=0.2, r_contact=0.3), tmp_path / f"s{W}")
        P = 4 / 3 * ESTAR * hist["depth"][-1] ** 1.5
        err[W] = hist["load"][-1] / P - 1
        print(f"sphere, block {W} x {W / 2}: P = {hist['load'][-1]:.5g}, Hertz {P:.5g}, error {err[W]:+.2%}")
    assert abs(err[20]) < 0.02 and abs(err[80]) < 0.5 * abs(err[20])


def test_flat_punch(tmp_path):
    """Boussinesq's flat punch: stiffness P/h = 2 a E* (a = 0.1, a node on the rim), within 2 %; the edge is
    singular, so the error falls slowly (about as h^(1/2))."""
    err = {}
    for h_tip in (0.004, 0.002):
        hist = run(axi_scene("{shape: flat_punch, radius: 0.1, contact: contact}", PUSH % 0.001, W=20, H=10, h_tip=h_tip,
                             h_far=1, r_fine=0.2, r_contact=0.3, x_mark=0.1), tmp_path / f"p{h_tip}")
        err[h_tip] = hist["load"][-1] / hist["depth"][-1] / (2 * 0.1 * ESTAR) - 1
        print(f"flat punch, h_tip {h_tip}: stiffness error {err[h_tip]:+.2%}")
    assert abs(err[0.002]) < 0.02 and abs(err[0.002]) < abs(err[0.004])


LHU = """  - {name: load, duration: 100, indenter: {load: {exp: {P0: 5, k: 0.1}}, until: {depth: 0.1}}, steps: {count: 10}}
  - {name: hold, duration: 10, indenter: {load: hold}, steps: {count: 2}}
  - {name: unload, duration: 2, indenter: {load: 0}, steps: {count: 4}}"""


def check_invariants(hist, tol=1e-10):
    """Every converged step, an independent balance: the supports' vertical reaction (from the element
    forces on the fixed components, not from the multipliers) equals the indenter load, relative to the
    largest load (equilibrium of the whole block; the rollers on the sides carry no vertical force)."""
    pmax = hist["load"].max()
    assert np.max(np.abs(hist["reaction_y"] - hist["load"])) <= tol * pmax


def gaps_from_fields(run, depth, psi):
    """The gaps of the top surface's nodes to the rigid cone (apex on the axis at the surface's height minus
    the depth, half-angle psi) recomputed from the written fields (mesh and displacement at the last output),
    against the analytic cone above the block: (H - depth + r cot psi) - y_node, measured vertically."""
    import h5py
    with h5py.File(run / "fields.h5", "r") as f:
        X = f["/mesh/coordinates"][()]
        k = sorted(f["/fields/displacement"].keys())[-1]
        u = f[f"/fields/displacement/{k}"][()][:, :2]
    H = X[:, 1].max()
    top = np.abs(X[:, 1] - H) < 1e-12 * np.ptp(X[:, 1])
    x = X[top] + u[top]
    return (H - depth + x[:, 0] / math.tan(psi)) - x[:, 1]


def test_load_hold_unload_elastic(tmp_path):
    """Force control: P0 exp(k t) until h = 0.1 (the step lands on it), hold, unload to zero: the invariants at
    every step; the elastic block returns to zero depth with an empty active set; 2 ranks give the same, and
    so does a run stopped after a checkpoint and restarted."""
    scene = axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=20, H=10, h_tip=0.02, h_far=1)
    hist = run(scene, tmp_path / "lhu")
    check_invariants(hist)
    load = hist[hist["stage_name"] == "load"]
    assert abs(load["depth"][-1] - 0.1) <= 1e-5 * 0.1, "the load stage ends on the target depth"
    hold = hist[hist["stage_name"] == "hold"]
    assert np.ptp(hold["depth"]) < 1e-9, "an elastic block does not creep"
    last = hist[-1]
    print(f"load-hold-unload: {len(hist) - 1} steps, max load {hist['load'].max():.4g}, final depth {last['depth']:.2e}, "
          f"active {last['active_nodes']}")
    assert last["load"] == 0 and last["active_nodes"] == 0 and abs(last["depth"]) < 1e-10
    par = run(scene, tmp_path / "lhu2", np_=2)
    assert len(par) == len(hist)
    assert np.max(np.abs(par["depth"] - hist["depth"])) < 1e-10
    # stopped after 7 steps with a checkpoint every 3, then restarted: the same history
    run(scene, tmp_path / "restart", args=["-checkpoint_every", "3", "-max_steps", "7"])
    again = run(scene, tmp_path / "restart", args=["-restart"])
    assert len(again) == len(hist) and np.max(np.abs(again["depth"] - hist["depth"])) < 1e-12


def test_direct_and_fieldsplit_agree(tmp_path):
    """The MatNest solved by MUMPS after conversion and by the Schur field split (GAMG on u) give the same
    steps to the solver tolerance."""
    scene = axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=10, H=5, h_tip=0.04, h_far=1)
    a = run(scene, tmp_path / "direct")
    b = run(scene, tmp_path / "split", args=["-indent_solver", "fieldsplit"])
    diff = np.max(np.abs(a["depth"] - b["depth"])) / a["depth"].max()
    print(f"direct vs fieldsplit: {len(a) - 1} steps each, depth difference {diff:.1e} (relative)")
    assert len(a) == len(b) and diff < 1e-8


def gamg_setups(proc):
    """PETSc's count of GAMG set-ups (-log_view's event PCSetUp_GAMG+) and the path the driver's summary line names."""
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr
    count = re.search(r"^PCSetUp_GAMG\+\s+(\d+)", proc.stdout, re.M)
    summary = re.search(r"linear solves [0-9.]+ s \((\w+), \d+ Krylov iterations, \d+ factorisations\)", proc.stdout)
    assert count and summary, proc.stdout[-3000:]
    return int(count.group(1)), summary.group(1)


def test_fieldsplit_keeps_its_hierarchy_and_auto_chooses_by_size(tmp_path):
    """The field split keeps its GAMG hierarchy across Newton iterations and steps (indent_solver.c, solve_split): PETSc
    itself counts fewer GAMG set-ups than the run that sets it up at every iteration (-indent_refactor_its 0), with the
    same history to the solver tolerance; with the rule off, one set-up and one more after each checkpoint; a restart
    from a checkpoint repeats the history. -indent_solver auto (the default) takes the field split in 3D above
    -indent_fieldsplit_above unknowns and the direct path below it and in 2D at any size."""
    scene = axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=10, H=5, h_tip=0.04, h_far=1)
    log = ["-log_view"]
    kept = run(scene, tmp_path / "kept", args=["-indent_solver", "fieldsplit", *log], check=False)
    fresh = run(scene, tmp_path / "fresh", args=["-indent_solver", "fieldsplit", "-indent_refactor_its", "0", *log], check=False)
    axi0 = run(scene, tmp_path / "axi0", args=["-indent_fieldsplit_above", "0"], check=False)
    cube = cube_scene(0.1, 0.5, PUSH % 0.1)
    auto = run(cube, tmp_path / "auto", check=False)
    above = run(cube, tmp_path / "above", args=["-indent_fieldsplit_above", "0"], check=False)
    for p in (kept, fresh, axi0, auto, above):
        assert p.returncode == 0, p.stdout + p.stderr
    (nk, sk), (nf, sf) = gamg_setups(kept), gamg_setups(fresh)
    newton = int(re.search(r"(\d+) Newton iterations", fresh.stdout).group(1))
    hk, hf = read_history(tmp_path / "kept"), read_history(tmp_path / "fresh")
    diff = np.max(np.abs(hk["depth"] - hf["depth"])) / hf["depth"].max()
    print(f"GAMG set-ups: kept {nk}, fresh {nf} ({newton} Newton iterations); depth difference {diff:.1e}")
    assert sk == sf == "fieldsplit" and nf == newton and nk < nf / 3 and diff < 1e-8
    # the rule's own count, known from its definition: with the rule off (-indent_refactor_its 1e6) one set-up, plus one
    # after each checkpoint that a step follows (every 3rd step of the run's steps)
    split, never = ["-indent_solver", "fieldsplit"], ["-indent_refactor_its", "1000000"]
    once = run(scene, tmp_path / "never", args=[*split, *never, *log], check=False)
    ck = run(scene, tmp_path / "never_ck", args=[*split, *never, "-checkpoint_every", "3", *log], check=False)
    steps = len(read_history(tmp_path / "never_ck")) - 1
    assert gamg_setups(once)[0] == 1 and gamg_setups(ck)[0] == 1 + (steps - 1) // 3, (gamg_setups(once), gamg_setups(ck), steps)
    # stopped after a checkpoint and restarted on the field split: the uninterrupted history to 1e-12
    run(scene, tmp_path / "restart", args=[*split, "-checkpoint_every", "3", "-max_steps", "7"])
    again = run(scene, tmp_path / "restart", args=[*split, "-restart"])
    assert len(again) == len(hk) and np.max(np.abs(again["depth"] - hk["depth"])) < 1e-12
    solver = {k: re.search(r"linear solves [0-9.]+ s \((\w+),", p.stdout).group(1) for k, p in
              (("axi0", axi0), ("auto", auto), ("above", above))}
    assert solver == {"axi0": "direct", "auto": "direct", "above": "fieldsplit"}, solver
    pa, pb = read_history(tmp_path / "auto")["load"][-1], read_history(tmp_path / "above")["load"][-1]
    assert abs(pb / pa - 1) < 1e-8
    par = run(cube, tmp_path / "above2", args=["-indent_solver", "fieldsplit"], np_=2)   # the field split on 2 ranks
    assert abs(par["load"][-1] / pa - 1) < 1e-8


MEASURED_BERKOVICH = {0.04: 0.1401, 0.03: 0.1350}      # Pb / Pc - 1, measured 2026-11 (regression values)


def test_berkovich_vs_equivalent_cone(tmp_path):
    """Elastic, the same depth: the 3D Berkovich (half model, mirror plane x = 0) against the axisymmetric
    cone of the same projected area (70.3 deg). A labelled REGRESSION check of the measured differences (it
    shrinks as the 3D mesh is refined: P1 tetrahedra are stiff where the contact radius spans few elements;
    docs/contact.md), not an accuracy check."""
    c = run(axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", PUSH % 0.1, W=2, H=2, h_tip=0.02, h_far=0.2,
                      r_fine=0.4, r_contact=0.8), tmp_path / "cone")
    diff = {}
    for h_tip in (0.04, 0.03):
        cube = cube_scene(h_tip, 0.4, PUSH % 0.1)
        b = run(cube, tmp_path / f"berkovich{h_tip}")
        Pb, Pc = 2 * b["load"][-1], c["load"][-1]   # the half model carries half the load
        diff[h_tip] = Pb / Pc - 1
        print(f"h = 0.1: Berkovich (3D h_tip {h_tip}) P = {Pb:.6g}, equivalent cone P = {Pc:.6g}, difference {diff[h_tip]:+.3%}")
    # REGRESSION check (no independent value: the 3D mesh is too coarse for the Berkovich-cone difference):
    # the measured differences, +14.01 % and +13.50 %, to 0.1 % (absolute).
    assert abs(diff[0.04] - MEASURED_BERKOVICH[0.04]) < 1e-3 and abs(diff[0.03] - MEASURED_BERKOVICH[0.03]) < 1e-3


def camclay_indent(eta, T):
    """Cam-Clay IX kerogen (soft frame only, eta_soft = eta) under a cone, coarse axisymmetric: a load ramp to
    100 uN in T/2, a hold of T (12 geometric steps), an unload to zero in T/2."""
    return f"""scene: fe
mesh:
  geometry: meshes/indent_block2d.geo
  parameters: {{W: 2, H: 2, half: 1, h_tip: 0.05, h_far: 0.2, r_fine: 0.4, r_contact: 0.9}}
  kinematics: axisymmetric
material: {{props: woodford, set: {{phi: 0, eta_soft: {eta!r}}}}}
boundary:
  fixed: {ROLLERS}
indenter: {{shape: cone, half_angle: 70.3, contact: contact}}
stages:
  - {{name: load, duration: {T / 2}, indenter: {{load: 100}}, steps: {{count: 5}}}}
  - {{name: hold, duration: {T}, indenter: {{load: hold}}, steps: {{count: 12, spacing: geometric, ratio: 1.5}}}}
  - {{name: unload, duration: {T / 2}, indenter: {{load: 0}}, steps: {{count: 4}}}}
"""


def test_camclay_creep_scales_with_eta(tmp_path):
    """Perzyna with linear overstress (theory.md §3.1, Y21 eq. 27): time enters only as t/eta, so the run with
    2 eta and every duration doubled is the run with eta at half the time: the same depths at matched steps
    (1e-9), early creep rates in the ratio 2 exactly. Also: the invariants at every step, creep in the hold
    at every step with a decaying rate, and a residual indent after unloading (viscoplastic strain stays)."""
    eta = 1.3e10
    a = run(camclay_indent(eta, 10.0), tmp_path / "eta", exe="driver")
    b = run(camclay_indent(2 * eta, 20.0), tmp_path / "eta2", exe="driver")
    for hist in (a, b):
        check_invariants(hist, tol=1e-9)
    assert len(a) == len(b) and np.allclose(b["time"], 2 * a["time"], rtol=1e-12, atol=0)
    assert np.max(np.abs(b["depth"] - a["depth"])) <= 1e-9 * a["depth"].max()
    hold = np.where(a["stage_name"] == "hold")[0]
    h0 = hold[0] - 1                                    # the end of the load
    rate_a = (a["depth"][hold[0]] - a["depth"][h0]) / (a["time"][hold[0]] - a["time"][h0])
    rate_b = (b["depth"][hold[0]] - b["depth"][h0]) / (b["time"][hold[0]] - b["time"][h0])
    rates = np.diff(a["depth"][np.r_[h0, hold]]) / np.diff(a["time"][np.r_[h0, hold]])
    creep = a["depth"][hold[-1]] - a["depth"][h0]
    print(f"Cam-Clay IX cone, 100 uN: depth {a['depth'][h0]:.5f} um at the end of the load, creep {creep:.5f} um "
          f"in {a['time'][hold[-1]] - a['time'][h0]:g} s; first-step creep rates eta / 2 eta: {rate_a / rate_b:.12f}; "
          f"rate at the end of the hold / at its start {rates[-1] / rates[0]:.3f}; residual depth {a['depth'][-1]:.5f}")
    assert abs(rate_a / rate_b - 2) < 1e-8
    assert creep > 0.05 * a["depth"][h0] and np.all(rates > 0) and np.all(np.diff(rates) < 0)
    assert 0 < a["depth"][-1] < a["depth"][h0] and a["active_nodes"][-1] == 0


BAD = [
    ("{shape: pyramid, half_angle: 65, contact: contact}", "indenter.shape", "pyramid"),
    ("{shape: berkovich, half_angle: 65.27, contact: contact}", "indenter.shape", "berkovich needs a 3D mesh"),
    ("{shape: cone, half_angle: 95, contact: contact}", "indenter.half_angle", "between 0 and 90"),
    ("{shape: cone, half_angle: 70.3, contact: nowhere}", "indenter.contact", "nowhere"),
    ("{shape: cone, half_angle: 70.3, contact: contact, gap: sideways}", "indenter.gap", "sideways"),
    ("{shape: sphere, contact: contact}", "indenter", "radius"),
]


@pytest.mark.parametrize("indenter,key,word", BAD)
def test_bad_indenter_input(tmp_path, indenter, key, word):
    """Each bad indenter key: a clear error naming the scene file, the key and the value; exit code 2."""
    proc = run(axi_scene(indenter, PUSH % 0.1, W=4, H=2, h_tip=0.1, h_far=0.5), tmp_path / "bad", check=False)
    msg = proc.stdout + proc.stderr
    assert proc.returncode != 0 and key in msg and word in msg and "bad.yaml" in msg, msg


def test_bad_stage_input(tmp_path):
    stages = "  - {name: hold, duration: 1, indenter: {load: hold, until: {depth: 0.1}}}"
    proc = run(axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", stages, W=4, H=2, h_tip=0.1, h_far=0.5),
               tmp_path / "bad", check=False)
    msg = proc.stdout + proc.stderr
    assert proc.returncode != 0 and "stages[0].indenter.until" in msg and "rising load" in msg, msg


def test_contact_outgrows_its_surface(tmp_path):
    """A potential contact surface too small for the indent: the run stops with an error naming the scene,
    the surface and the depth, and the history written so far stays."""
    scene = axi_scene("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=20, H=10, h_tip=0.02, h_far=1,
                      r_contact=0.12)
    proc = run(scene, tmp_path / "small", check=False)
    msg = proc.stdout + proc.stderr
    assert proc.returncode != 0 and "edge of the potential contact surface 'contact'" in msg and "small.yaml" in msg, msg
    assert (tmp_path / "small" / "history.csv").read_text().count("\n") >= 2


def test_contact_tangent_against_finite_differences(tmp_path):
    """-indent_check_tangent: the whole linearised system of eq. 15 (FE block, contact blocks, indenter row,
    multiplier rows of the active set) against central differences of the residual along a random direction,
    at every Newton iterate. With the vertical gap (the normal fixed along the axis) the tangent is exact:
    < 1e-6 at every iterate on the elastic UMAT, and on Cam-Clay IX except at the first iterate of a step that
    starts to yield (central differences across the yield surface), where it is asserted < 1e-4. The normal
    gap's tangent freezes the normal (exact on a flat face); under the apex the normal turns with the node,
    which this check shows as a large difference there (not asserted: docs/contact.md)."""
    stages = "  - {name: push, duration: 1, indenter: {load: 100}, steps: {count: 3}}"
    cone = "{shape: cone, half_angle: 70.3, contact: contact, gap: vertical}"
    checks = {}
    for exe, material in (("driver_elastic", ELASTIC), ("driver", "{props: woodford, set: {phi: 0}}")):
        text = axi_scene(cone, stages, W=2, H=2, h_tip=0.08, h_far=0.3, r_fine=0.4, r_contact=0.9).replace(
            f"material: {ELASTIC}", f"material: {material}")
        checks[exe], _ = tangent_checks(text, tmp_path / exe, exe)
        print(f"{exe}: {len(checks[exe])} iterates, |J d - FD| / |J d| from {min(checks[exe]):.1e} to {max(checks[exe]):.1e}")
    assert len(checks["driver_elastic"]) >= 3 and max(checks["driver_elastic"]) < 1e-6
    cc = checks["driver"]
    assert len(cc) >= 3 and max(cc) < 1e-4 and sorted(cc)[len(cc) // 2] < 1e-6
