"""Contact on quadratic (P2) elements (issue 12; docs/contact.md, "Quadratic elements"): the mortar-type weak
form with linear multipliers on the contact vertices, weighted gaps and the contact work at Gauss points of the
contact facets. On the linear-elastic UMAT (E = 1000, nu = 0.3), against closed forms: Sneddon's cone and Hertz's
sphere, axisymmetric and 3D (half model), with both gaps; the order of convergence on a small ladder; and a
force-controlled load-hold-unload with its invariants, 2 ranks, the field split and a restart."""
import math

import numpy as np

from test_contact import ELASTIC, ESTAR, NU, PSI, axi_scene, check_invariants, run, sneddon


def axi(indenter, stages, order=2, W=40, H=20, h_tip=0.02, h_far=2, r_fine=0.5, r_contact=1.0):
    """test_contact's axisymmetric block, with the element order."""
    text = axi_scene(indenter, stages, W=W, H=H, h_tip=h_tip, h_far=h_far, r_fine=r_fine, r_contact=r_contact)
    return text.replace("  kinematics: axisymmetric\n", f"  kinematics: axisymmetric\n  order: {order}\n")


def cube(indenter, stages, order=2, L=4, h_tip=0.06, h_far=0.8, r_fine=0.4, r_contact=0.6):
    return f"""scene: fe
mesh:
  geometry: meshes/indent_cube.geo
  parameters: {{L: {L}, half: 1, h_tip: {h_tip}, h_far: {h_far}, r_fine: {r_fine}, r_contact: {r_contact}}}
  order: {order}
material: {ELASTIC}
boundary:
  fixed: [{{group: bottom, components: [x, y, z]}}, {{group: x0, components: [x]}}, {{group: x1, components: [x]}},
          {{group: y0, components: [y]}}, {{group: y1, components: [y]}}]
indenter: {indenter}
stages:
{stages}
"""


def push(depth, steps=2):
    return f"  - {{name: push, duration: 1, indenter: {{depth: {depth}}}, steps: {{count: {steps}}}}}"


def hertz(h, R=1.0):
    """Hertz: P = (4/3) E* sqrt(R) h^(3/2)."""
    return 4 / 3 * ESTAR * math.sqrt(R) * h ** 1.5


CONE_V = "{shape: cone, half_angle: 70.3, contact: contact, gap: vertical}"
SPHERE_V = "{shape: sphere, radius: 1, contact: contact, gap: vertical}"


def test_p2_sneddon_hertz_axisymmetric(tmp_path):
    """P2, axisymmetric, on the P1 tests' blocks at twice their element size: Sneddon within 1.5 % (P1 at
    h_tip 0.01: +1.00 %, mostly the finite block), Hertz within 2 %; the normal gap's cone on the radial-
    displacement factor gamma of Hay, Bolshakov & Pharr (1999) within 0.5 %."""
    c = run(axi(CONE_V, push(0.1)), tmp_path / "cone")
    e_c = c["load"][-1] / sneddon(c["depth"][-1]) - 1
    n = run(axi("{shape: cone, half_angle: 70.3, contact: contact}", push(0.1)), tmp_path / "normal")
    check_invariants(n)
    gamma = 1 + (1 - 2 * NU) / (4 * (1 - NU) * math.tan(PSI))
    ratio = n["load"][-1] / sneddon(n["depth"][-1])
    s = run(axi(SPHERE_V, push(0.01), W=20, H=10, h_tip=0.02, h_far=1, r_fine=0.2, r_contact=0.3), tmp_path / "sphere")
    e_s = s["load"][-1] / hertz(s["depth"][-1]) - 1
    print(f"P2 axisymmetric: Sneddon {e_c:+.2%}, normal gap P / Sneddon {ratio:.4f} (gamma {gamma:.4f}), Hertz {e_s:+.2%}")
    assert abs(e_c) < 0.015 and abs(ratio / gamma - 1) < 0.005 and abs(e_s) < 0.02


