#!/usr/bin/env python3
"""Indentation benchmark (issue #5). Part 1: nanoindentation on kerogen (input/nanoindent_kerogen*.yaml:
load to 200 nm, hold 60 s, unload) as the 3D Berkovich half model and as the axisymmetric equivalent cone,
at coarser meshes and looser step tolerances, and with the step predictor off: wall time against the
error in the P-h curve, in the depth at the end of the hold and in the creep depth, relative to a fine
axisymmetric reference. Part 2: direct (MUMPS) against field-split solvers on the 3D microindentation mesh:
time per Newton iteration and peak memory. Medians of repeated runs where a run is short (--repeats);
the long runs once. Writes the section "Indentation" of docs/performance.md and an error-vs-time plot
docs/indent_accuracy.png.

Usage: bench/indent_bench.py [--repeats 3] [--quick]
"""
import argparse
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import DriverError, mesh_line, read_history, run_driver, summary_line
from matplotlib.figure import Figure
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TITLE = "## Indentation"


def run(scene_text, out, args=(), ranks=1):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(scene_text)
    try:  # $DRIVER: a copy, to rebuild meanwhile
        proc = run_driver(scene, out, args, root=ROOT, ranks=ranks, prefix=["/usr/bin/time", "-f", "maxrss_kB %M"],
                          cwd=ROOT, timeout=6 * 3600)
    except DriverError as err:
        raise SystemExit(f"{scene}: the driver failed: {err}")
    s = summary_line(proc.stdout, index=0)
    rss = max(int(x) for x in re.findall(r"maxrss_kB (\d+)", proc.stderr))
    return dict(wall=proc.wall, steps=s["steps"], newton=s["newton_iterations"], cutbacks=s["cutbacks"],
                assembly=s["assembly_s"], linear=s["linear_solves_s"], rss_MB=rss / 1024,
                cells=mesh_line(proc.stdout)["cells"], hist=read_history(out))


def curve_numbers(h, load_factor):
    """P-h loading branch (load in uN of the whole indenter), depth at the end of the hold, creep depth."""
    load = h[h["stage_name"] == "load"]
    hold = h[h["stage_name"] == "hold"]
    return dict(P=load["load"] * load_factor, h=load["depth"], h_hold=hold["depth"][-1],
                creep=hold["depth"][-1] - load["depth"][-1], P_max=load["load"][-1] * load_factor)


def errors(c, ref):
    """Largest depth difference on the loading branch at equal load (relative to 200 nm), and the relative
    errors of the end-of-hold depth and of the creep depth."""
    P = np.linspace(max(c["P"][1], ref["P"][1]), min(c["P_max"], ref["P_max"]), 200)
    dh = np.abs(np.interp(P, c["P"], c["h"]) - np.interp(P, ref["P"], ref["h"])).max() / 0.2
    return dh, abs(c["h_hold"] / ref["h_hold"] - 1), abs(c["creep"] / ref["creep"] - 1)


