#!/usr/bin/env python3
"""Indentation speed against the physics (issue 25): every shipped indentation scene with this tree's driver and,
with --against REV, with the driver of an earlier revision built beside it, interleaved, medians of --repeats runs.

Per scene and driver: CPU seconds of the run (the child's user + system time, one rank), steps, rejected steps,
Newton and Krylov iterations, factorisations, UMAT calls, and the ratio to the physics,
CPU / (UMAT calls x t_call), t_call the UMAT benchmark's median time per viscoplastic call (both frames yield,
NTENS 6: build/bench/umat_bench, measured in the same run); and the scene's outputs (load at the end of loading,
creep depth over the hold, residual depth) against the earlier revision's. Every run writes its
-log_view; the first run's gives the split of the time (factorisation, triangular solves, assembly, matrix-free products,
residual with the UMAT, contact). Writes the section "Indentation speed: the contact solve and the physics" of
docs/performance.md.

Usage: bench/indent_speed_bench.py [--against 1baa50c] [--repeats 3] [--scenes a,b,...] [--quick]
"""
import argparse
import re
import statistics
import subprocess
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import DriverError, read_history, run_driver, summary_line
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TITLE = "## Indentation speed: the contact solve and the physics"
SCENES = ["nanoindent_kerogen_sector", "microindent_BN_sector", "microindent_BP", "nanoindent_kerogen_axi",
          "microindent_BN_axi", "loading_rate_a0.1", "loading_rate_a1", "loading_rate_a10", "bedding_theta0",
          "bedding_theta45", "bedding_theta90"]
EVENTS = {"factorisation": ["MatLUFactorNum", "MatLUFactorSym"], "triangular solves": ["MatSolve"],
          "assembly of K": ["CC9 Jacobian"], "matrix-free K products": ["CC9 tangent apply"],
          "residual + UMAT": ["CC9 residual+UMAT"], "contact terms": ["CC9 contact"]}


def build_revision(rev, where):
    """The driver of revision rev, built in a worktree of its own under where."""
    src = where / "src"
    subprocess.run(["git", "worktree", "add", "--detach", str(src), rev], cwd=ROOT, check=True, capture_output=True)
    subprocess.run(["cmake", "-S", str(src), "-B", str(src / "build"), "-DCMAKE_BUILD_TYPE=Release"], check=True,
                   capture_output=True)
    subprocess.run(["cmake", "--build", str(src / "build"), "-j", "2", "--target", "driver"], check=True, capture_output=True)
    return src / "build" / "bin" / "driver"


def umat_time_per_call():
    """Median ns per viscoplastic call (both frames yield, NTENS 6) from the UMAT benchmark."""
    subprocess.run(["cmake", "--build", str(ROOT / "build"), "-j", "2", "--target", "umat_bench"], check=True, capture_output=True)
    out = subprocess.run([str(ROOT / "build" / "bench" / "umat_bench"), "200000", "5"], check=True, capture_output=True,
                         text=True).stdout
    m = re.search(r"\| viscoplastic, both frames yield \| 6 \|\s*([0-9.]+)", out)
    return float(m.group(1)) * 1e-9


def run(driver, scene, out, args=()):
    """One run: CPU seconds (children's rusage), the summary line's counts, the history."""
    try:
        proc = run_driver(ROOT / "input" / f"{scene}.yaml", out, args, driver=driver, cwd=out.parent, timeout=6 * 3600)
    except DriverError as err:
        raise SystemExit(f"{scene} ({driver}): failed: {err}")
    s = summary_line(proc.stdout, index=0)
    num = lambda key: s.get(key, 0)  # noqa: E731
    return dict(cpu=proc.cpu, steps=num("steps"), newton=num("newton_iterations"), rejected=num("cutbacks"),
                krylov=num("krylov_iterations"), factorisations=num("factorisations") or num("newton_iterations"),
                calls=num("umat_calls"), outputs=outputs(read_history(out)), log=proc.stdout)


def outputs(h):
    """Load at the end of loading, creep depth over the hold, residual depth."""
    stage = h["stage_name"]
    load = h[stage == stage[1]]
    hold = h[stage == "hold"] if np.any(stage == "hold") else load
    return np.array([load["load"][-1], hold["depth"][-1] - load["depth"][-1], h["depth"][-1]])