def test_p2_3d_against_axisymmetric(tmp_path):
    """3D half model (mirror plane x = 0) with P2 tetrahedra, a coarse mesh (h_tip 0.06, 2 to 3 elements across
    the contact radius) on a block of side 4: the closed forms hold for a half-space, so the reference here is the
    axisymmetric P2 twin on a cylinder of radius 2 and height 4 (h_tip 0.02, converged to 1e-3), whose own distance from the
    closed form (+2.5 % Hertz, +3.4 % Sneddon) is the finite block's. The 3D run must be within 2 % of its twin
    (the rest: the 3D mesh, and a square block against a round one), and within 6 % of the closed form; P1 on the
    same tetrahedra is 8-10 % off, and P2 must at least halve that error."""
    cases = [("cone", CONE_V, 0.1, sneddon, dict(r_fine=0.4, r_contact=0.6), 0.4),
             ("sphere", SPHERE_V, 0.02, hertz, dict(r_fine=0.3, r_contact=0.4), 0.3)]
    for name, ind, depth, exact, box, rf in cases:
        twin = run(axi(ind, push(depth), W=4, H=4, h_tip=0.02, h_far=0.4, r_fine=rf, r_contact=box["r_contact"]),
                   tmp_path / f"{name}_axi")
        p2 = run(cube(ind, push(depth, 1), **box), tmp_path / f"{name}_p2")
        p1 = run(cube(ind, push(depth, 1), order=1, **box), tmp_path / f"{name}_p1")
        Pt, P2, P1 = twin["load"][-1], 2 * p2["load"][-1], 2 * p1["load"][-1]   # the half model carries half the load
        print(f"{name} h = {depth}: 3D P2 {P2:.5g} ({P2 / Pt - 1:+.2%} from the axisymmetric twin, {P2 / exact(depth) - 1:+.2%} "
              f"from the closed form); 3D P1 {P1 / Pt - 1:+.2%} from the twin; twin {Pt / exact(depth) - 1:+.2%} from the closed form")
        assert abs(P2 / Pt - 1) < 0.02 and abs(P2 / exact(depth) - 1) < 0.06
        assert abs(P2 / Pt - 1) < 0.5 * abs(P1 / Pt - 1)


def test_p2_convergence_order(tmp_path):
    """Hertz, axisymmetric, vertical gap, block 4 x 2: the RMS of P / P_ref - 1 over 8 depths from h/2 to h (one
    depth alone is erratic as nodes enter the contact) on h_tip 0.04, 0.02, 0.01, the whole mesh refined with the
    tip (h_far = 20 h_tip), against P2 at 0.005 on the same block (the mesh error alone). bench/contact_p2_rates.py
    measures the orders on longer ladders (docs/contact.md); asserted here: P2's order above 1.5 in h_tip, and P2's
    error below P1's on each mesh."""
    stages = ("  - {name: touch, duration: 1, indenter: {depth: 0.005}, steps: {count: 1}}\n"
              "  - {name: push, duration: 1, indenter: {depth: 0.01}, steps: {count: 8}}")

    def loads(h, order):
        hist = run(axi(SPHERE_V, stages, order=order, W=4, H=2, h_tip=h, h_far=20 * h, r_fine=0.2, r_contact=0.3),
                   tmp_path / f"p{order}_{h}")
        return hist["load"][hist["stage_name"] == "push"]
    ref = loads(0.005, 2)
    hs = (0.04, 0.02, 0.01)
    err = {o: [math.sqrt(np.mean((loads(h, o) / ref - 1) ** 2)) for h in hs] for o in (2, 1)}
    order = np.polyfit(np.log(hs), np.log(err[2]), 1)[0]
    print(f"Hertz P2 errors {', '.join(f'{e:.2e}' for e in err[2])} (order {order:.2f}); P1 {', '.join(f'{e:.2e}' for e in err[1])}")
    assert order > 1.5 and all(a < b for a, b in zip(err[2], err[1]))


LHU = """  - {name: load, duration: 100, indenter: {load: {exp: {P0: 5, k: 0.1}}, until: {depth: 0.1}}, steps: {count: 10}}
  - {name: hold, duration: 10, indenter: {load: hold}, steps: {count: 2}}
  - {name: unload, duration: 2, indenter: {load: 0}, steps: {count: 4}}"""


