#!/usr/bin/env python3
"""FE linear-solver benchmark (issue 13, items 2 and 3): the triaxial cylinder of input/triaxial.yaml on a short
history (one 100 s step at the confinement, then creep under the 40 MPa deviator, adaptive steps, PROPS tol
1e-6) at several mesh sizes, one rank, with each candidate linear solver; time per Newton iteration,
preconditioner set-ups (factorisations), Krylov iterations, memory, and the largest difference of the axial
strain history from plain LU (PETSc's own, a new factorisation at every Newton iteration) in the same run.
Medians of repeats, interleaved. Writes the section "FE solver: defaults by measurement" of
docs/performance.md. --main-job instead runs input/triaxial.yaml as tools/run.sh does (2 ranks), the set-up before
issue 13 against the default, and writes its numbers into the results store docs/results/fe_main_job.json and the
section "FE solver: the triaxial main job" from it (camclay9.fe_main_job_study; tools/doc_numbers.py checks it).

Usage: bench/fe_solver_bench.py [--sizes 5.3,2.5,1.45] [--repeats 2] [--max-steps 0,0,20] [--ranks 1]
       bench/fe_solver_bench.py --main-job [--repeats 3]
"""
import argparse
import os
import re
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import mesh_line, read_history, results_store, run_driver, summary_line
from camclay9 import fe_main_job_study as main_study
from camclay9.launch import MPIEXEC
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TITLE = "## FE solver: defaults by measurement"
PLAIN = "-fe_refactor_its 0 -ksp_type preonly"
CANDIDATES = {  # name: options (the driver's defaults fill in the rest)
    "petsc LU (old 1-rank default; its ordering is nested dissection)": PLAIN + " -pc_factor_mat_solver_type petsc",
    "UMFPACK": PLAIN + " -pc_factor_mat_solver_type umfpack",
    "MUMPS AMD": PLAIN + " -mat_mumps_icntl_7 0",
    "MUMPS PORD": PLAIN + " -mat_mumps_icntl_7 4",
    "MUMPS METIS": PLAIN + " -mat_mumps_icntl_7 5",
    "MUMPS METIS, BLR 1e-8": PLAIN + " -mat_mumps_icntl_35 1 -mat_mumps_cntl_7 1e-8",
    "lagged MUMPS METIS (new default)": "",
    "the same, MatSetValues instead of COO": "-fe_coo false",
    "lagged MUMPS METIS, BLR 1e-8": "-mat_mumps_icntl_35 1 -mat_mumps_cntl_7 1e-8",
    "GAMG (lagged set-up)": "-pc_type gamg",
}
LARGE = ["MUMPS METIS", "lagged MUMPS METIS (new default)", "lagged MUMPS METIS, BLR 1e-8",
         "GAMG (lagged set-up)"]
HISTORY = """stages:
  - {name: hold, duration: 100, pressure: {top: 35, side: 35}, steps: {count: 1}}
  - name: creep
    duration: 3600
    load: instant
    pressure: {top: 75, side: 35}
    steps: {adaptive: true, first: 1.0e-2, max: 2000}
    creep: true
"""


def scene_text(size, history=HISTORY):
    base = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    base = base.replace("size: 6.0", f"size: {size}")
    return base[:base.index("stages:")] + history


