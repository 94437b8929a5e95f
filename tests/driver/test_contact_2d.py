"""Plane-strain rigid-indenter contact on the linear-elastic UMAT (E = 1000, nu = 0.3; driver_elastic):

* flat punch over the whole top of a laterally confined block (rollers on the sides, bottom fixed): the
  strain is uniform uniaxial, eps_yy = -h/H, so P = E(1-nu)/((1+nu)(1-2nu)) h/H W t exactly (P1 too),
  proportional to h; t = 0.5 checks that the thickness enters the plane-strain contact weights. The same block
  under force control with a table load: the force-control predictor is then exact.
* wedge (tip angle 136.51 deg, the paper's 2D section; linearised vertical gap) on a large block, two
  independent checks: (1) the 2D wedge on an elastic half-plane (Johnson, Contact Mechanics, 1985, ch. 5:
  p(x) = (E* tan(alpha)/pi) arccosh(a/|x|), hence P = E* a tan(alpha) per unit thickness, alpha = 90 deg -
  half angle) with the contact half-width a bracketed by the last active and the first inactive node of
  the top (read from the run's mesh.msh), 2 % slack for the FE error of P; (2) self-similarity: scaling
  every length (block, mesh sizes, depth) by 2 scales the load per unit thickness by exactly 2. The same
  bracket on the half model (x >= 0, mirror plane x = 0, indenter.copies 2), whose history holds the whole load.
"""
import math
from pathlib import Path

import numpy as np
import pytest
from camclay9 import read_history, run_driver

ROOT = Path(__file__).resolve().parents[2]
E, NU = 1000.0, 0.3
ESTAR = E / (1 - NU**2)
ELASTIC = "{umat: elastic, props: [1000.0, 0.3], nstatv: 0}"


def run(text, out, check=True):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    proc = run_driver(scene, out, name="driver_elastic", root=ROOT, cwd=ROOT, timeout=600, check=check)  # DriverError: it failed
    return read_history(out) if check else proc


def msh_nodes(path):
    """Node coordinates of a gmsh 4.1 ASCII file."""
    lines = path.read_text().split("$Nodes\n")[1].split("$EndNodes")[0].splitlines()
    nblocks, i, xyz = int(lines[0].split()[0]), 1, []
    for _ in range(nblocks):
        n = int(lines[i].split()[3])
        xyz += [[float(v) for v in line.split()] for line in lines[i + 1 + n:i + 1 + 2 * n]]
        i += 1 + 2 * n
    return np.array(xyz)


# the laterally confined block under a flat punch over its whole top: uniform uniaxial strain eps_yy = -h/H, so
# P = M h/H W t, M = E(1-nu)/((1+nu)(1-2nu)) the constrained modulus, exactly (P1 too)
BW, BH, BT = 2.0, 1.0, 0.5
BLOCK_STIFFNESS = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU)) / BH * BW * BT


def confined_block(stage):
    """The confined block's scene with one stage (its YAML flow mapping)."""
    return f"""scene: fe
mesh: {{geometry: {ROOT}/meshes/rectangle.geo, parameters: {{X0: {-BW / 2}, Lx: {BW}, Ly: {BH}, size: 0.2}},
        kinematics: plane_strain, thickness: {BT}}}
material: {ELASTIC}
boundary:
  fixed: [{{group: y0, components: [x, y]}}, {{group: x0, components: [x]}}, {{group: x1, components: [x]}}]
indenter: {{shape: flat_punch, radius: 5, tip: [0, {BH}], contact: y1}}
stages:
  - {stage}
"""


def test_flat_punch_on_a_confined_block(tmp_path):
    h = run(confined_block("{name: push, duration: 1, indenter: {depth: 0.002}, steps: {count: 2}}"), tmp_path / "punch")
    exact = BLOCK_STIFFNESS * h["depth"][1:]
    print(f"plane-strain flat punch: P = {h['load'][1:]}, exact {exact}")
    assert np.allclose(h["depth"][1:], [0.001, 0.002], rtol=1e-12, atol=0)
    assert np.max(np.abs(h["load"][1:] / exact - 1)) < 1e-9


