#!/usr/bin/env python3
"""The contact solve's two paths against each other (issue 33): CPU and peak memory of the kept MUMPS factorisation
(`-indent_solver direct`) and of the field split (`-indent_solver fieldsplit`: one GAMG cycle on the displacement block,
its hierarchy kept across Newton iterations and steps, the factored selfp Schur approximation on the contact block, the
lower Schur factorisation, flexible GMRES outside; docs/contact.md, "The field split"), and of the field split as it
was before (GAMG set up at every Newton iteration, the full Schur factorisation: "fieldsplit, before"), on the first
steps of the kerogen nanoindentation:

  axi P1    input/nanoindent_kerogen_axi.yaml as shipped (P1), the first 60 steps
  axi P2    the same block, P2, h_tip 0.02 um: the first 60 steps
  lr1       input/loading_rate_a1.yaml as shipped (plane strain, P2, 76 k unknowns): the first 60 steps
  sector    input/nanoindent_kerogen_sector.yaml (P2), h_tip 0.12, 0.0707, 0.05, 0.0425, 0.034 um (h_far 4 h_tip): the
            first 8 steps of the loading (the first three are the 3D mesh study's rungs, docs/performance.md
            "3D indentation"); h_tip 0.018 (about a million unknowns) on the field split alone

CPU: user + system of the driver and its gmsh (wait4), median of --repeats runs (one run for the three finest sectors); memory:
the driver's peak resident set (the largest of the repeats). The same steps are run by every path (-max_steps), so the two compare at equal
work; the Newton iterations say whether a path's directions cost the Newton extra iterations.

  bench/contact_solver_bench.py [--repeats 3] [--cases axi1,axi2,sector0.12,...] [--no-doc]

Writes its numbers into the results store (docs/results/contact_solver.json), which docs/contact.md's reading quotes
(camclay9.doc_quotes), and the section "## Contact solve: direct against field split" of docs/performance.md from
that store (camclay9.contact_solver_study; tools/doc_numbers.py checks the section against the store).
"""
import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

import yaml
from camclay9 import driver_command, mesh_line, results_store, run_measured, summary_line
from camclay9 import contact_solver_study as study
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 3600  # s, one run
BEFORE = ["-indent_refactor_its", "0", "-indent_pc_fieldsplit_schur_fact_type", "full"]
SOLVERS = {"direct": ["-indent_solver", "direct"], "fieldsplit": ["-indent_solver", "fieldsplit"],
           "fieldsplit, before": ["-indent_solver", "fieldsplit"] + BEFORE}
ALL = ("direct", "fieldsplit", "fieldsplit, before")
# case: (scene in input/, mesh overrides, order, steps, solvers)
CASES = {
    "axi1": ("nanoindent_kerogen_axi", {}, None, 60, ALL),
    "axi2": ("nanoindent_kerogen_axi", {}, 2, 60, ALL),
    "sector0.12": ("nanoindent_kerogen_sector", {"h_tip": 0.12, "h_far": 0.48}, None, 8, ALL),
    "sector0.0707": ("nanoindent_kerogen_sector", {"h_tip": 0.07071, "h_far": 0.28284}, None, 8, ALL),
    "sector0.05": ("nanoindent_kerogen_sector", {"h_tip": 0.05, "h_far": 0.2}, None, 8, ("direct", "fieldsplit")),
    "sector0.0425": ("nanoindent_kerogen_sector", {"h_tip": 0.0425, "h_far": 0.17}, None, 8, ("direct", "fieldsplit")),
    "sector0.034": ("nanoindent_kerogen_sector", {"h_tip": 0.034, "h_far": 0.136}, None, 8, ("direct", "fieldsplit")),
    # 2D at the shipped loading-rate scene's size (P2, 76 k unknowns): where auto keeps the direct path
    "lr1": ("loading_rate_a1", {}, None, 60, ("direct", "fieldsplit")),
    # about a million unknowns: the field split alone (the direct path's factors would not fit in 23 GB)
    "sector0.018": ("nanoindent_kerogen_sector", {"h_tip": 0.018, "h_far": 0.072}, None, 8, ("fieldsplit",)),
}
ONCE = ("sector0.05", "sector0.0425", "sector0.034", "sector0.018")  # one run each: 30 s to several minutes of CPU


