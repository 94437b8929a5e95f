#!/usr/bin/env python3
"""Contact on P1 and P2 elements (issue 12): the convergence of the indentation load under mesh refinement.

Elastic (E = 1000, nu = 0.3), axisymmetric, vertical gap (the linearised contact of the closed forms), depth
control. Two problems:
  Hertz    sphere R = 1, h = 0.01 (a = 0.1), block 8 x 4 (radius x height);
  Sneddon  cone 70.3 deg, h = 0.1 (a = 0.177), block 16 x 8.
The mesh is refined as a whole: h_far = 20 h_tip (a ladder refining the tip alone converges each order to its own
far-field error: P1 and P2 then differ by 0.15 % in their limits on a fixed h_far = 1).
Each on a ladder of h_tip (the element size under the tip) with P1 and P2, against a fine P2 run on the same
block (h_tip half the ladders' finest), so that the error measured is the mesh's alone (the finite block's
is the same in every run; the closed forms, against which each run is also printed, hold for a half-space).
The error is the RMS of P / P_ref - 1 over 8 depths from h/2 to h (one depth alone is erratic: the load
jumps as a node enters the contact). Orders: a least-squares slope over the ladder, and between rungs.
Observed orders: between successive rungs, in h_tip and in the number of unknowns N. P2 against P1 at equal
unknowns: the P1 error interpolated (log-log) at each P2 run's N. Writes the section "P1 and P2: convergence"
of docs/contact.md. Timings on a shared, loaded machine (2 cores, 5 users): CPU time of the driver beside
wall time, medians of --repeats runs.

Usage: bench/contact_p2_rates.py [--repeats 1] [--quick]
"""
import argparse
import math
import statistics
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import DriverError, mesh_line, read_history, run_driver
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "contact.md"
TITLE = "## P1 and P2: convergence"
E, NU = 1000.0, 0.3
ESTAR = E / (1 - NU ** 2)
PSI = math.radians(70.3)
NSAMPLE = 8  # depths from h/2 to h at which the load is compared: the mean over them smooths the stair steps of
             # the discrete contact radius (a node entering contact), which make a single depth's error erratic

FAR = 20  # the far-field element size is FAR x h_tip (up to W/4): the whole mesh is refined, not the tip alone
PROBLEMS = {
    "hertz": dict(indenter="{shape: sphere, radius: 1, contact: contact, gap: vertical}", depth=0.01,
                  mesh=dict(W=8, H=4, r_fine=0.2, r_contact=0.3),
                  exact=lambda h: 4 / 3 * ESTAR * h ** 1.5),
    "sneddon": dict(indenter="{shape: cone, half_angle: 70.3, contact: contact, gap: vertical}", depth=0.1,
                    mesh=dict(W=16, H=8, r_fine=0.4, r_contact=0.6),
                    exact=lambda h: 2 / math.pi * ESTAR * math.tan(PSI) * h ** 2),
}


def scene(prob, h_tip, order):
    m = prob["mesh"]
    return f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_block2d.geo
  parameters: {{W: {m['W']}, H: {m['H']}, half: 1, h_tip: {h_tip}, h_far: {min(FAR * h_tip, m['W'] / 4):g}, r_fine: {m['r_fine']}, r_contact: {m['r_contact']}}}
  kinematics: axisymmetric
  order: {order}
material: {{umat: elastic, props: [{E}, {NU}], nstatv: 0}}
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {prob['indenter']}
stages:
  - {{name: touch, duration: 1, indenter: {{depth: {prob['depth'] / 2}}}, steps: {{count: 1}}}}
  - {{name: push, duration: 1, indenter: {{depth: {prob['depth']}}}, steps: {{count: {NSAMPLE}}}}}
