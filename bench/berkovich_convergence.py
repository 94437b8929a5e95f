#!/usr/bin/env python3
"""The elastic 3D Berkovich (half model, mirror plane x = 0) against its equivalent cone (issue 12, item 2).

Elastic (E = 1000, nu = 0.3), depth 0.1 under depth control, the default (normal) gap. The Berkovich (half-angle
65.27 deg) on a block of side 4 (x >= 0, height 4) meshed with tetrahedra graded toward the tip, on a ladder of
h_tip with P1 and with P2, the far field refined with the tip (h_far = 10 h_tip, at most 0.8); the cone of the same projected area (70.3 deg) axisymmetric, P2, on a cylinder of
radius 2 and height 4 at h_tip 0.01 and 0.005 (converged: its two runs agree to the printed digits). Richardson
extrapolation of each 3D ladder (three rungs at a constant ratio): the observed order p and the limit
P_inf = P_3 + (P_3 - P_2) / (r^p - 1). The ratio P_Berkovich / P_cone at equal depth is set against the published
corrections: King (1987), beta = 1.034 for a triangular flat punch (the stiffness of a triangle against the circle
of the same area); Hay, Bolshakov & Pharr (1999), gamma, the radial-displacement factor, which both indenters
share here (normal gap), so it cancels from the ratio to first order. Timings on a shared, loaded machine
(2 cores, 5 users): the driver's CPU time beside wall time. Writes the section "The 3D Berkovich against the
cone" of docs/contact.md.

Usage: bench/berkovich_convergence.py [--quick]
"""
import argparse
import math
import tempfile
from pathlib import Path

from camclay9 import DriverError, mesh_line, read_history, run_driver
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "contact.md"
TITLE = "## The 3D Berkovich against the cone"
ELASTIC = "{umat: elastic, props: [1000.0, 0.3], nstatv: 0}"
DEPTH = 0.1
PUSH = f"  - {{name: push, duration: 1, indenter: {{depth: {DEPTH}}}, steps: {{count: 2}}}}"
BETA_KING = 1.034
FAR = 10  # h_far = FAR x h_tip (at most 0.8): the far field is refined with the tip. With h_far fixed at 0.8, the
          # P1 ladder (h_tip 0.04 to 0.02) stalls at a ratio of 1.130 and the P2 ladder (0.08 to 0.04) at 1.074: each
          # converges to its own far-field error, and P1 tetrahedra are stiff on the coarse far mesh


def cube(h_tip, order):
    return f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_cube.geo
  parameters: {{L: 4, half: 1, h_tip: {h_tip}, h_far: {min(FAR * h_tip, 0.8):.4g}, r_fine: 0.4, r_contact: 0.6}}
  order: {order}
material: {ELASTIC}
boundary:
  fixed: [{{group: bottom, components: [x, y, z]}}, {{group: x0, components: [x]}}, {{group: x1, components: [x]}},
          {{group: y0, components: [y]}}, {{group: y1, components: [y]}}]
indenter: {{shape: berkovich, half_angle: 65.27, contact: contact}}
stages:
{PUSH}
"""


def cylinder(h_tip):
    return f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_block2d.geo
  parameters: {{W: 4, H: 4, half: 1, h_tip: {h_tip}, h_far: 0.4, r_fine: 0.4, r_contact: 0.6}}
  kinematics: axisymmetric
  order: 2
material: {ELASTIC}
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {{shape: cone, half_angle: 70.3, contact: contact}}
stages:
{PUSH}
"""


def run(text, out):
    out.parent.mkdir(parents=True, exist_ok=True)
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    try:
        proc = run_driver(scene, out, name="driver_elastic", root=ROOT, cwd=ROOT, timeout=6 * 3600)
    except DriverError as err:
        raise SystemExit(f"{scene}: the driver failed: {err}")
    h = read_history(out, need=("load",))
    return dict(P=h["load"][-1], N=mesh_line(proc.stdout)["unknowns"], wall=proc.wall, cpu=proc.cpu)


