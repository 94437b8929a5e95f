#!/usr/bin/env python3
"""Scaling study (issue 13, item 4): the triaxial cylinder of input/triaxial.yaml from about 1e4 unknowns to
the largest mesh this machine runs in reasonable time, on 1 and 2 MPI ranks, with the direct solver (MUMPS in
GMRES, factorisation kept; asked for by name, since the driver takes GAMG itself above -fe_gamg_above) and with GAMG (-pc_type gamg, rigid-body near null space): time per
Newton iteration, its parts (-log_view: residual with the UMAT, Jacobian, preconditioner set-up, Krylov
solve), Krylov iterations, memory (largest RSS of a rank and the sum over the ranks). The history: one 100 s
step at the confinement, then the first steps of the creep under the deviator (--max-steps in all). Each mesh
is made once by gmsh and read by every run. The axial strain history of each run is compared with the
direct one-rank run on the same mesh. Keeps every number in docs/results/fe_scaling.json and writes the section
"FE scaling: 1 and 2 ranks, direct and GAMG" of docs/performance.md from it (camclay9.fe_scaling_study).

Usage: bench/scaling_bench.py [--sizes 2.4,1.13,0.78] [--gamg-only 0.62] [--max-steps 5] [--repeats 1] [--ranks 1,2]
                              [--merge] [--no-doc]
       bench/scaling_bench.py --from-store
"""
import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import fe_scaling_study as study
from camclay9 import mesh_line, partition_line, read_history, results_store, run_driver, summary_line
from camclay9.launch import MPIEXEC
from fe_solver_bench import HISTORY
from camclay9.performance_doc import publish, republish

ROOT = Path(__file__).resolve().parents[1]
TITLE = "## FE scaling: 1 and 2 ranks, direct and GAMG"
# the driver picks GAMG above -fe_gamg_above unknowns by itself: each solver is asked for by name here
SOLVERS = {"direct": "-fe_gamg_above 2000000000", "GAMG": "-pc_type gamg"}
EVENTS = {"residual": "CC9 residual+UMAT", "jacobian": "CC9 Jacobian", "pcsetup": "PCSetUp", "ksp": "KSPSolve"}


def make_mesh(size, out):
    cmd = ["gmsh", "-3", "-format", "msh41", "-v", "2", "-setnumber", "R", "12.7", "-setnumber", "H", "50.8",
           "-setnumber", "size", str(size), str(ROOT / "meshes" / "cylinder.geo"), "-o", str(out)]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, timeout=3 * 3600)
    return time.perf_counter() - t0


def scene_text(msh):
    base = (ROOT / "input" / "triaxial.yaml").read_text()
    head = base[:base.index("mesh:")]
    rest = base[base.index("material:"):base.index("stages:")]
    return head + f"mesh:\n  file: {msh}\n  order: 1\n" + rest + HISTORY


def run(scene, out, ranks, opts, max_steps):
    options = ["-progress_every", "1000000", "-max_steps", str(max_steps), "-log_view"] + opts.split()
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    proc = run_driver(scene, out, options, root=ROOT, prefix=[*MPIEXEC, str(ranks)], cwd=ROOT, env=env, timeout=6 * 3600,
                      check=False)
    wall = proc.wall
    if proc.returncode:
        return dict(failed=(proc.stdout + proc.stderr)[-400:])
    m, s = mesh_line(proc.stdout), summary_line(proc.stdout, index=0)
    k = re.search(r"fe solver: (\S+), (\d+) Krylov iterations, (\d+) preconditioner set-ups, max RSS ([0-9.]+) MB per rank, "
                  r"([0-9.]+) MB in all, CPU ([0-9.]+) s", proc.stdout)
    ev = {}
    for key, name in EVENTS.items():  # -log_view: name, count, ratio, max time
        e = re.search(rf"^{re.escape(name)}\s+(\d+) \S+ (\S+)", proc.stdout, re.M)
        ev[key] = float(e.group(2)) if e else 0.0
    h, part = read_history(out, need=("eps_33",)), partition_line(proc.stdout)
    return dict(partition={k: part[k] for k in ("type", "vertices", "copies")} if part else None, cells=m["cells"], unknowns=m["unknowns"], steps=s["steps"], newton=s["newton_iterations"],
                cutbacks=s["cutbacks"], solve_wall=s["wall_s"], wall=wall, solver=k.group(1), krylov=int(k.group(2)),
                setups=int(k.group(3)), rss=float(k.group(4)), rss_all=float(k.group(5)), cpu=float(k.group(6)), ev=ev,
                eps33=h["eps_33"])