"""


def run(text, out, repeats):
    """The load at the target depth, the unknowns, and the medians of wall and CPU time (driver only)."""
    walls, cpus = [], []
    for _ in range(repeats):
        out.parent.mkdir(parents=True, exist_ok=True)
        (out.parent / (out.name + ".yaml")).write_text(text)
        try:
            proc = run_driver(out.parent / (out.name + ".yaml"), out, name="driver_elastic", root=ROOT, cwd=ROOT,
                              timeout=6 * 3600)
        except DriverError as err:
            raise SystemExit(f"{out}: the driver failed: {err}")
        walls.append(proc.wall)
        cpus.append(proc.cpu)
    h = read_history(out, need=("stage_name", "load", "depth"))
    h = h[h["stage_name"] == "push"]
    unknowns = mesh_line(proc.stdout)["unknowns"]
    return dict(P=h["load"][-1], Ps=h["load"], depth=h["depth"][-1], N=unknowns, wall=statistics.median(walls),
                cpu=statistics.median(cpus))


def ladder(name, hs, repeats, tmp):
    """hs: the h_tip of each order's rungs; the reference: P2 at half the finest."""
    prob = PROBLEMS[name]
    href = min(min(v) for v in hs.values()) / 2
    ref = run(scene(prob, href, 2), tmp / f"{name}_ref", 1)
    ref["h"] = href
    print(f"{name} reference P2 h_tip {href:g}: N {ref['N']}, P {ref['P']:.8g}, wall {ref['wall']:.1f} s, cpu {ref['cpu']:.1f} s", flush=True)
    rows = []
    for order in (1, 2):
        for h in hs[order]:
            r = run(scene(prob, h, order), tmp / f"{name}_p{order}_{h}", repeats)
            r.update(order=order, h=h, err=float(np.sqrt(np.mean((r["Ps"] / ref["Ps"] - 1) ** 2))),
                     exact=r["P"] / prob["exact"](r["depth"]) - 1)
            rows.append(r)
            print(f"{name} P{order} h_tip {h:<7g} N {r['N']:>7d}  P {r['P']:.7g}  error vs fine P2 {r['err']:.3e}  "
                  f"vs closed form {r['exact']:+.3%}  wall {r['wall']:.2f} s  cpu {r['cpu']:.2f} s", flush=True)
    for order in (1, 2):  # observed orders between successive rungs
        rs = [r for r in rows if r["order"] == order]
        for a, b in zip(rs, rs[1:]):
            b["rate_h"] = math.log(a["err"] / b["err"]) / math.log(a["h"] / b["h"])
            b["rate_N"] = -math.log(a["err"] / b["err"]) / math.log(a["N"] / b["N"])
    slopes = {}
    for order in (1, 2):  # least-squares slopes of log err against log h_tip and log N over the ladder
        rs = [r for r in rows if r["order"] == order]
        le = np.log([r["err"] for r in rs])
        slopes[order] = (np.polyfit(np.log([r["h"] for r in rs]), le, 1)[0], -np.polyfit(np.log([r["N"] for r in rs]), le, 1)[0])
        print(f"{name} P{order}: observed order {slopes[order][0]:.2f} in h_tip, {slopes[order][1]:.2f} in N (least squares)")
    p1 = [r for r in rows if r["order"] == 1]
    for r in rows:  # the P1 error at this run's unknowns (log-log interpolation, within the P1 ladder only)
        if r["order"] == 2 and p1[0]["N"] <= r["N"] <= p1[-1]["N"]:
            lN, le = np.log([q["N"] for q in p1]), np.log([q["err"] for q in p1])
            r["p1_at_N"] = float(np.exp(np.interp(math.log(r["N"]), lN, le)))
    return ref, rows, slopes


def section(results, repeats):
    lines = [TITLE, "",
             "`bench/contact_p2_rates.py`: the elastic load at the target depth on a ladder of meshes (h_tip: the element",
             "size under the tip; the far field refined with it, h_far = 20 h_tip), axisymmetric, vertical gap, P1 (nodal quadrature) and P2 (the mortar form above), each",
             "against a fine P2 run on the same block (the mesh error alone; the closed form, which holds for a half-space,",
             "is also shown: the rest is the finite block). Rates: observed orders between successive rungs, in h_tip and in",
             "the unknowns N. 'P1 at the same N': the P1 error interpolated (log-log) at the P2 run's unknowns.",
             f"Timings on a shared, loaded machine (2 cores, 5 users), the driver's CPU time beside wall time, medians of {repeats} run(s).", ""]
    for name, (ref, rows, slopes) in results.items():
        prob = PROBLEMS[name]
        lines += [f"**{name.capitalize()}** ({prob['indenter']}, depth {prob['depth']}, block {prob['mesh']['W']} x {prob['mesh']['H']}; "
                  f"reference P2 h_tip {ref['h']:g}: P = {ref['P']:.7g}, {ref['N']} unknowns, "
                  f"{ref['P'] / prob['exact'](ref['depth']) - 1:+.2%} from the closed form)", "",
                  "| order | h_tip | unknowns | P | error vs fine P2 | rate (h) | rate (N) | P1 at the same N | vs closed form | wall s | CPU s |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for r in rows:
            f = lambda k, fmt: format(r[k], fmt) if k in r else ""  # noqa: E731
            lines.append(f"| P{r['order']} | {r['h']:g} | {r['N']} | {r['P']:.6g} | {r['err']:.2e} | {f('rate_h', '.2f')} | "
                         f"{f('rate_N', '.2f')} | {f('p1_at_N', '.2e')} | {r['exact']:+.2%} | {r['wall']:.2f} | {r['cpu']:.2f} |")
        lines += ["", f"Least-squares orders over the ladder: P1 {slopes[1][0]:.2f} in h_tip ({slopes[1][1]:.2f} in N), "
                      f"P2 {slopes[2][0]:.2f} in h_tip ({slopes[2][1]:.2f} in N).", ""]
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--quick", action="store_true", help="three rungs, no document")
    a = ap.parse_args()
    # P2 has about four times the unknowns of P1 on a mesh: P2 on h_tip overlaps P1 on h_tip / 2 in unknowns
    hs = {1: [0.04, 0.02], 2: [0.04, 0.02]} if a.quick else {1: [0.04, 0.02, 0.01], 2: [0.04, 0.02, 0.01]}
    with tempfile.TemporaryDirectory() as d:
        results = {name: ladder(name, hs, a.repeats, Path(d)) for name in PROBLEMS}
    if not a.quick:
        replace_section(TITLE, section(results, a.repeats), DOC)
        print(f"wrote the section '{TITLE}' of {DOC}")


if __name__ == "__main__":
    main()