def test_force_control_predicts_a_linear_response_exactly(tmp_path):
    """The flat punch under force control, the load a table that jumps to 8 at the start and then rises by 4, 2 and 1
    in equal steps: the response is linear in the load once the punch is down, so the predictor's extrapolation by
    the ratio of load increments (semismooth.c, predictor_ratio: here the smaller ratio, 1/3 and 1/2) is the solution
    itself, and steps 2 and 3 converge with no Newton iteration. Scaled by the ratio of step lengths (1) instead, it
    predicts the last step's load increment again, and each of those steps needs one iteration."""
    (tmp_path / "load.csv").write_text("t,P\n0,8\n1,12\n2,14\n3,15\n")
    h = run(confined_block("{name: push, duration: 3, indenter: {load: {table: {file: load.csv, time: t, value: P}}}, "
                           "steps: {count: 3}}"), tmp_path / "punch")
    target = np.array([12.0, 14.0, 15.0])
    exact = target / BLOCK_STIFFNESS
    print(f"flat punch under a table load: loads {h['load'][1:]}, depths {h['depth'][1:]} (exact {exact}), "
          f"Newton iterations {h['newton_its'][1:]}")
    assert np.allclose(h["load"][1:], target, rtol=1e-9, atol=0)
    assert np.allclose(h["depth"][1:], exact, rtol=1e-9, atol=0)
    assert h["newton_its"][1] > 0 and list(h["newton_its"][2:]) == [0, 0]


def wedge_scene(k, h_tip, r_fine, half=False, copies=None, mirror=False):
    """The wedge on the whole block (mirror: meshed as two mirror halves), or (half) on its half x >= 0 with the mirror
    plane x = 0."""
    sides = ("[{group: bottom, components: [x, y]}, {group: right, components: [x]}]\n  mirror: [{group: left, normal: [1, 0]}]"
             if half else "[{group: bottom, components: [x, y]}, {group: left, components: [x]}, {group: right, components: [x]}]")
    more = f", copies: {copies}" if copies else ""
    return f"""scene: fe
mesh:
  geometry: meshes/indent_block2d.geo
  parameters: {{W: {40 * k}, H: {20 * k}, half: {int(half)}, h_tip: {h_tip * k}, h_far: {2 * k}, r_fine: {r_fine * k}, r_contact: {3 * r_fine * k}{", mirror: 1" if mirror else ""}}}
  kinematics: plane_strain
material: {ELASTIC}
boundary:
  fixed: {sides}
indenter: {{shape: wedge, tip_angle: 136.51, contact: contact, gap: vertical{more}}}
stages:
  - {{name: push, duration: 1, indenter: {{depth: {0.02 * k}}}, steps: {{count: 2}}}}
"""


def test_wedge_johnson_half_width(tmp_path):
    tan_alpha = 1 / math.tan(math.radians(136.51 / 2))
    h = run(wedge_scene(1, 0.001, 0.03), tmp_path / "wedge")
    xy = msh_nodes(tmp_path / "wedge" / "mesh.msh")
    top = np.sort(np.abs(xy[np.abs(xy[:, 1]) < 1e-12, 0]))
    n = int(h["active_nodes"][-1])
    a_lo, a_hi = top[n - 1], top[n]                     # the n active nodes are the n nearest the tip
    a = h["load"][-1] / (ESTAR * tan_alpha)
    print(f"wedge, h = 0.02: P = {h['load'][-1]:.5g}, Johnson's a = P/(E* tan alpha) = {a:.5f}; {n} active nodes, "
          f"the contact edge between {a_lo:.5f} and {a_hi:.5f}")
    assert n >= 15 and a_hi - a_lo < 0.15 * a            # the bracket resolves a
    assert a_lo * 0.98 <= a <= a_hi * 1.02


def test_wedge_half_model_carries_the_whole_load(tmp_path):
    """indenter.copies: 2 on the plane-strain half x >= 0 (mirror plane x = 0): the history's load is the whole wedge's,
    so Johnson's half-width from it, a = P / (E* tan alpha), falls between the last active and the first inactive node
    of the half as it does on the whole block (a load of the half alone would put it at half the bracket)."""
    tan_alpha = 1 / math.tan(math.radians(136.51 / 2))
    h = run(wedge_scene(1, 0.001, 0.03, half=True, copies=2), tmp_path / "half")
    xy = msh_nodes(tmp_path / "half" / "mesh.msh")
    assert xy[:, 0].min() > -1e-12
    top = np.sort(xy[np.abs(xy[:, 1]) < 1e-12, 0])
    n = int(h["active_nodes"][-1])
    a_lo, a_hi = top[n - 1], top[n]
    a = h["load"][-1] / (ESTAR * tan_alpha)
    print(f"half wedge, h = 0.02: whole load P = {h['load'][-1]:.5g}, Johnson's a = {a:.5f}; {n} active nodes, "
          f"the contact edge between {a_lo:.5f} and {a_hi:.5f}")
    assert n >= 8 and a_hi - a_lo < 0.15 * a
    assert a_lo * 0.98 <= a <= a_hi * 1.02