def measure(a):
    """Every (mesh, ranks, solver) run the arguments ask for: [(ranks, solver, the run's numbers)], each compared with
    the 1-rank direct run on its mesh (on the GAMG-only meshes, the 1-rank GAMG run)."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        gamg_only = [float(x) for x in a.gamg_only.split(",") if x]
        for size in [float(x) for x in a.sizes.split(",") if x] + gamg_only:
            msh = Path(tmp) / f"cyl{size}.msh"
            tmesh = make_mesh(size, msh)
            scene = Path(tmp) / f"s{size}.yaml"
            scene.write_text(scene_text(msh))
            ref = None
            for ranks in [int(x) for x in a.ranks.split(",")]:
                for name, opts in SOLVERS.items():
                    if size in gamg_only and name != "GAMG":
                        continue
                    runs = [run(scene, Path(tmp) / f"o{size}_{ranks}_{len(rows)}_{k}", ranks, opts, a.max_steps) for k in range(a.repeats)]
                    good = [r for r in runs if "failed" not in r]
                    if not good:
                        print(f"size {size} ranks {ranks} {name}: FAILED {runs[0]['failed']}", flush=True)
                        continue
                    r = good[0]
                    for key in ("wall", "solve_wall", "cpu"):
                        r[key] = float(np.median([x[key] for x in good]))
                    if ref is None or size in gamg_only and ranks == 1:
                        ref = r  # the 1-rank direct run (GAMG-only sizes: the 1-rank GAMG run)
                    d = ref["eps33"] - ref["eps33"][0]
                    n = min(len(r["eps33"]), len(ref["eps33"]))
                    r["diff"] = float(np.max(np.abs(r["eps33"][:n] - ref["eps33"][:n])) / np.max(np.abs(d)))
                    r["tmesh"] = tmesh
                    rows.append((ranks, name, r))
                    per = 1e3 / max(r["newton"], 1)
                    print(f"size {size}: {r['cells']} cells {r['unknowns']} unknowns (gmsh {tmesh:.1f} s), {ranks} rank(s) {name}: "
                          f"{r['steps']} steps {r['newton']} Newton {r['krylov']} Krylov {r['setups']} set-ups, wall {r['solve_wall']:.2f} s "
                          f"CPU {r['cpu']:.2f} s, per Newton {r['solve_wall'] * per:.0f} ms; residual {r['ev']['residual'] * per:.0f} ms, "
                          f"Jacobian {r['ev']['jacobian'] * per:.0f} ms, PC set-up {r['ev']['pcsetup'] * per:.0f} ms, KSP {r['ev']['ksp'] * per:.0f} ms; "
                          f"RSS {r['rss']:.0f} MB/rank, {r['rss_all']:.0f} MB in all, diff {r['diff']:.1e}", flush=True)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="2.4,1.13,0.78", help="element sizes [mm]")
    ap.add_argument("--max-steps", type=int, default=5, help="steps in all (1 hold, the rest creep)")
    ap.add_argument("--repeats", type=int, default=1)
    ap.add_argument("--ranks", default="1,2")
    ap.add_argument("--gamg-only", default="", help="further (larger) sizes run with GAMG only")
    ap.add_argument("--no-doc", action="store_true", help="print the table; write neither the store nor the section")
    ap.add_argument("--from-store", action="store_true", help="write the section from the store, without running")
    ap.add_argument("--merge", action="store_true", help="keep the store's rows of other (mesh, ranks, solver) runs")
    a = ap.parse_args(argv)
    if a.from_store:
        return republish(study, write=not a.no_doc) or 0
    load0 = os.getloadavg()[0]
    rows = measure(a)
    keep = ("cells", "unknowns", "steps", "newton", "cutbacks", "krylov", "setups", "solve_wall", "cpu", "rss", "rss_all",
            "ev", "diff", "tmesh", "partition")
    new = [dict(ranks=ranks, solver=name, driver_solver=r["solver"], **{k: r[k] for k in keep}) for ranks, name, r in rows]
    command = "bench/scaling_bench.py " + shlex.join(argv if argv is not None else sys.argv[1:])
    record = {"command": command, "date": time.strftime("%Y-%m-%d"), "rev": results_store.revision(ROOT),
              "load": [load0, os.getloadavg()[0]], "max_steps": a.max_steps}
    old = results_store.load(study.STORE) if a.merge else {}
    store = study.merged(old, new, record)
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