def scene_file(case, work):
    """The case's scene: the shipped file with an absolute geometry and the case's mesh and order."""
    name, mesh, order, _, _ = CASES[case]
    src = ROOT / "input" / f"{name}.yaml"
    d = yaml.safe_load(src.read_text())
    d["mesh"]["geometry"] = str((src.parent / d["mesh"]["geometry"]).resolve())
    d["mesh"]["parameters"].update(mesh)
    if order:
        d["mesh"]["order"] = order
    out = work / f"{case}.yaml"
    out.write_text(yaml.safe_dump(d, sort_keys=False))
    return out


def run(scene, steps, solver, out):
    """One run: its CPU [s] (user + system, its children's included) and peak memory [MB] (camclay9.run_measured),
    and the driver's counts from its summary line."""
    out.mkdir(parents=True, exist_ok=True)
    log, cmd = out / "driver.out", driver_command(scene, out, ["-max_steps", steps, *SOLVERS[solver]], root=ROOT)
    rc, cpu, mem, _ = run_measured(cmd, log, timeout=TIMEOUT)
    if rc:
        raise SystemExit(f"{' '.join(cmd)} failed ({rc}):\n{log.read_text()[-2000:]}")
    text = log.read_text()
    s, m = summary_line(text), mesh_line(text)
    return {"unknowns": m["unknowns"], "steps": s["steps"], "newton": s["newton_iterations"],
            "krylov": s["krylov_iterations"], "cpu": cpu, "mem": mem}


def measure(case, repeats, work):
    """Every solver of the case, repeats runs each."""
    scene = scene_file(case, work)
    rows = []
    for solver in CASES[case][4]:
        runs = [run(scene, CASES[case][3], solver, work / f"{case}_{k}") for k in range(repeats)]
        r = dict(runs[-1], case=case, solver=solver, repeats=repeats, cpu=statistics.median(x["cpu"] for x in runs),
                 mem=max(x["mem"] for x in runs))
        print(f"{case:13s} {solver:19s} {r['unknowns']:7d} unknowns  {r['newton']:4d} Newton  {r['krylov']:6d} Krylov  "
              f"CPU {r['cpu']:7.2f} s  peak {r['mem']:7.0f} MB", flush=True)
        rows.append(r)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--no-doc", action="store_true", help="print only; leave docs/performance.md")
    ap.add_argument("--merge", action="store_true", help="replace only the cases run in the store, keep its other rows")
    a = ap.parse_args(argv)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in a.cases.split(","):
            rows += measure(case, 1 if case in ONCE else a.repeats, Path(tmp))
    stamp = time.strftime("%Y-%m-%d")
    rows = [{k: r[k] for k in ("case", "solver", "unknowns", "steps", "newton", "krylov", "cpu", "mem", "repeats")} for r in rows]
    store = {"provenance": {"command": f"bench/contact_solver_bench.py --repeats {a.repeats}", "date": stamp}, "rows": rows}
    if a.merge:   # the store's other cases kept, with their provenance beside this run's
        old = results_store.load(study.STORE)
        run = set(a.cases.split(","))
        kept = [r for r in old["rows"] if r["case"] not in run]
        store = {"provenance": dict(old["provenance"], merged={"command": f"bench/contact_solver_bench.py --cases {a.cases} --merge",
                                                               "date": stamp, "cases": sorted(run)}),
                 "rows": kept + rows}
    section = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(section)
    if not a.no_doc:
        replace_section(study.TITLE, section)
        results_store.save(study.STORE, store)


if __name__ == "__main__":
    main()