def test_half_model_runs_the_whole_blocks_mesh(tmp_path):
    """mirror: 1 meshes the whole block as two mirror halves (meshes/indent_block2d.geo): its mesh is symmetric about
    x = 0 and its half x >= 0 is the half model's mesh node for node. On it the half model (the mirror plane x = 0,
    indenter.copies 2) and the whole block solve the same discrete problem: the same loads to 1e-8, and 2 n - 1 active
    nodes on the whole block where the half has n (the node on the axis counted once). The whole block's log says its
    mesh's periodic copy is read as one mesh, not as periodic boundary conditions."""
    logs = {}
    for name, text in (("whole", wedge_scene(1, 0.004, 0.03, mirror=True)), ("half", wedge_scene(1, 0.004, 0.03, half=True, copies=2))):
        (tmp_path / f"{name}.yaml").write_text(text)
        logs[name] = run_driver(tmp_path / f"{name}.yaml", tmp_path / name, name="driver_elastic", root=ROOT, cwd=ROOT, timeout=600).stdout
    whole, half = read_history(tmp_path / "whole"), read_history(tmp_path / "half")
    # the log says how the mirrored copy was read: joined, not periodic
    assert "lists periodic copies ($Periodic)" in logs["whole"] and "$Periodic" not in logs["half"]
    xw, xh = msh_nodes(tmp_path / "whole" / "mesh.msh")[:, :2], msh_nodes(tmp_path / "half" / "mesh.msh")[:, :2]
    key = lambda xy: sorted(map(tuple, np.round(xy, 9)))
    right = xw[xw[:, 0] > -1e-12]
    mirrored = xw * [-1, 1]
    print(f"whole block {len(xw)} nodes ({len(right)} with x >= 0), half model {len(xh)}; loads {whole['load'][-1]:.9g} "
          f"and {half['load'][-1]:.9g}; active nodes {int(whole['active_nodes'][-1])} and {int(half['active_nodes'][-1])}")
    assert key(mirrored) == key(xw) and key(right) == key(xh)
    assert np.max(np.abs(whole["load"] - half["load"])) < 1e-8 * np.max(np.abs(whole["load"]))
    assert np.array_equal(whole["active_nodes"], np.maximum(2 * half["active_nodes"] - 1, 0)) and half["active_nodes"][-1] >= 3


@pytest.mark.parametrize("half,copies,word", [(False, 2, "lies on both sides"), (True, 3, "or its half on one side")])
def test_bad_plane_strain_copies(tmp_path, half, copies, word):
    """copies 2 on the whole block would report twice its load; plane strain has no cut with more than 2 copies."""
    proc = run(wedge_scene(1, 0.004, 0.03, half=half, copies=copies), tmp_path / "bad", check=False)
    print(proc.stderr.strip())
    assert proc.returncode == 2 and "indenter.copies" in proc.stderr and word in proc.stderr and "bad.yaml" in proc.stderr


def test_wedge_self_similar(tmp_path):
    one = run(wedge_scene(1, 0.004, 0.03), tmp_path / "k1")
    two = run(wedge_scene(2, 0.004, 0.03), tmp_path / "k2")
    ratio = two["load"][1:] / one["load"][1:]
    print(f"wedge scaled by 2 (block, mesh, depth): load ratio {ratio}")
    assert np.all(one["load"][1:] > 0) and np.max(np.abs(ratio - 2)) < 1e-9
    assert np.array_equal(one["active_nodes"], two["active_nodes"])


def test_direct_package(tmp_path):
    """The direct contact solve of a 2D model on one rank is UMFPACK's with METIS' ordering, and the log's indenter line
    names it; MUMPS, asked by -indent_pc_factor_mat_solver_type and used on 2 ranks, solves the same systems: the same
    loads to 1e-9 (both factorisations are exact; only round-off differs)."""
    scene = tmp_path / "wedge.yaml"
    scene.write_text(wedge_scene(1, 0.004, 0.03))
    runs = {}
    for name, options, ranks in (("umfpack", [], 1), ("mumps", ["-indent_pc_factor_mat_solver_type", "mumps"], 1),
                                 ("mumps2", [], 2)):
        proc = run_driver(scene, tmp_path / name, options, name="driver_elastic", root=ROOT, cwd=ROOT, ranks=ranks, timeout=600)
        line = next(s for s in proc.stdout.splitlines() if s.startswith("indenter:"))
        runs[name] = (line, read_history(tmp_path / name)["load"])
        print(name, line)
    assert "solver direct (umfpack)" in runs["umfpack"][0] and "solver direct (mumps)" in runs["mumps"][0]
    assert "solver direct (mumps)" in runs["mumps2"][0]
    for name in ("mumps", "mumps2"):
        assert np.max(np.abs(runs[name][1] - runs["umfpack"][1])) < 1e-9 * np.max(np.abs(runs["umfpack"][1]))
