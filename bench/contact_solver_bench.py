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
            "3D indentation"); h_tip 0.018 (1.21 M unknowns) on the field splits alone, 0.019 (1.03 M) on the field split
  lhu0.12, lhu0.0707, lhu0.0425  the sector through its whole load, hold and unload in about 23 steps (the stages'
            error tolerance 0.3: LOOSE), one rank
  fix0.12 ... fix0.019  the sector's uniform ladder from 5.9 k to 1.03 M unknowns, each through its whole load, hold and
            unload on the same fixed steps (contact_solver_study.FIXED_STEPS), the field split on 2 ranks: Krylov
            iterations per Newton iteration from 1e5 to 1e6 unknowns, memory, and the reported outputs, whose
            differences between rungs are the mesh's alone (the steps' error is the same on every rung); bnfix3 ...
            bnfix0.475 BN's sector alike. Newton
            stops at a residual of 1e-6 of the load (FIX_OPTIONS): at the default 1e-10 the finer rungs' hold steps
            stalled and were cut back again and again; fix0.0707 also runs to the default ('fieldsplit, Newton to 1e-10');
            fix0.12 to fix0.019, bnfix1.062 and bnfix0.475 also with GMRES' tolerance by the forcing term
            ('fieldsplit, forcing term'); each row's Krylov iterations also by stage (the solves' counts in its log)
  whole0.0707, whole0.05, whole0.034  the sector (24 k, 63 k and 190 k unknowns) through its whole load, hold and
            unload at the shipped time-step control (about 600 steps), one rank, direct and field split: the size at
            which -indent_solver auto should switch over a whole run, where the kept factorisation serves many steps
  ranks0.0425  the first 4 steps at 101 k unknowns on 2 ranks, with the driver's graph partitioner and with the
            simple one (the cells in the mesh file's order), with -log_view's events

CPU: user + system of the driver and its gmsh (wait4), median of --repeats runs (one run for the cases of ONCE); memory:
the driver's peak resident set (the largest of the repeats; on 2 ranks the largest rank's, and the ranks' sum from the
driver's 'memory:' line). The same steps are run by every path (-max_steps), so the two compare at equal
work; the Newton iterations say whether a path's directions cost the Newton extra iterations.

  bench/contact_solver_bench.py [--repeats 3] [--cases axi1,axi2,sector0.12,...] [--solvers 'direct;fieldsplit;...'] [--merge] [--no-doc]
                                [--keep DIR [--budget SECONDS]]

--keep runs in DIR (kept) with a checkpoint at every step; with --budget each run is stopped after that much wall time
and the same command continues it from its last step: a run of hours (fix0.019) in parts, its CPU and Krylov iterations
summed over the parts (a stopped part's unfinished step counts in its CPU, not in its iterations), its memory the
largest part's (mem_all, the ranks' sum: its last part's). A finished run's last part is kept in DIR's parts.json with
the driver's counts: the same command then reports the run again without running it. A checkpoint at every step rebuilds the kept multigrid hierarchy
at every step (docs/driver.md, "What a restart reproduces"), so a kept run's Krylov iterations differ a little from
one run straight through (fix0.12 in two parts, twice: 2 293 and 2 359 against 2 333, the same outputs to the digits
printed).

--merge replaces only the rows (case, solver) run in the store and keeps the others, each merge's command and date
listed in the store's provenance.

Writes its numbers into the results store (docs/results/contact_solver.json), which docs/contact.md's reading quotes
(camclay9.contact_quotes), and the section "## Contact solve: direct against field split" of docs/performance.md from
that store (camclay9.contact_solver_study; tools/doc_numbers.py checks the section against the store).
"""
import argparse
import json
import re
import signal
import statistics
import tempfile
import time
from pathlib import Path

import yaml
from camclay9 import (driver_command, memory_line, mesh_line, partition_line, read_summary, reported, results_store,
                      run_measured, summary_line)
from camclay9 import contact_solver_study as study
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TIMEOUT = 3600  # s, one run
GAMG = ["-indent_solver", "fieldsplit", "-indent_fieldsplit_pmg", "false"]
BEFORE = GAMG + ["-indent_refactor_its", "0", "-indent_pc_fieldsplit_schur_fact_type", "full"]
# the displacement block solved exactly (a fresh MUMPS LU at every Newton iteration): what is left is the Schur estimate's
EXACT_U = GAMG + ["-indent_refactor_its", "0", "-indent_fieldsplit_u_pc_type", "lu", "-indent_fieldsplit_u_pc_factor_mat_solver_type", "mumps"]
SOLVERS = {"direct": ["-indent_solver", "direct"], "fieldsplit": ["-indent_solver", "fieldsplit"], "fieldsplit, GAMG on P2": GAMG,
           "fieldsplit, before": BEFORE, "fieldsplit, LU on u": EXACT_U,
           # the cells cut in the mesh file's order, as the driver did before it took a graph partitioner
           "fieldsplit, simple partition": ["-indent_solver", "fieldsplit", "-petscpartitioner_type", "simple"],
           # the fixed-step ladder's rung with Newton to the driver's default residual (FIX_OPTIONS' 1e-6 overridden)
           "fieldsplit, Newton to 1e-10": ["-indent_solver", "fieldsplit", "-indent_rtol", "1e-10"],
           # GMRES' tolerance by the inexact Newton forcing term on a settled active set (semismooth.c, forcing)
           study.FORCING: ["-indent_solver", "fieldsplit", "-indent_ksp_ew"]}
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
    # ... and at 1.03 M (the fixed-step ladder's finest mesh): 1e5 to 1e6 unknowns
    "sector0.019": ("nanoindent_kerogen_sector", {"h_tip": 0.019, "h_far": 0.076}, None, 8, ("fieldsplit",)),
    # the sector through its whole load, hold and unload (steps None: the whole run), one rank, with the steps of LOOSE
    # (about 23 where the shipped control takes about 550): how the iterations grow once the whole contact is active
    "lhu0.12": ("nanoindent_kerogen_sector", {"h_tip": 0.12, "h_far": 0.48}, None, None, ("direct", "fieldsplit", "fieldsplit, LU on u")),
    "lhu0.0707": ("nanoindent_kerogen_sector", {"h_tip": 0.07071, "h_far": 0.28284}, None, None,
                  ("direct", "fieldsplit", "fieldsplit, LU on u")),
    "lhu0.0425": ("nanoindent_kerogen_sector", {"h_tip": 0.0425, "h_far": 0.17}, None, None, ("direct", "fieldsplit")),
    # the sector through its whole load, hold and unload at the shipped time-step control (about 600 steps), one rank:
    # where -indent_solver auto should switch over a whole run (the factorisation is kept across the steps)
    "whole0.0707": ("nanoindent_kerogen_sector", {"h_tip": 0.07071, "h_far": 0.28284}, None, None, ("direct", "fieldsplit")),
    "whole0.05": ("nanoindent_kerogen_sector", {"h_tip": 0.05, "h_far": 0.2}, None, None, ("direct", "fieldsplit")),
    "whole0.034": ("nanoindent_kerogen_sector", {"h_tip": 0.034, "h_far": 0.136}, None, None, ("direct", "fieldsplit")),
}
# the sector's uniform ladder to a million unknowns on the steps of study.FIXED_STEPS, the field split on 2 ranks: the
# Krylov iterations from 1e5 to 1e6 unknowns under a whole load, hold and unload, and the mesh's share of the reported
# outputs at equal time steps (the converged 3D answer's cross-check beyond the direct path's memory)
FIX = {"fix0.12": (0.12, 0.48), "fix0.0707": (0.07071, 0.28284), "fix0.0425": (0.0425, 0.17), "fix0.034": (0.034, 0.136),
       "fix0.019": (0.019, 0.076)}
# ... and BN's sector alike: the same geometry at 25 times the size (input/microindent_BN_sector.yaml), so the same
# unknowns at 25 times the element sizes
FIX.update({f"bnfix{25 * t:.4g}": (round(25 * t, 6), round(25 * f, 6)) for t, f in list(FIX.values())})
CASES.update({c: ("microindent_BN_sector" if c.startswith("bn") else "nanoindent_kerogen_sector", {"h_tip": t, "h_far": f},
                  None, None, ("fieldsplit",) + (("fieldsplit, Newton to 1e-10",) if c == "fix0.0707" else ())
                  + ((study.FORCING,) if c in ("fix0.12", "fix0.0707", "fix0.0425", "fix0.034", "fix0.019", "bnfix1.062", "bnfix0.475")
                     else ()))
              for c, (t, f) in FIX.items()})
# ... and every solve's Krylov iterations in the log, so that the rows give them by stage (stage_split)
FIX_OPTIONS = study.FIXED_RTOL + ["-indent_ksp_converged_reason"]
# 2 ranks, the first 4 steps: the graph partitioner against the simple one (docs/parallel.md, "The partition")
CASES["ranks0.0425"] = ("nanoindent_kerogen_sector", {"h_tip": 0.0425, "h_far": 0.17}, None, 4,
                        ("fieldsplit", "fieldsplit, simple partition"))
ONCE = ("sector0.05", "sector0.0425", "sector0.034", "sector0.018", "sector0.019", "lhu0.0707", "lhu0.0425",
        "ranks0.0425", "whole0.0707", "whole0.05", "whole0.034") + tuple(FIX)  # one run each
RANKS = dict({"ranks0.0425": 2}, **{c: 2 for c in FIX})
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
    for stage, steps in zip(d["stages"], study.FIXED_STEPS if case in FIX else []):
        stage["steps"] = dict(steps)
    out = work / f"{case}.yaml"
    out.write_text(yaml.safe_dump(d, sort_keys=False))
    return out


# PETSc's -log_view events kept from the runs of LOG_VIEW's cases: where a Newton iteration's time goes
EVENTS = ("CC9 residual+UMAT", "CC9 Jacobian", "CC9 contact", "CC9 tangent apply", "CC9 contact solve", "PCSetUp",
          "KSPSolve_FS_0", "KSPSolve_FS_Schu", "MatMult", "VecScatterEnd")
LOG_VIEW = ("ranks0.0425",)


def events(text):
    """{event: its time [s], the largest over the ranks} of EVENTS from a -log_view table."""
    out = {}
    for e in EVENTS:
        m = re.search(rf"^{re.escape(e)}\s+\d+ [0-9.]+ ([0-9.]+e[+-]\d+)", text, re.M)
        if m:
            out[e] = float(m[1])
    return out


# a run kept (--keep) writes a checkpoint at every step, and its log says every solve's Krylov iterations and every
# Newton iteration: a run stopped by --budget continues from its last step at the next invocation, and its stall, if
# any, can be read from the log
RESUMABLE = ["-checkpoint_every", "1", "-indent_ksp_converged_reason", "-indent_monitor"]
KSP_ITS = re.compile(r"^Linear indent_ solve (?:converged|did not converge) due to \S+ iterations (\d+)", re.M)


STEP_LINE = re.compile(r"^step +\d+ +(\S+) ", re.M)


def stage_split(text):
    """{stage: {"steps", "solves", "krylov"}} of a log's whole steps: each solve's Krylov iterations
    (-indent_ksp_converged_reason) counted in the stage of the progress line that ends its step, rejected attempts
    (cut back, stalled) included; what follows the last progress line (a step stopped by --budget) is not counted."""
    out, start = {}, 0
    for m in STEP_LINE.finditer(text):
        its = [int(k) for k in KSP_ITS.findall(text, start, m.start())]
        d = out.setdefault(m[1], {"steps": 0, "solves": 0, "krylov": 0})
        d["steps"], d["solves"], d["krylov"] = d["steps"] + 1, d["solves"] + len(its), d["krylov"] + sum(its)
        start = m.end()
    return out


def stopped_part(text, cpu, mem):
    """An invocation stopped by --budget: its CPU and peak memory, and the Krylov iterations of its whole steps (those
    before its last progress line, each checkpointed; the step it was stopped in is solved again after the restart,
    so its iterations are not counted, though its CPU is), also by stage."""
    stages = stage_split(text)
    return {"cpu": cpu, "mem": mem, "krylov": sum(d["krylov"] for d in stages.values()),
            "steps": sum(d["steps"] for d in stages.values()), "stages": stages}


def summed_stages(parts):
    """The parts' stage splits summed (a part without one, from before the split was kept: none at all)."""
    if not all("stages" in x for x in parts):
        return {}
    out = {}
    for x in parts:
        for name, d in x["stages"].items():
            o = out.setdefault(name, {k: 0 for k in d})
            for k, v in d.items():
                o[k] += v
    return {"stages": out} if out else {}


def combined(parts):
    """A run's row from its parts (the last one finished, holding the driver's counts): CPU and Krylov iterations
    summed, memory the largest part's, the stage split summed; the steps and Newton iterations are the driver's, which
    a restart carries on."""
    n = len(parts)
    return dict(parts[-1]["row"], cpu=sum(x["cpu"] for x in parts), mem=max(x["mem"] for x in parts),
                krylov=sum(x["krylov"] for x in parts), **summed_stages(parts), **({"parts": n} if n > 1 else {}))


def run(scene, steps, solver, out, ranks=1, log_view=False, extra=(), budget=None, keep=False):
    """One run (steps None: the whole run): its CPU [s] (user + system, its children's included: every rank's) and peak
    memory [MB] (camclay9.run_measured: the largest process's), and the driver's counts from its summary line. keep: a
    run that can be stopped after `budget` seconds and resumed from its checkpoint by the same command; its parts are
    listed in OUT/parts.json, and it returns None until its last part is done (then combined), and that part's row
    again at a later invocation."""
    out.mkdir(parents=True, exist_ok=True)
    parts = json.loads((out / "parts.json").read_text()) if keep and (out / "parts.json").exists() else []
    if parts and "row" in parts[-1]:   # finished by an earlier invocation: its measures, not a second run
        return combined(parts)
    resume = ["-restart"] if keep and (out / "checkpoint.latest").exists() else []
    opts = ((["-max_steps", steps] if steps else []) + list(extra) + SOLVERS[solver] + (["-log_view"] if log_view else [])
            + (RESUMABLE + resume if keep else []))
    log = out / (f"driver.{len(parts)}.out" if keep else "driver.out")
    if keep and log.exists():   # a part that ended otherwise than by its budget (killed, or failed): not measured
        raise SystemExit(f"{log}: a part of this run that was not stopped by --budget (killed or failed), so its CPU and "
                         f"Krylov iterations are not in {out / 'parts.json'} and a total would be wrong; remove {out} to run "
                         "the case again from its start")
    cmd = driver_command(scene, out, opts, root=ROOT, ranks=ranks)
    rc, cpu, mem, _ = run_measured(cmd, log, timeout=TIMEOUT * (4 if steps is None else 1), budget=budget)
    text = log.read_text()
    if keep and rc == -signal.SIGTERM:
        parts.append(dict(stopped_part(text, cpu, mem), date=time.strftime("%Y-%m-%d %H:%M")))
        (out / "parts.json").write_text(json.dumps(parts, indent=1))
        print(f"stopped after --budget {budget:g} s, {parts[-1]['steps']} steps in this part: the same command continues "
              f"from the last checkpoint in {out}", flush=True)
        return None
    if rc:
        raise SystemExit(f"{' '.join(cmd)} failed ({rc}):\n{text[-2000:]}")
    s, m, part, memory = summary_line(text), mesh_line(text), partition_line(text), memory_line(text)
    if keep and sum(int(k) for k in KSP_ITS.findall(text)) != s["krylov_iterations"]:   # how a stopped part is counted
        raise SystemExit(f"{log}: its solves' Krylov iterations (-indent_ksp_converged_reason) do not add up to its summary's "
                         f"{s['krylov_iterations']}: the count of a stopped part would be wrong")
    split = {"stages": stage_split(text)} if KSP_ITS.search(text) else {}
    parts.append({"cpu": cpu, "mem": mem, "krylov": s["krylov_iterations"], **split, "date": time.strftime("%Y-%m-%d %H:%M"),
                  "row": {"unknowns": m["unknowns"], "steps": s["steps"], "newton": s["newton_iterations"], "ranks": ranks,
                          **({"partition": {k: part[k] for k in ("type", "vertices", "copies")}} if part else {}),
                          **({"mem_all": memory["all_mb"]} if memory and ranks > 1 else {}),
                          **({"events": events(text)} if log_view else {})}})
    if keep:
        (out / "parts.json").write_text(json.dumps(parts, indent=1))
    row = combined(parts)
    if sum(d["krylov"] for d in row.get("stages", {}).values()) not in (0, row["krylov"]):   # every solve in one stage
        raise SystemExit(f"{out}: the Krylov iterations by stage {row['stages']} do not add up to the run's {row['krylov']}")
    return row


def outputs(run_dir):
    """A whole run's reported outputs (camclay9.summary): the load at the end of loading, the creep depth (the hold's
    change of depth) and the residual depth [nm], as the study's table of the fixed-step ladders reads them."""
    s = read_summary(run_dir)
    return {"P": reported(s, "load", "load"), "creep": 1e3 * reported(s, "hold", "depth", "change"),
            "h_res": 1e3 * reported(s, "unload", "depth")}


def measure(case, repeats, work, solvers=None, budget=None, keep=False):
    """Every solver of the case (or those of them in `solvers`), repeats runs each; a kept run stopped by its budget
    gives no row (the same command continues it)."""
    scene = scene_file(case, work)
    rows = []
    for solver in (x for x in CASES[case][4] if solvers is None or x in solvers):
        dirs = [work / f"{case}_{re.sub(r'[^A-Za-z0-9.]+', '_', solver)}_{k}" for k in range(repeats)]
        runs = [run(scene, CASES[case][3], solver, d, RANKS.get(case, 1), case in LOG_VIEW,
                    FIX_OPTIONS if case in FIX else (), budget, keep) for d in dirs]
        if None in runs:
            continue
        if case in FIX:   # the outputs of equal fixed steps, the study's ladder table (the LOOSE runs' steps differ)
            runs[-1]["outputs"] = outputs(dirs[-1])
        r = dict(runs[-1], case=case, solver=solver, repeats=repeats, cpu=statistics.median(x["cpu"] for x in runs),
                 mem=max(x["mem"] for x in runs))
        print(f"{case:13s} {solver:19s} {r['unknowns']:7d} unknowns  {r['newton']:4d} Newton  {r['krylov']:6d} Krylov  "
              f"CPU {r['cpu']:7.2f} s  peak {r['mem']:7.0f} MB"
              + "".join(f"  {k} {v:.5g}" for k, v in r.get("outputs", {}).items()), flush=True)
        rows.append(r)
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--no-doc", action="store_true", help="print only; leave docs/performance.md")
    ap.add_argument("--solvers", default=None, help=f"only these of each case's solvers, separated by ';' ({'; '.join(SOLVERS)})")
    ap.add_argument("--merge", action="store_true", help="replace only the rows (case, solver) run in the store, keep its others")
    ap.add_argument("--note", default="", help="--merge: a remark on the machine kept beside this run's command (e.g. shared)")
    ap.add_argument("--keep", type=Path, default=None, help="run in this directory, kept, with a checkpoint at every step "
                    "(default: a temporary one): a run stopped by --budget continues at the same command")
    ap.add_argument("--budget", type=float, default=None, help="--keep: stop each run after this many seconds of wall "
                    "time, to be continued by the same command (its row is stored by the invocation that finishes it)")
    a = ap.parse_args(argv)
    if a.budget is not None and (a.keep is None or a.budget <= 0):
        raise SystemExit(f"--budget {a.budget:g}: expected a positive number of seconds, with --keep")
    solvers = a.solvers.split(";") if a.solvers else None   # a solver's name may hold a comma
    if solvers and set(solvers) - set(SOLVERS):
        raise SystemExit(f"--solvers: {sorted(set(solvers) - set(SOLVERS))} unknown; expected among {list(SOLVERS)}")
    for case in a.cases.split(","):   # a case the bench does not know, or none of whose solvers was asked, runs nothing
        if case not in CASES:
            raise SystemExit(f"--cases: '{case}' unknown; expected among {', '.join(CASES)}")
        if solvers and not set(solvers) & set(CASES[case][4]):
            raise SystemExit(f"--solvers: case {case} runs none of {solvers}; its solvers: {'; '.join(CASES[case][4])}")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep.resolve() if a.keep else Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        for case in a.cases.split(","):
            rows += measure(case, 1 if case in ONCE else a.repeats, work, solvers, a.budget, a.keep is not None)
    if not rows:
        return
    stamp = time.strftime("%Y-%m-%d")
    rows = [{k: r[k] for k in ("case", "solver", "unknowns", "steps", "newton", "krylov", "cpu", "mem", "repeats", "ranks", "outputs",
                               "partition", "mem_all", "events", "parts", "stages")
             if k in r} for r in rows]
    command = (f"bench/contact_solver_bench.py --repeats {a.repeats} --cases {a.cases}" + (f" --solvers '{a.solvers}'" if a.solvers else "")
               + (f" --keep DIR --budget {a.budget:g}" if a.budget else " --keep DIR" if a.keep else ""))
    store = {"provenance": {"command": command, "date": stamp}, "rows": rows}
    if a.merge:   # the store's other rows kept (read now, as late as possible), this run's command listed beside its own
        old = results_store.load(study.STORE)
        run = {(r["case"], r["solver"]) for r in rows}
        kept = [r for r in old["rows"] if (r["case"], r["solver"]) not in run]
        merged = study.merges(old["provenance"]) + [{"command": command + " --merge", "date": stamp,
                                                     "rows": sorted(f"{c}: {s}" for c, s in run), **({"note": a.note} if a.note else {})}]
        store = {"provenance": dict(old["provenance"], merged=merged), "rows": kept + rows}
    if not a.no_doc:   # the store first: a section that cannot be written loses no run
        results_store.save(study.STORE, store)
    section = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(section)
    if not a.no_doc:
        replace_section(study.TITLE, section)


if __name__ == "__main__":
    main()