def richardson(hs, Ps):
    """Three rungs at a constant ratio r: the observed order and the extrapolated limit (None if not monotone)."""
    r = hs[0] / hs[1]
    d1, d2 = Ps[0] - Ps[1], Ps[1] - Ps[2]
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(d1 / d2) / math.log(r)
    return p, Ps[2] + (Ps[2] - Ps[1]) / (r ** p - 1)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="two coarse rungs per order, no document")
    a = ap.parse_args()
    ladders = {1: [0.04, 0.04 / 2 ** 0.5, 0.02], 2: [0.08, 0.08 / 2 ** 0.5, 0.04]}
    if a.quick:
        ladders = {1: [0.06, 0.045], 2: [0.1, 0.08]}
    rows, cone = [], {}
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for h in ([0.01] if a.quick else [0.01, 0.005]):
            cone[h] = run(cylinder(h), tmp / f"cone{h}")
            print(f"cone P2 axisymmetric h_tip {h}: P {cone[h]['P']:.7g} ({cone[h]['N']} unknowns, wall {cone[h]['wall']:.1f} s, "
                  f"cpu {cone[h]['cpu']:.1f} s)", flush=True)
        Pc = cone[min(cone)]["P"]
        for order, hs in ladders.items():
            for h in hs:
                r = run(cube(h, order), tmp / f"b{order}_{h:.4f}")
                r.update(order=order, h=h, P=2 * r["P"])  # the half model carries half the load
                rows.append(r)
                print(f"Berkovich P{order} h_tip {h:.4f}: P {r['P']:.6g}, ratio to the cone {r['P'] / Pc:.4f} ({r['N']} unknowns, "
                      f"wall {r['wall']:.1f} s, cpu {r['cpu']:.1f} s)", flush=True)
    lim = {}
    for order, hs in ladders.items():
        Ps = [r["P"] for r in rows if r["order"] == order]
        if len(Ps) == 3:
            lim[order] = richardson(hs, Ps)
            p, Pinf = lim[order]
            print(f"P{order}: Richardson order {p}, limit {Pinf}, ratio {Pinf / Pc if Pinf else None}")
    if a.quick:
        return
    lines = [TITLE, "",
             "`bench/berkovich_convergence.py`: elastic (E = 1000, ν = 0.3), depth 0.1, normal gap. The Berkovich half model",
             "on a block of side 4 (tetrahedra graded toward the tip, h_far = 10 h_tip up to 0.8), P1 and P2 on ladders of h_tip at ratio √2; the",
             "equivalent cone (70.3°) axisymmetric P2 on a cylinder of radius 2 and height 4. Load of the whole indenter. Timings",
             "on a shared, loaded machine (2 cores, 5 users): CPU time of the driver beside wall time, one run each.", "",
             "| model | h_tip | unknowns | P | P / P_cone | wall s | CPU s |", "|---|---|---|---|---|---|---|"]
    for h, c in sorted(cone.items(), reverse=True):
        lines.append(f"| cone, axisymmetric P2 | {h:g} | {c['N']} | {c['P']:.6g} | {c['P'] / Pc:.4f} | {c['wall']:.1f} | {c['cpu']:.1f} |")
    for r in rows:
        lines.append(f"| Berkovich 3D P{r['order']} | {r['h']:.4f} | {r['N']} | {r['P']:.6g} | {r['P'] / Pc:.4f} | {r['wall']:.1f} | {r['cpu']:.1f} |")
    lines.append("")
    for order, (p, Pinf) in lim.items():
        if Pinf is None:
            lines.append(f"P{order}: the ladder does not converge monotonically; no Richardson estimate.")
        else:
            last = [r for r in rows if r["order"] == order][-1]
            lines.append(f"P{order}: Richardson order {p:.2f}, limit P = {Pinf:.5g}, ratio to the cone {Pinf / Pc:.4f} "
                         f"(the finest rung is {last['P'] / Pinf - 1:+.2%} from the limit).")
    g = lambda psi: 1 + (1 - 2 * 0.3) / (4 * (1 - 0.3) * math.tan(math.radians(psi)))  # noqa: E731
    lines += ["", f"Published: King (1987) β = {BETA_KING} for a triangular punch against the circle of the same area. The radial-"
              f"displacement factor γ = 1 + (1 − 2ν)/(4(1 − ν) tan ψ) of Hay, Bolshakov & Pharr (1999) enters both runs (normal "
              f"gap): {g(70.3):.4f} for the cone's 70.3°, {g(65.27):.4f} if taken at the Berkovich's face angle 65.27°, a ratio "
              f"of {g(65.27) / g(70.3):.4f}; with it, β γ_B/γ_C = {BETA_KING * g(65.27) / g(70.3):.3f}.", ""]
    replace_section(TITLE, "\n".join(lines) + "\n", DOC)
    print(f"wrote the section '{TITLE}' of {DOC}")


if __name__ == "__main__":
    main()