def log_split(text):
    """Seconds per group of -log_view events (the 4th column: max time over ranks)."""
    split = {}
    for name, events in EVENTS.items():
        total = 0.0
        for ev in events:
            m = re.search(rf"^{re.escape(ev)}\s+\d+\s+[0-9.]+\s+([0-9.eE+-]+)", text, re.M)
            total += float(m.group(1)) if m else 0.0
        split[name] = total
    m = re.search(r"^Time \(sec\):\s+([0-9.eE+-]+)", text, re.M)
    split["total"] = float(m.group(1)) if m else 0.0
    return split


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--against", default="1baa50c", help="the revision before (built beside this tree); '' for none")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--quick", action="store_true", help="nanoindent_kerogen_axi only, one repeat, no document")
    ap.add_argument("--long", type=float, default=300, help="a run longer than this (CPU s) is not repeated")
    a = ap.parse_args()
    scenes = ["nanoindent_kerogen_axi"] if a.quick else a.scenes.split(",")
    repeats = 1 if a.quick else a.repeats
    t_call = umat_time_per_call()
    print(f"UMAT benchmark: {t_call * 1e9:.0f} ns per viscoplastic call (both frames yield, NTENS 6)")
    with tempfile.TemporaryDirectory(dir=ROOT / "build") as tmp:
        tmp = Path(tmp)
        this = ROOT / "build" / "bin" / "driver"
        drivers = {"this tree": (this, ()), "this tree, elementary controller": (this, ("-step_alpha", "1", "-step_beta", "0"))}
        if a.against:
            drivers[f"before ({a.against})"] = (build_revision(a.against, tmp / "before"), ())
        rows = {}
        for scene in scenes:
            for k in range(repeats):
                for label, (drv, args) in drivers.items():   # interleaved, so that the machine's load hits all alike
                    done = rows.get((scene, label), [])
                    if done and done[0]["cpu"] > a.long:      # a long run once (said in the table)
                        continue
                    lv = tmp / f"{scene}_{abs(hash(label))}_{k}_log.txt"   # -log_view in every run: no extra runs for the split
                    r = run(drv, scene, tmp / f"{scene}_{abs(hash(label))}_{k}", (*args, "-log_view", f":{lv}"))
                    rows.setdefault((scene, label), []).append(r)
                    rows.setdefault((scene, label, "log"), log_split(lv.read_text()))
                    print(f"{scene:28s} {label:34s} CPU {r['cpu']:7.1f} s  steps {r['steps']}  Newton {r['newton']}  "
                          f"calls {r['calls']}", flush=True)
        if a.against:
            subprocess.run(["git", "worktree", "remove", "--force", str(tmp / "before" / "src")], cwd=ROOT, capture_output=True)
    section = document(scenes, list(drivers), rows, t_call, repeats, a.long)
    print(section)
    if not a.quick:
        replace_section(TITLE, section)


def document(scenes, labels, rows, t_call, repeats, long):
    out = [TITLE, "",
           f"Command: `bench/indent_speed_bench.py --repeats {repeats}`. Each shipped indentation scene on one rank with this "
           "tree's driver and with the revision before issue 25 built beside it, runs interleaved; CPU seconds are the "
           f"median of {repeats} runs (user + system of the driver), on a 2-core machine shared with other jobs. The ratio to "
           f"the physics is CPU / (UMAT calls x {t_call * 1e9:.0f} ns), the UMAT benchmark's median time per viscoplastic "
           "call measured in the same run. Outputs: the load at the end of loading, the creep depth over the hold and the "
           "residual depth, relative to the revision before.", "",
           f"A run longer than {long:.0f} s of CPU is not repeated (its CPU is that run's). 'this tree, elementary controller' is "
           "this tree with -step_alpha 1 -step_beta 0: the step controller before issue 25 with the new contact solve.", "",
           "| scene | driver | CPU [s] | ratio | steps | rejected | Newton | Krylov | factorisations | UMAT calls | "
           "load | creep depth | residual depth |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    base = labels[-1]   # the revision before (or the elementary controller without --against)
    for scene in scenes:
        ref = rows[(scene, base)][0]["outputs"]
        for label in labels:
            rs = rows[(scene, label)]
            cpu = statistics.median(r["cpu"] for r in rs)
            r = rs[0]
            rel = r["outputs"] / ref - 1
            out.append(f"| {scene} | {label} | {cpu:.1f} | {cpu / (r['calls'] * t_call):.2f} | {r['steps']} | {r['rejected']} | "
                       f"{r['newton']} | {r['krylov']} | {r['factorisations']} | {r['calls'] / 1e6:.2f} M | {rel[0]:+.1e} | "
                       f"{rel[1]:+.1e} | {rel[2]:+.1e} |")
    out += ["", "Where the time goes (-log_view, the first run of each; seconds of wall time of the events, which include the "
            "children events: the factorisation and the triangular solves are inside the contact solve):", "",
            "| scene | driver | total | " + " | ".join(EVENTS) + " |", "|---|---|---|" + "---|" * len(EVENTS)]
    for scene in scenes:
        for label in labels:
            s = rows[(scene, label, "log")]
            out.append(f"| {scene} | {label} | {s['total']:.1f} | " + " | ".join(f"{s[k]:.1f}" for k in EVENTS) + " |")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
