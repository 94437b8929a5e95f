#!/usr/bin/env python3
"""Speed and accuracy of the triaxial creep point (issue #3 benchmark): the shipped scene
input/point/triaxial_creep_theta0.yaml run with the UMAT's step tolerance (PROPS(20)) over five decades.
For each tolerance: the median wall time of repeated runs (the driver's own timing of the run, without
start-up), the steps taken, and the relative error of the creep strain at 1 h and 10 h against the
independent Radau integration (camclay9.reference) with the same hold. Keeps every number of the table in the
results store docs/results/point_creep.json and writes from it the section "Material point: triaxial creep, accuracy
against cost" of docs/performance.md (camclay9.point_creep_study, which tools/doc_numbers.py checks) and its plot
docs/point_creep_accuracy.png.

Usage: bench/point_creep_accuracy.py [--repeats 5] [--driver build/bin/driver] [--machine NOTE] [--no-doc]
"""
import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import point_creep_study as study
from camclay9 import read_history, results_store, run_driver, summary_line
from camclay9 import reference as ref
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]

TOLS = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
TIMES = (3600.0, 36000.0)
SHIPPED = "tol: 2.0e-7"   # the scene's PROPS(20)


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


def plot(rows, path):
    """The plot of the section: each tolerance's error at 1 h and 10 h against its median wall time."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    w = [r["wall_s"] * 1e3 for r in rows]
    for k, label in (("err_1h", "creep strain at 1 h"), ("err_10h", "creep strain at 10 h")):
        ax.loglog(w, [r[k] for r in rows], "o-", label=label)
    for r in rows:
        ax.annotate(f"tol {r['tol']:.0e}", (r["wall_s"] * 1e3, r["err_1h"]), fontsize=7, textcoords="offset points",
                    xytext=(4, 4))
    ax.set_xlabel("median wall time of the run [ms]")
    ax.set_ylabel("relative error against Radau")
    ax.set_title("Triaxial creep point, theta = 0: accuracy against cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def measure(driver, repeats):
    """One row per tolerance of TOLS: steps, cutbacks, the repeats' wall times and their median, the two errors."""
    base = (ROOT / "input/point/triaxial_creep_theta0.yaml").read_text()
    assert SHIPPED in base, f"input/point/triaxial_creep_theta0.yaml: '{SHIPPED}' not in it"
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for tol in TOLS:
            scene = tmp / f"tol{tol:g}.yaml"
            scene.write_text(base.replace(SHIPPED, f"tol: {tol:g}"))
            walls = []
            for r in range(repeats):
                steps, cutbacks, wall = run(driver, scene, tmp / f"out{tol:g}")
                walls.append(wall)
            err = creep_errors(tmp / f"out{tol:g}")
            rows.append({"tol": tol, "steps": steps, "cutbacks": cutbacks, "wall_s": float(np.median(walls)),
                         "walls_s": walls, "err_1h": float(err[0]), "err_10h": float(err[1])})
            print(f"tol {tol:8.1e}: {steps:6d} steps, {cutbacks:4d} cutbacks, median {np.median(walls) * 1e3:8.2f} ms, "
                  f"error at 1 h {err[0]:.2e}, at 10 h {err[1]:.2e}")
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--driver", default=None, help="the driver (default: $DRIVER or build/bin/driver)")
    ap.add_argument("--machine", default="a shared 2-core machine",
                    help="the machine note the store and the section carry (default: %(default)s)")
    ap.add_argument("--no-doc", action="store_true",
                    help="print the section; write neither the store, the plot nor the document")
    a = ap.parse_args(argv)
    rows = measure(a.driver, a.repeats)
    store = {"provenance": {"command": f"bench/point_creep_accuracy.py --repeats {a.repeats}",
                            "date": time.strftime("%Y-%m-%d", time.gmtime()), "machine": a.machine},
             "shipped_tol": float(SHIPPED.split(":")[1]), "rows": rows}
    section = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(section)
    if not a.no_doc:
        plot(store["rows"], ROOT / "docs" / "point_creep_accuracy.png")
        replace_section(study.TITLE, section)
        results_store.save(study.STORE, store)
        print(f"written: docs/performance.md, docs/point_creep_accuracy.png, docs/results/{study.STORE}.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