def test_p2_load_hold_unload(tmp_path):
    """Force control on P2 (normal gap): the supports' reaction equals the load at every step (1e-10); the step
    lands on the target depth; the elastic block returns to zero depth with an empty active set (the indenter
    rests at its pointwise first touch); a restart from a checkpoint gives the same history; on a small block,
    2 ranks (multipliers and facets split over the ranks) and the field-split solver give the serial history."""
    scene = axi("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=10, H=5, h_tip=0.05, h_far=1)
    hist = run(scene, tmp_path / "lhu")
    check_invariants(hist)
    assert abs(hist[hist["stage_name"] == "load"]["depth"][-1] - 0.1) <= 1e-5 * 0.1
    last = hist[-1]
    assert last["load"] == 0 and last["active_nodes"] == 0 and abs(last["depth"]) < 1e-10
    run(scene, tmp_path / "restart", args=["-checkpoint_every", "3", "-max_steps", "7"])
    again = run(scene, tmp_path / "restart", args=["-restart"])
    small = axi("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=4, H=2, h_tip=0.06, h_far=0.5, r_fine=0.4,
                r_contact=0.6)
    ser = run(small, tmp_path / "ser")
    par = run(small, tmp_path / "par", np_=2)
    split = run(small, tmp_path / "split", args=["-indent_solver", "fieldsplit"])
    diffs = [np.max(np.abs(o["depth"] - r["depth"])) for o, r in ((again, hist), (par, ser), (split, ser))]
    print(f"P2 load-hold-unload: {len(hist) - 1} steps, final depth {last['depth']:.1e}; restart, 2 ranks, field split "
          f"differ by {diffs[0]:.1e}, {diffs[1]:.1e}, {diffs[2]:.1e}")
    assert len(again) == len(hist) and len(par) == len(ser) and len(split) == len(ser)
    assert diffs[0] < 1e-12 and diffs[1] < 1e-10 and diffs[2] < 1e-8


def test_p2_tangent_against_finite_differences(tmp_path):
    """-indent_check_tangent with P2 and the vertical gap: the mortar blocks (Bt, B, the indenter row) are the
    exact derivatives of the residual: below 1e-8 at every iterate."""
    from test_contact import tangent_checks
    text = axi(CONE_V, "  - {name: push, duration: 1, indenter: {load: 100}, steps: {count: 3}}", W=2, H=2, h_tip=0.08,
               h_far=0.3, r_fine=0.4, r_contact=0.9)
    checks, _ = tangent_checks(text, tmp_path / "fd")
    print(f"P2 tangent: {len(checks)} iterates, |J d - FD| / |J d| up to {max(checks):.1e}")
    assert len(checks) >= 3 and max(checks) < 1e-8


def test_p2_contact_outgrows_its_surface(tmp_path):
    """The rim check on P2 (the multipliers' vertices on the edge of the potential contact surface): the run
    stops with the error naming the surface and the scene, and keeps the history."""
    scene = axi("{shape: cone, half_angle: 70.3, contact: contact}", LHU, W=20, H=10, h_tip=0.02, h_far=1, r_contact=0.12)
    proc = run(scene, tmp_path / "small", check=False)
    msg = proc.stdout + proc.stderr
    assert proc.returncode != 0 and "edge of the potential contact surface 'contact'" in msg and "small.yaml" in msg, msg
    assert (tmp_path / "small" / "history.csv").read_text().count("\n") >= 2


def test_p2_force_control_first_touch_on_a_coarse_mesh(tmp_path):
    """Force control from a load jump (P0 of an exp load) on a coarse P2 mesh: the tip vertex's mean gap is
    positive while the tip touches, so no multiplier is active at first; the indenter is moved down to the first
    touch of the mean gaps (semismooth.c, approach) instead of by the indenter row's small shift steps, which
    needed more than the iteration limit here and cut the first step to nothing. The depth lands on 0.1 and
    the load there is Sneddon's within 3 % (coarse mesh)."""
    load = ("  - {name: load, duration: 10, indenter: {load: {exp: {P0: 0.2, k: 0.6}}, until: {depth: 0.1}}, "
            "steps: {adaptive: true, first: 0.05, max: 1}}")
    h = run(axi(CONE_V, load, h_tip=0.08, h_far=2), tmp_path / "coarse")
    e = h["load"][-1] / sneddon(h["depth"][-1]) - 1
    print(f"P2 coarse, force control from P0: {len(h) - 1} steps, depth {h['depth'][-1]:.6f}, Sneddon {e:+.2%}")
    assert abs(h["depth"][-1] - 0.1) < 1e-5 and abs(e) < 0.03
