#!/usr/bin/env python3
"""FE benchmark of input/triaxial.yaml (issue #4): time to solution at three mesh sizes and two step
tolerances, the creep error against the finest run, the time per Newton iteration split into assembly
(UMAT calls included) and the rest (linear solves), and 1 vs 2 MPI ranks. Median of repeated runs.
Writes its numbers into the results store (docs/results/fe_triaxial.json, which README.md and docs/paper.md quote) and
the section "FE: triaxial cylinder" of docs/performance.md from that store (camclay9.fe_triaxial_study;
tools/doc_numbers.py checks the section against the store).

Usage: bench/fe_triaxial.py [--repeats 3]
"""
import argparse
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import fe_triaxial_study as study
from camclay9 import mesh_line, read_history, results_store, run_driver, summary_line
from camclay9.launch import MPIEXEC
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]


def run(scene, out, ranks):
    proc = run_driver(scene, out, root=ROOT, prefix=[*MPIEXEC, str(ranks)], cwd=ROOT, timeout=6 * 3600)  # 1 rank too
    wall = proc.wall
    cells = mesh_line(proc.stdout)["cells"]
    m = summary_line(proc.stdout, index=0)
    h = read_history(out, need=("newton_its", "stage", "eps_33"))
    newton = int(h["newton_its"].sum())
    rows = np.where(h["stage"] == 1)[0]
    t = h["time"][rows] - h["time"][rows[0]]
    eps = -(h["eps_33"][rows] - h["eps_33"][rows[0]])
    creep = [float(np.interp(x, t, eps)) for x in (3600.0, 36000.0)]
    return dict(cells=cells, steps=m["steps"], newton=newton, assembly=m["assembly_s"], wall=wall, creep=creep)


def store_rows(results):
    """The store's rows (camclay9.fe_triaxial_study): each run's numbers, its time per Newton iteration split into
    assembly and the rest, and its creep's relative errors against the finest run's."""
    finest = study.finest([dict(size=size, tol=tol, creep=r["creep"]) for size, tol, _, r in results])["creep"]
    rows = []
    for size, tol, ranks, r in results:
        e = [abs(c - f) / abs(f) for c, f in zip(r["creep"], finest)]
        per = 1e3 / max(r["newton"], 1)
        rows.append(dict(size=size, tol=tol, ranks=ranks, cells=r["cells"], steps=r["steps"], newton=r["newton"],
                         wall=r["wall"], assembly_ms=r["assembly"] * per, rest_ms=(r["wall"] - r["assembly"]) * per,
                         err_1h=e[0], err_10h=e[1]))
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args(argv)
    base = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    cases = [(6.0, 1e-6, 1), (6.0, 1e-6, 2), (4.0, 1e-6, 2), (3.0, 1e-6, 2), (4.0, 1e-7, 2), (3.0, 1e-7, 2)]
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for size, tol, ranks in cases:
            scene = Path(tmp) / f"s{size}_{tol}.yaml"
            scene.write_text(base.replace("size: 6.0", f"size: {size}").replace("tol: 1.0e-6", f"tol: {tol:g}"))
            runs = [run(scene, Path(tmp) / f"o{size}_{tol}_{ranks}_{k}", ranks) for k in range(a.repeats)]
            r = runs[0]
            r["wall"] = float(np.median([x["wall"] for x in runs]))
            r["assembly"] = float(np.median([x["assembly"] for x in runs]))
            results.append((size, tol, ranks, r))
            print(f"size {size} tol {tol:g} ranks {ranks}: {r['cells']} cells, {r['steps']} steps, {r['newton']} Newton, "
                  f"wall {r['wall']:.1f} s (assembly {r['assembly']:.1f} s), creep 1 h {r['creep'][0]:.4e}, 10 h {r['creep'][1]:.4e}")
    store = {"provenance": {"command": f"bench/fe_triaxial.py --repeats {a.repeats}", "date": time.strftime("%Y-%m-%d"),
                            "section": f"docs/performance.md, '{study.TITLE[3:]}'"},
             "rows": store_rows(results), "shipped": {"size": 6, "tol": 1e-6}}   # input/triaxial.yaml's
    section = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    replace_section(study.TITLE, section)
    results_store.save(study.STORE, store)
    print(f"written: docs/performance.md, docs/results/{study.STORE}.json")


if __name__ == "__main__":
    sys.exit(main())