def run(scene, out, ranks, opts, max_steps=0):
    options = ["-progress_every", "1000000"] + opts.split() + (["-max_steps", str(max_steps)] if max_steps else [])
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")  # one core per rank: CPU time = work
    # through mpiexec, even on 1 rank: the same launch for every row
    proc = run_driver(scene, out, options, root=ROOT, prefix=[*MPIEXEC, str(ranks)], cwd=ROOT, env=env, timeout=6 * 3600,
                      check=False)
    if proc.returncode:
        return dict(failed=(proc.stdout + proc.stderr)[-300:])
    m, s = mesh_line(proc.stdout), summary_line(proc.stdout, index=0)
    k = re.search(r"fe solver: (\S+), (\d+) Krylov iterations, (\d+) preconditioner set-ups, max RSS ([0-9.]+) MB per rank, "
                  r"([0-9.]+) MB in all, CPU ([0-9.]+) s", proc.stdout)
    h = read_history(out, need=("eps_33",))
    return dict(cells=m["cells"], unknowns=m["unknowns"], steps=s["steps"], newton=s["newton_iterations"],
                cutbacks=s["cutbacks"], assembly=s["assembly_s"], solve_wall=s["wall_s"], wall=proc.wall,
                cpu=proc.cpu, solver=k.group(1), krylov=int(k.group(2)),
                setups=int(k.group(3)), rss=float(k.group(4)), rss_all=float(k.group(5)), solve_cpu=float(k.group(6)), eps33=h["eps_33"], time=h["time"],
                stage=h["stage"])


OLD = "-fe_refactor_its 0 -ksp_type preonly -fe_coo false -mat_mumps_icntl_7 7"  # main before issue 13 on 2 ranks
SETUPS = {"old (MUMPS each Newton iteration, MatSetValues)": OLD, "default": ""}


