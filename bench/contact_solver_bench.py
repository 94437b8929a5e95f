#!/usr/bin/env python3
"""The contact solve's two paths against each other (issue 33): CPU and peak memory of the kept MUMPS factorisation
(`-indent_solver direct`) and of the field split (`-indent_solver fieldsplit`: one multigrid cycle on the displacement
block, on P2 the p-multigrid to the P1 space of the same mesh with GAMG there, its hierarchy kept across Newton
iterations and steps, the factored selfp Schur approximation on the contact block, the lower Schur factorisation,
flexible GMRES outside; docs/contact.md, "The field split"); of the field split with GAMG on the P2 block itself
("fieldsplit, GAMG on P2": -indent_fieldsplit_pmg false); and of that as it was before its hierarchy was kept (GAMG
set up at every Newton iteration, the full Schur factorisation: "fieldsplit, before"); and, to show the Schur estimate's
own share of the Krylov iterations, of the field split with the displacement block solved exactly ("fieldsplit, LU on
u": a fresh MUMPS LU of K at every Newton iteration), on the first steps of the kerogen nanoindentation:

  axi P1    input/nanoindent_kerogen_axi.yaml as shipped (P1), the first 60 steps
  axi P2    the same block, P2, h_tip 0.02 um: the first 60 steps
  lr1       input/loading_rate_a1.yaml as shipped (plane strain, P2, 76 k unknowns): the first 60 steps
  sector    input/nanoindent_kerogen_sector.yaml (P2), h_tip 0.12, 0.0707, 0.05, 0.0425, 0.034 um (h_far 4 h_tip): the
            first 8 steps of the loading (the first three are the 3D mesh study's rungs, docs/performance.md
            "3D indentation"); h_tip 0.018 (about a million unknowns) on the field splits alone
  lhu0.018  that million-unknown sector through its whole load, hold and unload on 2 ranks, in about 23 steps (the
            stages' error tolerance 0.3: LOOSE), the field split alone; lhu0.12, lhu0.0707, lhu0.0425 the coarser
            sectors alike on one rank

CPU: user + system of the driver and its gmsh (wait4), median of --repeats runs (one run for the cases of ONCE); memory:
the driver's peak resident set (the largest of the repeats). The same steps are run by every path (-max_steps), so the two compare at equal
work; the Newton iterations say whether a path's directions cost the Newton extra iterations.

  bench/contact_solver_bench.py [--repeats 3] [--cases axi1,axi2,sector0.12,...] [--solvers 'direct;fieldsplit;...'] [--merge] [--no-doc]

--merge replaces only the rows (case, solver) run in the store and keeps the others, each merge's command and date
listed in the store's provenance.

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
GAMG = ["-indent_solver", "fieldsplit", "-indent_fieldsplit_pmg", "false"]
BEFORE = GAMG + ["-indent_refactor_its", "0", "-indent_pc_fieldsplit_schur_fact_type", "full"]
# the displacement block solved exactly (a fresh MUMPS LU at every Newton iteration): what is left is the Schur estimate's
EXACT_U = GAMG + ["-indent_refactor_its", "0", "-indent_fieldsplit_u_pc_type", "lu", "-indent_fieldsplit_u_pc_factor_mat_solver_type", "mumps"]
SOLVERS = {"direct": ["-indent_solver", "direct"], "fieldsplit": ["-indent_solver", "fieldsplit"], "fieldsplit, GAMG on P2": GAMG,
           "fieldsplit, before": BEFORE, "fieldsplit, LU on u": EXACT_U}
ALL = ("direct", "fieldsplit", "fieldsplit, GAMG on P2", "fieldsplit, before")
SPLITS = ("direct", "fieldsplit", "fieldsplit, GAMG on P2")
# case: (scene in input/, mesh overrides, order, steps, solvers)
CASES = {
    "axi1": ("nanoindent_kerogen_axi", {}, None, 60, ("direct", "fieldsplit", "fieldsplit, before")),   # P1: no p-multigrid
    "axi2": ("nanoindent_kerogen_axi", {}, 2, 60, ALL),
    "sector0.12": ("nanoindent_kerogen_sector", {"h_tip": 0.12, "h_far": 0.48}, None, 8, ALL),
    "sector0.0707": ("nanoindent_kerogen_sector", {"h_tip": 0.07071, "h_far": 0.28284}, None, 8, ALL + ("fieldsplit, LU on u",)),
    "sector0.05": ("nanoindent_kerogen_sector", {"h_tip": 0.05, "h_far": 0.2}, None, 8, SPLITS),
    "sector0.0425": ("nanoindent_kerogen_sector", {"h_tip": 0.0425, "h_far": 0.17}, None, 8, SPLITS + ("fieldsplit, LU on u",)),
    "sector0.034": ("nanoindent_kerogen_sector", {"h_tip": 0.034, "h_far": 0.136}, None, 8, SPLITS),
    # 2D at the shipped loading-rate scene's size (P2, 76 k unknowns): where auto keeps the direct path
    "lr1": ("loading_rate_a1", {}, None, 60, SPLITS),
    # about a million unknowns: the field split alone (the direct path's factors would not fit in 23 GB)
    "sector0.018": ("nanoindent_kerogen_sector", {"h_tip": 0.018, "h_far": 0.072}, None, 8, SPLITS[1:]),
    # the same mesh through its whole load, hold and unload (steps None: the whole run), on 2 ranks, with the steps of
    # LOOSE (about 23 where the shipped control takes about 550)
    "lhu0.018": ("nanoindent_kerogen_sector", {"h_tip": 0.018, "h_far": 0.072}, None, None, ("fieldsplit",)),
    # ... and coarser sectors alike, one rank: how the iterations grow once the whole contact is active
    "lhu0.12": ("nanoindent_kerogen_sector", {"h_tip": 0.12, "h_far": 0.48}, None, None, ("direct", "fieldsplit", "fieldsplit, LU on u")),
    "lhu0.0707": ("nanoindent_kerogen_sector", {"h_tip": 0.07071, "h_far": 0.28284}, None, None,
                  ("direct", "fieldsplit", "fieldsplit, LU on u")),
    "lhu0.0425": ("nanoindent_kerogen_sector", {"h_tip": 0.0425, "h_far": 0.17}, None, None, ("direct", "fieldsplit")),
}
ONCE = ("sector0.05", "sector0.0425", "sector0.034", "sector0.018", "lhu0.0707", "lhu0.0425", "lhu0.018")  # one run each
RANKS = {"lhu0.018": 2}
# a whole run in few steps: the stages' error tolerance 0.3 (shipped 1.5e-2 and 0.1), the load's first step 5 s
LOOSE = {c: [{"first": 5, "max": 100}, {"first": 5, "max": 30}, {"first": 5, "max": 10}] for c in CASES if c.startswith("lhu")}


def scene_file(case, work):
    """The case's scene: the shipped file with an absolute geometry and the case's mesh and order."""
    name, mesh, order, _, _ = CASES[case]
    src = ROOT / "input" / f"{name}.yaml"
    d = yaml.safe_load(src.read_text())
    d["mesh"]["geometry"] = str((src.parent / d["mesh"]["geometry"]).resolve())
    d["mesh"]["parameters"].update(mesh)
    if order:
        d["mesh"]["order"] = order
    for stage, steps in zip(d["stages"], LOOSE.get(case, [])):
        stage["steps"].update(steps, error={"measure": "output", "tol": 0.3})
    out = work / f"{case}.yaml"
    out.write_text(yaml.safe_dump(d, sort_keys=False))
    return out


def run(scene, steps, solver, out, ranks=1):
    """One run (steps None: the whole run): its CPU [s] (user + system, its children's included: every rank's) and peak
    memory [MB] (camclay9.run_measured: the largest process's), and the driver's counts from its summary line."""
    out.mkdir(parents=True, exist_ok=True)
    opts = (["-max_steps", steps] if steps else []) + SOLVERS[solver]
    log, cmd = out / "driver.out", driver_command(scene, out, opts, root=ROOT, ranks=ranks)
    rc, cpu, mem, _ = run_measured(cmd, log, timeout=TIMEOUT * (4 if steps is None else 1))
    if rc:
        raise SystemExit(f"{' '.join(cmd)} failed ({rc}):\n{log.read_text()[-2000:]}")
    text = log.read_text()
    s, m = summary_line(text), mesh_line(text)
    return {"unknowns": m["unknowns"], "steps": s["steps"], "newton": s["newton_iterations"],
            "krylov": s["krylov_iterations"], "cpu": cpu, "mem": mem, "ranks": ranks}


def measure(case, repeats, work, solvers=None):
    """Every solver of the case (or those of them in `solvers`), repeats runs each."""
    scene = scene_file(case, work)
    rows = []
    for solver in (x for x in CASES[case][4] if solvers is None or x in solvers):
        runs = [run(scene, CASES[case][3], solver, work / f"{case}_{k}", RANKS.get(case, 1)) for k in range(repeats)]
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
    ap.add_argument("--solvers", default=None, help=f"only these of each case's solvers, separated by ';' ({'; '.join(SOLVERS)})")
    ap.add_argument("--merge", action="store_true", help="replace only the rows (case, solver) run in the store, keep its others")
    a = ap.parse_args(argv)
    solvers = a.solvers.split(";") if a.solvers else None   # a solver's name may hold a comma
    if solvers and set(solvers) - set(SOLVERS):
        raise SystemExit(f"--solvers: {sorted(set(solvers) - set(SOLVERS))} unknown; expected among {list(SOLVERS)}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case in a.cases.split(","):
            rows += measure(case, 1 if case in ONCE else a.repeats, Path(tmp), solvers)
    stamp = time.strftime("%Y-%m-%d")
    rows = [{k: r[k] for k in ("case", "solver", "unknowns", "steps", "newton", "krylov", "cpu", "mem", "repeats", "ranks")} for r in rows]
    command = f"bench/contact_solver_bench.py --repeats {a.repeats} --cases {a.cases}" + (f" --solvers '{a.solvers}'" if a.solvers else "")
    store = {"provenance": {"command": command, "date": stamp}, "rows": rows}
    if a.merge:   # the store's other rows kept (read now, as late as possible), this run's command listed beside its own
        old = results_store.load(study.STORE)
        run = {(r["case"], r["solver"]) for r in rows}
        kept = [r for r in old["rows"] if (r["case"], r["solver"]) not in run]
        merged = study.merges(old["provenance"]) + [{"command": command + " --merge", "date": stamp,
                                                     "rows": sorted(f"{c}: {s}" for c, s in run)}]
        store = {"provenance": dict(old["provenance"], merged=merged), "rows": kept + rows}
    section = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(section)
    if not a.no_doc:
        replace_section(study.TITLE, section)
        results_store.save(study.STORE, store)


if __name__ == "__main__":
    main()
