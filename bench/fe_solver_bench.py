#!/usr/bin/env python3
"""FE linear-solver benchmark (issue 13, items 2, 3 and 6): the triaxial cylinder of input/triaxial.yaml on a short
history (one 100 s step at the confinement, then creep under the 40 MPa deviator, adaptive steps, PROPS tol 1e-6) at
several mesh sizes, one rank, with each candidate linear solver (camclay9.fe_solver_study.CANDIDATES, every run with
-log_view); time per Newton iteration, preconditioner set-ups (factorisations), Krylov iterations, memory, where the
time goes, and the largest difference of the axial strain history from the mesh's first candidate in the same run.
Medians of repeats, interleaved. Before the runs (not with --merge), a probe on the first mesh: the Jacobians of the
default run (-ksp_view_mat binary) for their asymmetry, PETSc LU's ordering (-ksp_view), and what MUMPS reports when
asked for each ordering (its diagnostics, -mat_mumps_icntl_4 2). Every number goes into the results store
docs/results/fe_solver.json, and the section "FE solver: defaults by measurement" of docs/performance.md is written
from it (camclay9.fe_solver_study; tools/doc_numbers.py checks it). --merge replaces only the rows (mesh, candidate)
run and keeps the store's others and its probe; --from-store rewrites the section from the store without running.

--main-job instead runs input/triaxial.yaml as tools/run.sh does (2 ranks), the set-up before issue 13 against the
default, and writes its numbers into docs/results/fe_main_job.json and the section "FE solver: the triaxial main job"
from it (camclay9.fe_main_job_study).

Usage: bench/fe_solver_bench.py [--sizes 5.3,2.5,1.45] [--repeats 2] [--max-steps 0,0,16] [--large-from 2] [--ranks 1]
                                [--merge] [--machine TEXT] [--no-doc]
       bench/fe_solver_bench.py --from-store [--no-doc]
       bench/fe_solver_bench.py --main-job [--repeats 3]
The section's two commands: --sizes 5.3,2.5 --repeats 2, then --sizes 1.45 --max-steps 10 --large-from 0 --repeats 1
--merge.
"""
import argparse
import os
import re
import shlex
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml
from camclay9 import mesh_line, read_history, results_store, run_driver, summary_line
from camclay9 import fe_main_job_study as main_study
from camclay9 import fe_solver_study as study
from camclay9.launch import MPIEXEC
from camclay9.performance_doc import publish, replace_section, republish

ROOT = Path(__file__).resolve().parents[1]
HISTORY = """stages:
  - {name: hold, duration: 100, pressure: {top: 35, side: 35}, steps: {count: 1}}
  - name: creep
    duration: 3600
    load: instant
    pressure: {top: 75, side: 35}
    steps: {adaptive: true, first: 1.0e-2, max: 2000}
    creep: true
"""
ENV = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")  # one core per rank: CPU time = work


