#!/usr/bin/env python3
"""Speed and accuracy of the triaxial creep point (issue #3 benchmark): the shipped scene
input/point/triaxial_creep_theta0.yaml run with the UMAT's step tolerance (PROPS(20)) over five decades.
For each tolerance: the median wall time of repeated runs (the driver's own timing of the run, without
start-up), the steps taken, and the relative error of the creep strain at 1 h and 10 h against the
independent Radau integration (camclay9.reference) with the same hold. Writes a table and a plot into
docs/ (performance.md section "Material point: triaxial creep, accuracy against cost").

Usage: bench/point_creep_accuracy.py [--repeats 5] [--driver build/bin/driver]
"""
import argparse
import json
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import read_history, run_driver, summary_line
from camclay9 import reference as ref
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]

TOLS = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
TIMES = (3600.0, 36000.0)


def run(driver, scene, outdir):
    s = summary_line(run_driver(scene, outdir, driver=driver, root=ROOT, timeout=3600).stdout)
    return s["steps"], s["cutbacks"], s["wall_s"]


def creep_errors(outdir):
    meta = json.loads((outdir / "scene.json").read_text())
    h = read_history(outdir, need=("stage", "eps_33"))
    rows = np.where(h["stage"] == 1)[0]
    t = h["time"][rows] - h["time"][rows[0]]
    eps = h["eps_33"][rows] - h["eps_33"][rows[0]]
    n, sig0 = [0.0, 0.0, 1.0], -35.0 * np.eye(3)
    held = ref.creep_mixture(ref.WOODFORD, n, sig0, sig0, [meta["segments"][0]["t_end"]], rtol=1e-10)
    sol = ref.creep_mixture(ref.WOODFORD, n, sig0, np.diag([-35.0, -35.0, -75.0]), list(TIMES), rtol=1e-10,
                            evp0_hard=held["evp_hard"][-1], evp0_soft=held["evp_soft"][-1])
    exact = [sol["strain"][k][2] - sol["strain0"][2] for k in range(len(TIMES))]
    return [abs(np.interp(tt, t, eps) - e) / abs(e) for tt, e in zip(TIMES, exact)]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--driver", default=None, help="the driver (default: $DRIVER or build/bin/driver)")
    a = ap.parse_args(argv)
    base = (ROOT / "input/point/triaxial_creep_theta0.yaml").read_text()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for tol in TOLS:
            scene = tmp / f"tol{tol:g}.yaml"
            scene.write_text(base.replace("tol: 2.0e-7", f"tol: {tol:g}"))
            walls = []
            for r in range(a.repeats):
                steps, cutbacks, wall = run(a.driver, scene, tmp / f"out{tol:g}")
                walls.append(wall)
            err = creep_errors(tmp / f"out{tol:g}")
            rows.append((tol, steps, cutbacks, float(np.median(walls)), err[0], err[1]))
            print(f"tol {tol:8.1e}: {steps:6d} steps, {cutbacks:4d} cutbacks, median {np.median(walls) * 1e3:8.2f} ms, "
                  f"error at 1 h {err[0]:.2e}, at 10 h {err[1]:.2e}")
    table = ["| tol (PROPS 20) | steps | cutbacks | median wall [ms] | error at 1 h | error at 10 h |",
             "|---|---|---|---|---|---|"]
    table += [f"| {r[0]:.0e} | {r[1]} | {r[2]} | {r[3] * 1e3:.2f} | {r[4]:.2e} | {r[5]:.2e} |" for r in rows]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    w = [r[3] * 1e3 for r in rows]
    for k, label in ((4, "creep strain at 1 h"), (5, "creep strain at 10 h")):
        ax.loglog(w, [r[k] for r in rows], "o-", label=label)
    for r in rows:
        ax.annotate(f"tol {r[0]:.0e}", (r[3] * 1e3, r[4]), fontsize=7, textcoords="offset points", xytext=(4, 4))
    ax.set_xlabel("median wall time of the run [ms]")
    ax.set_ylabel("relative error against Radau")
    ax.set_title("Triaxial creep point, theta = 0: accuracy against cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "point_creep_accuracy.png", dpi=110)
    section = ("## Material point: triaxial creep, accuracy against cost\n\n"
               f"Command: `bench/point_creep_accuracy.py --repeats {a.repeats}`. The shipped scene\n"
               "`input/point/triaxial_creep_theta0.yaml` (hold at -35 MPa to a viscoplastic rate of 1e-13 /s, then\n"
               "sigma_d = 40 MPa for 10 h, adaptive steps driven by the UMAT's PNEWDT) with the step tolerance\n"
               "PROPS(20) over four decades. Wall time: median over the repeats of the driver's own timing of\n"
               "the run (no process start-up). Error: relative error of the creep strain against an independent\n"
               "Radau integration (rtol 1e-10) with the same hold. The shipped default is tol = 2e-7.\n\n"
               + "\n".join(table) + "\n\n![accuracy against cost](point_creep_accuracy.png)\n")
    replace_section("## Material point: triaxial creep, accuracy against cost", section)
    print("written: docs/performance.md, docs/point_creep_accuracy.png")
    return 0


if __name__ == "__main__":
    sys.exit(main())