def main_job(repeats, tmp):
    """input/triaxial.yaml as tools/run.sh runs it (2 ranks), the old set-up against the default, interleaved: the
    store's rows (camclay9.fe_main_job_study)."""
    scene = Path(tmp) / "main.yaml"
    scene.write_text((ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/"))
    res = {name: [] for name in SETUPS}
    for k in range(repeats):
        for name, opts in SETUPS.items():
            r = run(scene, Path(tmp) / f"main_{k}_{len(res[name])}_{name[:3]}", 2, opts)
            if "failed" in r:
                raise SystemExit(f"main job, {name}: failed\n{r['failed']}")
            res[name].append(r)
    rows = []
    for name, runs in res.items():
        r = median_run(runs)
        at = np.where(r["stage"] == 1)[0]
        t = r["time"][at] - r["time"][at[0]]
        eps = -(r["eps33"][at] - r["eps33"][at[0]])
        rows.append({"setup": name, "options": SETUPS[name], "steps": r["steps"], "newton": r["newton"],
                     "krylov": r["krylov"], "setups": r["setups"], "wall": r["solve_wall"], "cpu": r["solve_cpu"],
                     "creep_1h": float(np.interp(3600.0, t, eps)), "creep_10h": float(np.interp(36000.0, t, eps))})
    return rows


def median_run(runs):
    r = dict(runs[0])
    for key in ("wall", "cpu", "solve_wall", "solve_cpu", "assembly"):
        r[key] = float(np.median([x[key] for x in runs]))
    return r


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="5.3,2.5,1.45", help="element sizes [mm] (about 1k, 10k, 50k tets)")
    ap.add_argument("--max-steps", default="0,0,16", help="per size: stop after N steps (0: the whole history)")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--large-from", type=int, default=2, help="from this size index on, only the shortlist")
    ap.add_argument("--no-doc", action="store_true")
    ap.add_argument("--main-job", action="store_true", help="only the main job, old set-up against new (2 ranks)")
    a = ap.parse_args(argv)
    if a.main_job:
        load = os.getloadavg()[0]
        with tempfile.TemporaryDirectory() as tmp:
            rows = main_job(a.repeats, tmp)
        rev = results_store.revision(ROOT)
        store = {"provenance": {"command": f"bench/fe_solver_bench.py --main-job --repeats {a.repeats}",
                                "date": time.strftime("%Y-%m-%d"), "rev": rev, "load": [load, os.getloadavg()[0]]}, "rows": rows}
        section = main_study.section(store)
        print(section)
        if not a.no_doc:
            results_store.save(main_study.STORE, store)
            replace_section(main_study.TITLE, section)
        return 0
    sizes = [float(x) for x in a.sizes.split(",")]
    caps = [int(x) for x in a.max_steps.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, size in enumerate(sizes):
            scene = Path(tmp) / f"s{size}.yaml"
            scene.write_text(scene_text(size))
            names = list(CANDIDATES) if i < a.large_from else [n for n in CANDIDATES if n in LARGE]
            res = {n: [] for n in names}
            for rep in range(a.repeats):  # interleaved: every candidate once per round
                for n in names:
                    r = run(scene, Path(tmp) / f"o{i}_{rep}_{abs(hash(n))}", a.ranks, CANDIDATES[n], caps[i])
                    res[n].append(r)
                    if "failed" in r:
                        print(f"size {size} {n}: FAILED {r['failed']}", flush=True)
            ref = None
            for n in names:
                good = [r for r in res[n] if "failed" not in r]
                if not good:
                    rows.append((size, n, None, None))
                    continue
                r = median_run(good)
                if ref is None:
                    ref = r  # the first candidate: plain LU (or, on the shortlist, its first entry)
                    refname = n
                err = np.nan
                if len(r["eps33"]) == len(ref["eps33"]) and np.allclose(r["time"], ref["time"], rtol=1e-12):
                    d = ref["eps33"] - ref["eps33"][0]
                    err = float(np.max(np.abs((r["eps33"] - r["eps33"][0]) - d)) / np.max(np.abs(d)))
                rows.append((size, n, r, (err, refname)))
                print(f"size {size}: {r['cells']} cells {r['unknowns']} unknowns, {n}: {r['steps']} steps {r['newton']} Newton "
                      f"{r['krylov']} Krylov {r['setups']} set-ups, solve wall {r['solve_wall']:.2f} s (process wall {r['wall']:.2f} s, "
                      f"cpu {r['cpu']:.2f} s), solve CPU {r['solve_cpu']:.2f} s, {1e3 * r['solve_cpu'] / max(r['newton'], 1):.1f} ms CPU/Newton, RSS {r['rss']:.0f} MB, "
                      f"diff {err:.1e}", flush=True)
    lines = ["| cells | unknowns | solver | steps | Newton its | Krylov its | set-ups | wall [s] | CPU [s] | CPU ms per Newton it. | "
             "max RSS [MB] | axial strain vs reference |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for size, n, r, e in rows:
        if r is None:
            lines.append(f"| | | {n} | failed | | | | | | | | |")
            continue
        lines.append(f"| {r['cells']} | {r['unknowns']} | {n} | {r['steps']} | {r['newton']} | {r['krylov']} | {r['setups']} | "
                     f"{r['solve_wall']:.2f} | {r['solve_cpu']:.2f} | {1e3 * r['solve_cpu'] / max(r['newton'], 1):.1f} | {r['rss']:.0f} | "
                     f"{e[0]:.1e} |")
    print("\n".join(lines))
    if not a.no_doc:
        section = (f"{TITLE}\n\nCommand: `bench/fe_solver_bench.py --sizes {a.sizes} --max-steps {a.max_steps} --repeats {a.repeats}`"
                   f" ({a.ranks} rank, one BLAS thread). The triaxial cylinder on a short history (one 100 s step at the confinement, then "
                   "creep under the deviator, adaptive steps; on the largest mesh only the first steps, `--max-steps`), each "
                   "candidate run in turn, medians of the repeats. Wall and CPU: of the stepping (the stage runner's wall clock, "
                   "the process's CPU clock from the solver set-up on; meshing excluded); the choice is made on CPU time, "
                   "less disturbed by the other jobs than the wall clock. The last column: the largest difference of the axial strain history "
                   "from the first row of the mesh (plain LU; on the largest mesh the first of the shortlist), relative to "
                   "its creep strain. Measured on a shared 2-core machine with other jobs running: rough numbers.\n\n"
                   + "\n".join(lines) + "\n")
        replace_section(TITLE, section)
        print("written: docs/performance.md")


if __name__ == "__main__":
    sys.exit(main())