def scene_text(size, history=HISTORY):
    base = (ROOT / "input" / "triaxial.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    base = base.replace("size: 6.0", f"size: {size}")
    return base[:base.index("stages:")] + history


def history_figures():
    """The short history's figures for the store, read from HISTORY and input/triaxial.yaml."""
    hold, creep = yaml.safe_load(HISTORY)["stages"]
    tol = yaml.safe_load((ROOT / "input" / "triaxial.yaml").read_text())["material"]["set"]["tol"]
    return {"hold_s": hold["duration"], "creep_s": creep["duration"], "first_dt": creep["steps"]["first"],
            "max_dt": creep["steps"]["max"], "tol": tol}


def events(text):
    """{event: {"count", "s"}} of study.EVENTS from a -log_view table (count and time: the largest over the ranks)."""
    out = {}
    for e in study.EVENTS:
        m = re.search(rf"^{re.escape(e)}\s+(\d+) [0-9.]+ ([0-9.]+e[+-]\d+)", text, re.M)
        if not m:
            raise SystemExit(f"-log_view: no event {e!r} in the driver's output")
        out[e] = {"count": int(m[1]), "s": float(m[2])}
    return out


def launch(scene, out, ranks, options, timeout=6 * 3600):
    # through mpiexec, even on 1 rank: the same launch for every row
    return run_driver(scene, out, ["-progress_every", "1000000"] + options, root=ROOT, prefix=[*MPIEXEC, str(ranks)],
                      cwd=ROOT, env=ENV, timeout=timeout, check=False)


def run(scene, out, ranks, opts, max_steps=0, log_view=False):
    proc = launch(scene, out, ranks, opts.split() + (["-max_steps", str(max_steps)] if max_steps else [])
                  + (["-log_view"] if log_view else []))
    if proc.returncode:
        return dict(failed=(proc.stdout + proc.stderr)[-300:])
    m, s = mesh_line(proc.stdout), summary_line(proc.stdout, index=0)
    k = re.search(r"fe solver: (\S+), (\d+) Krylov iterations, (\d+) preconditioner set-ups, max RSS ([0-9.]+) MB per rank, "
                  r"([0-9.]+) MB in all, CPU ([0-9.]+) s", proc.stdout)
    h = read_history(out, need=("eps_33",))
    return dict(cells=m["cells"], unknowns=m["unknowns"], steps=s["steps"], newton=s["newton_iterations"],
                cutbacks=s["cutbacks"], assembly=s["assembly_s"], solve_wall=s["wall_s"], wall=proc.wall, cpu=proc.cpu,
                solver=k.group(1), krylov=int(k.group(2)), setups=int(k.group(3)), rss=float(k.group(4)),
                rss_all=float(k.group(5)), solve_cpu=float(k.group(6)), eps33=h["eps_33"], time=h["time"], stage=h["stage"],
                events=events(proc.stdout) if log_view else {})


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


def petsc_matrices(path):
    """The matrices of a PETSc binary file (MatView, one after the other; 32-bit indices, big-endian doubles: PETSc's
    binary format, https://petsc.org/release/manualpages/Mat/MatLoad/) as scipy CSR matrices."""
    import scipy.sparse as sp
    data, at = path.read_bytes(), 0
    while at < len(data):
        cls, m, n, nz = (int(x) for x in np.frombuffer(data, ">i4", 4, at))
        if cls != 1211216:   # MAT_FILE_CLASSID
            raise SystemExit(f"{path}: not a PETSc matrix at byte {at}")
        lens = np.frombuffer(data, ">i4", m, at + 16)
        cols = np.frombuffer(data, ">i4", nz, at + 16 + 4 * m)
        vals = np.frombuffer(data, ">f8", nz, at + 16 + 4 * (m + nz))
        at += 16 + 4 * (m + nz) + 8 * nz
        yield sp.csr_matrix((vals, cols, np.concatenate([[0], np.cumsum(lens)])), shape=(m, n))


def driver_text(scene, out, opts, max_steps=0):
    """One probe run's output (it must succeed)."""
    proc = launch(scene, out, 1, opts.split() + (["-max_steps", str(max_steps)] if max_steps else []), timeout=3600)
    if proc.returncode:
        raise SystemExit(f"probe {opts}: failed\n{(proc.stdout + proc.stderr)[-2000:]}")
    return proc.stdout


def probe(size, tmp):
    """What the solvers report on the mesh of element size `size`: the default run's Jacobians' largest asymmetry,
    PETSc LU's ordering, MUMPS' version and what it does when asked for each ordering (study.ORDERING_PROBES)."""
    import scipy.sparse.linalg as sla
    scene = Path(tmp) / f"probe{size}.yaml"
    scene.write_text(scene_text(size))
    mats = Path(tmp) / "jacobians.bin"
    text = driver_text(scene, Path(tmp) / "probe_j", f"-ksp_view_mat binary:{mats}::append")
    asym = [sla.norm(A - A.T, "fro") / sla.norm(A, "fro") for A in petsc_matrices(mats)]
    lu = driver_text(scene, Path(tmp) / "probe_lu", study.CANDIDATES[study.LU] + " -ksp_view", max_steps=1)
    order = re.search(r"matrix ordering: (\S+)", lu)
    out = {"size": size, "cells": mesh_line(text)["cells"], "jacobians": len(asym), "asymmetry": float(max(asym)),
           "petsc_ordering": order[1] if order else "", "mumps_version": "", "orderings": {}}
    for k, (_, opts) in study.ORDERING_PROBES.items():
        t = driver_text(scene, Path(tmp) / f"probe_{len(out['orderings'])}", opts, max_steps=1)
        v, o = re.search(r"Entering DMUMPS (\d[\d.]*)", t), re.search(r"Ordering based on (\w+)", t)
        out["mumps_version"] = out["mumps_version"] or (v[1] if v else "")
        warnings = list(dict.fromkeys(" ".join(x.split()) for x in re.findall(r"^.*WARNING.*$", t, re.M)))
        out["orderings"][k] = {"options": opts, "ordering": o[1] if o else "", "warnings": warnings}
    print(f"probe: {out}", flush=True)
    return out


def stored_row(size, name, runs, cap, ref, hists):
    """The store's row of one candidate on one mesh from its runs (medians of the repeats): its history compared with
    the reference's (ref: the mesh's first candidate's median run) and the earlier candidates' (hists)."""
    r = median_run(runs)
    err = None
    if len(r["eps33"]) == len(ref["eps33"]) and np.allclose(r["time"], ref["time"], rtol=1e-12):
        d = ref["eps33"] - ref["eps33"][0]
        err = float(np.max(np.abs((r["eps33"] - r["eps33"][0]) - d)) / np.max(np.abs(d)))
    same = [n for n, h in hists.items() if np.array_equal(h["time"], r["time"]) and np.array_equal(h["eps33"], r["eps33"])]
    creep = np.diff(r["time"])[r["stage"][1:] == 1]
    ev = {e: {"count": runs[0]["events"][e]["count"], "s": float(np.median([x["events"][e]["s"] for x in runs]))}
          for e in study.EVENTS}
    return {"size": size, "candidate": name, "options": study.CANDIDATES[name], "max_steps": cap, "repeats": len(runs),
            "cells": r["cells"], "unknowns": r["unknowns"], "steps": r["steps"], "newton": r["newton"], "krylov": r["krylov"],
            "setups": r["setups"], "wall": r["solve_wall"], "cpu": r["solve_cpu"], "cpu_runs": [x["solve_cpu"] for x in runs],
            "rss": r["rss"], "reference": ref["name"], "diff": err, "identical_to": same, "dt_first": float(creep[0]),
            "dt_last": float(creep[-1]), "events": ev}


def measure(i, size, names, repeats, ranks, cap, tmp):
    """Every candidate of `names` on the mesh of element size `size`, interleaved (each once per round): the rows."""
    scene = Path(tmp) / f"s{size}.yaml"
    scene.write_text(scene_text(size))
    res = {n: [] for n in names}
    for rep in range(repeats):
        for k, n in enumerate(names):
            r = run(scene, Path(tmp) / f"o{i}_{rep}_{k}", ranks, study.CANDIDATES[n], cap, log_view=True)
            if "failed" in r:
                raise SystemExit(f"size {size} {n}: failed\n{r['failed']}")
            res[n].append(r)
    rows, hists, ref = [], {}, None
    for n in names:
        ref = ref or dict(median_run(res[n]), name=n)
        row = stored_row(size, n, res[n], cap, ref, hists)
        hists[n] = res[n][0]
        rows.append(row)
        print(f"size {size}: {row['cells']} cells {row['unknowns']} unknowns, {n}: {row['steps']} steps {row['newton']} Newton "
              f"{row['krylov']} Krylov {row['setups']} set-ups, wall {row['wall']:.2f} s, CPU {row['cpu']:.2f} s "
              f"{study.ms(row):.1f} ms/Newton, RSS {row['rss']:.0f} MB, diff {row['diff']}, same as {row['identical_to']}",
              flush=True)
    return rows


def merged(old, store):
    """The store `old` with the rows (mesh, candidate) of `store` replaced or added, its probe and history kept, and
    the new run's provenance listed among its merges."""
    if not old:
        raise SystemExit(f"--merge: no {results_store.path(study.STORE)} to merge into")
    if old["history"] != store["history"]:
        raise SystemExit(f"--merge: the store's history {old['history']} is not this bench's {store['history']}")
    run = {(r["size"], r["candidate"]) for r in store["rows"]}
    rows = [r for r in old["rows"] if (r["size"], r["candidate"]) not in run] + store["rows"]
    order = list(study.CANDIDATES)
    rows.sort(key=lambda r: (-r["size"], order.index(r["candidate"])))
    entry = dict(store["provenance"], rows=[f"{s:g} mm: {c}" for s, c in sorted(run, key=lambda x: (-x[0], order.index(x[1])))])
    pv = dict(old["provenance"], merged=old["provenance"].get("merged", []) + [entry])
    return dict(old, provenance=pv, rows=rows)


def command(argv):
    """The bench's command line as run, for the provenance (--machine and --no-doc left out)."""
    args, skip = [], False
    for x in argv:
        if skip or x == "--no-doc":
            skip = False
            continue
        if x == "--machine":
            skip = True
            continue
        if not x.startswith("--machine="):
            args.append(x)
    return shlex.join(["bench/fe_solver_bench.py", *args])


def main_job_cli(a):
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


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", default="5.3,2.5,1.45", help="element sizes [mm] (about 1k, 10k, 50k tets)")
    ap.add_argument("--max-steps", default="0,0,16", help="per size: stop after N steps (0: the whole history)")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--large-from", type=int, default=2, help="from this size index on, only the shortlist")
    ap.add_argument("--merge", action="store_true", help="replace only the rows (mesh, candidate) run, keep the store's others")
    ap.add_argument("--from-store", action="store_true", help="write the section from the store, run nothing")
    ap.add_argument("--machine", default="no other job running", help="what else ran on the machine, for the provenance")
    ap.add_argument("--no-doc", action="store_true", help="print only; leave the store and docs/performance.md")
    ap.add_argument("--main-job", action="store_true", help="only the main job, old set-up against new (2 ranks)")
    argv = sys.argv[1:] if argv is None else argv
    a = ap.parse_args(argv)
    if a.main_job:
        return main_job_cli(a)
    if a.from_store:
        return republish(study, write=not a.no_doc) or 0
    sizes = [float(x) for x in a.sizes.split(",")]
    caps = [int(x) for x in a.max_steps.split(",")]
    load, stamp = os.getloadavg()[0], time.strftime("%Y-%m-%d")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        found = None if a.merge else probe(sizes[0], tmp)
        for i, size in enumerate(sizes):
            names = list(study.CANDIDATES) if i < a.large_from else list(study.SHORTLIST)
            rows += measure(i, size, names, a.repeats, a.ranks, caps[i], tmp)
    pv = {"command": command(argv), "date": stamp, "rev": results_store.revision(ROOT), "load": [load, os.getloadavg()[0]],
          "machine": a.machine}
    store = {"provenance": pv, "history": history_figures(), "probe": found, "rows": rows}
    if a.merge:
        store = merged(results_store.load(study.STORE), store)
    if not a.no_doc:   # the store first: a section that cannot be written loses no run
        results_store.save(study.STORE, store)
    try:
        section = study.section(store)
    except ValueError as e:   # e.g. the first of the section's two commands alone
        print(f"{e}\nThe store is kept; the section is written once it holds what the reading needs (the docstring's two "
              "commands).")
        return 1
    publish(study.TITLE, section, study.STORE, store, write=not a.no_doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