def axi(h_tip, tol):
    text = (ROOT / "input" / "nanoindent_kerogen_axi.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    return text.replace("h_tip: 0.02", f"h_tip: {h_tip}").replace("tol: 1.5e-2", f"tol: {tol:g}")


def cube(h_tip, tol):
    text = (ROOT / "input" / "nanoindent_kerogen.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    return text.replace("h_tip: 0.05", f"h_tip: {h_tip}").replace("tol: 1.5e-2", f"tol: {tol:g}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--quick", action="store_true", help="skip the reference and the 3D runs (a smoke test)")
    a = ap.parse_args(argv)
    rows, plot = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        # Part 1: nanoindentation variants; the reference is the fine axisymmetric cone at a tight tolerance
        ref_case = ("axisymmetric cone (reference)", axi(0.01, 2.5e-3), (), 1, 1)
        cases = [("axisymmetric cone", axi(0.02, 1.5e-2), (), 1, a.repeats),
                 ("axisymmetric cone, predictor off", axi(0.02, 1.5e-2), ("-indent_predictor", "0"), 1, 1),
                 ("axisymmetric cone", axi(0.04, 1.5e-2), (), 1, a.repeats),
                 ("axisymmetric cone", axi(0.02, 3e-2), (), 1, a.repeats),
                 ("axisymmetric cone", axi(0.04, 3e-2), (), 1, a.repeats)]
        if not a.quick:
            cases += [("3D Berkovich, half model", cube(0.05, 1.5e-2), (), 2, 1),
                      ("3D Berkovich, half model", cube(0.08, 3e-2), (), 2, 1)]
        else:
            ref_case = ("axisymmetric cone (reference)", axi(0.02, 5e-3), (), 1, 1)
        ref_run = run(ref_case[1], tmp / "ref")
        ref = curve_numbers(ref_run["hist"], 1)
        print(f"reference: {ref_run['cells']} cells, {ref_run['steps']} steps, wall {ref_run['wall']:.1f} s, "
              f"P(200 nm) {ref['P_max']:.5g} uN, depth after hold {ref['h_hold']:.5g} um, creep {ref['creep']:.5g} um")
        rows.append((ref_case[0], re.search(r"h_tip: ([0-9.e-]+)", ref_case[1]).group(1),
                     re.search(r"tol: ([0-9.e-]+)", ref_case[1]).group(1), ref_run, ref, (0.0, 0.0, 0.0)))
        for k, (label, text, args, factor, reps) in enumerate(cases):
            runs = [run(text, tmp / f"c{k}_{r}", args) for r in range(reps)]
            r0 = runs[0]
            r0["wall"] = float(np.median([x["wall"] for x in runs]))
            c = curve_numbers(r0["hist"], factor)
            e = errors(c, ref)
            h_tip = re.search(r"h_tip: ([0-9.e-]+)", text).group(1)
            tol = re.search(r"tol: ([0-9.e-]+)", text).group(1)
            rows.append((label, h_tip, tol, r0, c, e))
            plot.append((label, h_tip, tol, r0["wall"], e))
            print(f"{label} h_tip {h_tip} tol {tol}: {r0['cells']} cells, {r0['steps']} steps, {r0['newton']} Newton, "
                  f"wall {r0['wall']:.1f} s; P-h {e[0]:.2%}, depth after hold {e[1]:.2%}, creep {e[2]:.2%}")
        # Part 2: direct vs field split on the 3D microindentation mesh, the first steps of the loading
        solver_rows = []
        if not a.quick:
            micro = (ROOT / "input" / "microindent_BN.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
            for solver in ("direct", "fieldsplit"):
                r = run(micro, tmp / f"micro_{solver}", ("-indent_solver", solver, "-max_steps", "5"))
                solver_rows.append((solver, r))
                print(f"microindentation, {solver}: {r['cells']} cells, {r['newton']} Newton its, linear {r['linear']:.2f} s, "
                      f"{r['linear'] / r['newton']:.3f} s per iteration, peak {r['rss_MB']:.0f} MB")

    lines = ["| model | h_tip [um] | tol | cells | steps | Newton its | wall [s] | P-h error | depth after hold | creep depth | P(200 nm) [uN] |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for label, h_tip, tol, r, c, e in rows:
        lines.append(f"| {label} | {h_tip} | {tol} | {r['cells']} | {r['steps']} | {r['newton']} | {r['wall']:.1f} | {e[0]:.2%} | "
                     f"{e[1]:.2%} | {e[2]:.1%} | {c['P_max']:.4g} |")
    solver_lines = ""
    if solver_rows:
        sl = ["| solver | cells | Newton its | linear solves [s] | per Newton iteration [s] | peak memory [MB] |", "|---|---|---|---|---|---|"]
        for solver, r in solver_rows:
            sl.append(f"| {solver} | {r['cells']} | {r['newton']} | {r['linear']:.2f} | {r['linear'] / r['newton']:.3f} | {r['rss_MB']:.0f} |")
        solver_lines = ("\nDirect against field split on the 3D microindentation mesh (`input/microindent_BN.yaml`, the first\n"
                        "5 steps of the loading; one rank; peak resident memory of the whole driver):\n\n" + "\n".join(sl) + "\n")
    section = (f"{TITLE}\n\nCommand: `bench/indent_bench.py --repeats {a.repeats}{' --quick' if a.quick else ''}`. Nanoindentation on kerogen "
               "(load P0 exp(kt) to 200 nm, hold 60 s,\nunload 20 s), one rank. Errors relative to the fine axisymmetric reference: "
               "P-h is the largest depth\ndifference at equal load on the loading branch, over 200 nm; the others are relative. The 3D "
               "rows carry\nthe Berkovich-vs-cone difference besides their discretisation error (the half model's load is doubled).\n"
               "Wall times are medians of the repeats for the axisymmetric rows, single runs otherwise; the machine is shared.\n\n"
               + "\n".join(lines) + "\n" + solver_lines + "\n![error vs time](indent_accuracy.png)\n")
    replace_section(TITLE, section)
    fig = Figure(figsize=(6, 4))
    ax = fig.subplots()
    for label, h_tip, tol, wall, e in plot:
        ax.loglog(wall, max(e[2], 1e-5), "o" if "3D" not in label else "s")
        ax.annotate(f"{'3D' if '3D' in label else 'axi'} {h_tip}/{tol}{' no pred.' if 'predictor' in label else ''}",
                    (wall, max(e[2], 1e-5)), fontsize=7)
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("creep-depth error vs reference")
    ax.set_title("Nanoindentation: accuracy against cost")
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "indent_accuracy.png", dpi=120)
    print("written: docs/performance.md, docs/indent_accuracy.png")


if __name__ == "__main__":
    sys.exit(main())
