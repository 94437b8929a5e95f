#!/usr/bin/env python3
"""Indentation speed against the physics: every shipped indentation scene (SCENES) with this tree's driver, on one
rank, as shipped; a scene whose first run takes at most --long s of CPU runs --repeats times, a longer one once.

Per scene: CPU seconds of the run (user + system of the driver and of the gmsh it starts: the children's rusage),
steps, rejected steps, Newton and Krylov iterations, factorisations, UMAT calls, the mesh line (cells, order,
unknowns), and the ratio to the physics, CPU / (UMAT calls x t_call), t_call the UMAT benchmark's median time per
viscoplastic call (both frames yield, NTENS 6: build/bench/umat_bench, run just before the scene, so at that time's
load); the scene's outputs from its summary.json (load at the end of loading, creep depth over the hold, depth at the
end of the last stage); every run writes its -log_view, and the first run's gives the split of the time (the
contact solve, its factorisation, triangular solves and matrix-free products, the assembly of K, the residual with
the UMAT, the contact terms).

Writes every number at full digits into the results store docs/results/indent_speed.json and the section
"Indentation speed: the contact solve and the physics" of docs/performance.md from it (camclay9.indent_speed_study;
tools/doc_numbers.py checks the section and README's quotes of it against the store). --from-store writes the section
from the store without running. --against REV adds the driver of an earlier revision, built beside this tree in a git
worktree of its own, and --elementary this tree's driver with the elementary step controller (-step_alpha 1
-step_beta 0); the drivers' runs are interleaved, so that the machine's load hits them alike.

Usage: bench/indent_speed_bench.py [--repeats 3] [--long 30] [--scenes a,b,...] [--machine TEXT] [--against REV]
                                   [--elementary] [--no-doc] [--quick]
       bench/indent_speed_bench.py --from-store [--no-doc]
"""
import argparse
import os
import re
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

from camclay9 import (DriverError, memory_line, mesh_line, read_summary, reported, results_store, run_driver,
                      summary_line)
from camclay9 import indent_speed_study as study
from camclay9.performance_doc import publish, republish

ROOT = Path(__file__).resolve().parents[1]
SCENES = ["nanoindent_kerogen_sector", "microindent_BN_sector", "microindent_BP", "nanoindent_kerogen_axi",
          "microindent_BN_axi", "loading_rate_a0.1", "loading_rate_a1", "loading_rate_a10", "bedding_theta0",
          "bedding_theta45", "bedding_theta90"]
UMAT_CASE = "viscoplastic, both frames yield, NTENS 6"
COUNTS = ("steps", "rejected", "stalled", "not_converged", "newton", "krylov", "factorisations", "umat_calls")


def build_revision(rev, where):
    """The driver of revision rev, built in a worktree of its own under where."""
    src = where / "src"
    subprocess.run(["git", "worktree", "add", "--detach", str(src), rev], cwd=ROOT, check=True, capture_output=True,
                   timeout=600)
    subprocess.run(["cmake", "-S", str(src), "-B", str(src / "build"), "-DCMAKE_BUILD_TYPE=Release"], check=True,
                   capture_output=True, timeout=1800)
    subprocess.run(["cmake", "--build", str(src / "build"), "-j", "2", "--target", "driver"], check=True,
                   capture_output=True, timeout=3600)
    return src / "build" / "bin" / "driver"


def umat_ns_per_call():
    """The UMAT benchmark's median ns per viscoplastic call (both frames yield, NTENS 6), this tree's build."""
    subprocess.run(["cmake", "--build", str(ROOT / "build"), "--target", "umat_bench"], check=True, capture_output=True,
                   timeout=1800)
    out = subprocess.run([str(ROOT / "build" / "bench" / "umat_bench"), "200000", "5"], check=True, capture_output=True,
                         text=True, timeout=600).stdout
    m = re.search(r"\| viscoplastic, both frames yield \| 6 \|\s*([0-9.]+)", out)
    if not m:
        raise SystemExit(f"build/bench/umat_bench: no line '| viscoplastic, both frames yield | 6 |' in its output:\n{out}")
    return float(m.group(1))


def outputs(run_dir):
    """Load at the end of loading [µN], the hold's change of depth and the depth at the last stage's end [µm]."""
    s = read_summary(run_dir)
    last = s["stages"][-1]["name"]
    return {"load": reported(s, "load", "load"), "creep_depth": reported(s, "hold", "depth", "change"),
            "final_depth": reported(s, last, "depth"), "final_stage": last}


def log_split(text):
    """Seconds per group of -log_view events (the 4th column: the largest time over ranks), and the total."""
    split = {}
    for name, events in study.EVENTS.items():
        total = 0.0
        for ev in events:
            m = re.search(rf"^{re.escape(ev)}\s+\d+\s+[0-9.]+\s+([0-9.eE+-]+)", text, re.M)
            total += float(m.group(1)) if m else 0.0
        split[name] = total
    m = re.search(r"^Time \(sec\):\s+([0-9.eE+-]+)", text, re.M)
    split["total"] = float(m.group(1)) if m else 0.0
    return split


def run(driver, scene, out, args=()):
    """One run: CPU and wall seconds, the summary line's counts, the mesh line, the outputs, the -log_view split."""
    log = out.parent / f"{out.name}_log.txt"
    try:
        proc = run_driver(ROOT / "input" / f"{scene}.yaml", out, (*args, "-log_view", f":{log}"), driver=driver,
                          cwd=out.parent, timeout=6 * 3600)
    except DriverError as err:
        raise SystemExit(f"{scene} ({driver}): failed: {err}")
    s, m, mem = summary_line(proc.stdout, index=0), mesh_line(proc.stdout), memory_line(proc.stdout)
    num = lambda key: s.get(key, 0)  # noqa: E731
    return dict(cpu=proc.cpu, wall=proc.wall, steps=num("steps"), rejected=num("cutbacks"), stalled=num("cutbacks_stalled"),
                not_converged=num("cutbacks_not_converged"), newton=num("newton_iterations"),
                krylov=num("krylov_iterations"), factorisations=num("factorisations") or num("newton_iterations"),
                umat_calls=num("umat_calls"), order=m["order"], cells=m["cells"], unknowns=m["unknowns"],
                rss_mb=mem["rank_mb"] if mem else None, outputs=outputs(out), log_view=log_split(log.read_text()))


def kinematics(scene):
    m = re.search(r"^\s+kinematics:\s*(\w+)", (ROOT / "input" / f"{scene}.yaml").read_text(), re.M)
    return m.group(1) if m else "3d"


def row(scene, label, options, runs, umat_ns):
    """The store's row of one scene and driver (camclay9.indent_speed_study)."""
    first, cpu = runs[0], statistics.median(r["cpu"] for r in runs)
    same = all(r[k] == first[k] for r in runs for k in (*COUNTS, "outputs"))
    return {"scene": scene, "driver": label, "options": " ".join(options), "kinematics": kinematics(scene),
            "order": first["order"], "cells": first["cells"], "unknowns": first["unknowns"], "cpu": cpu,
            "cpu_runs": [r["cpu"] for r in runs], "wall_runs": [r["wall"] for r in runs],
            **{k: first[k] for k in COUNTS}, "same_runs": same, "umat_ns": umat_ns,
            "ratio": cpu / (first["umat_calls"] * umat_ns * 1e-9), "rss_mb": first["rss_mb"], "outputs": first["outputs"],
            "log_view": first["log_view"]}


def measure(scenes, drivers, repeats, long, tmp):
    """The store's rows: per scene the UMAT benchmark, then the drivers' runs interleaved, repeat by repeat."""
    rows = []
    for scene in scenes:
        umat_ns = umat_ns_per_call()
        print(f"{scene}: UMAT benchmark {umat_ns:.1f} ns per call ({UMAT_CASE})", flush=True)
        runs = {label: [] for label in drivers}
        for k in range(repeats):
            for j, (label, (drv, args)) in enumerate(drivers.items()):
                if runs[label] and runs[label][0]["cpu"] > long:     # a long run once
                    continue
                r = run(drv, scene, tmp / f"{scene}_{j}_{k}", args)
                runs[label].append(r)
                print(f"{scene:28s} {label:34s} CPU {r['cpu']:7.1f} s  wall {r['wall']:7.1f} s  steps {r['steps']}  "
                      f"Newton {r['newton']}  calls {r['umat_calls']}", flush=True)
        rows += [row(scene, label, drivers[label][1], rs, umat_ns) for label, rs in runs.items()]
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--long", type=float, default=30, help="a scene whose first run takes more CPU [s] runs once")
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--machine", default="2 cores, shared with other jobs",
                    help="what the machine was and what else ran on it (default: %(default)s)")
    ap.add_argument("--against", default="", help="also the driver of this revision, built beside this tree")
    ap.add_argument("--elementary", action="store_true", help="also this tree with the elementary step controller")
    ap.add_argument("--quick", action="store_true", help="nanoindent_kerogen_axi only, one run, no document")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    ap.add_argument("--from-store", action="store_true", help="write the section from the store, without running")
    a = ap.parse_args(argv)
    if a.from_store:
        return republish(study, write=not a.no_doc) or 0
    scenes = ["nanoindent_kerogen_axi"] if a.quick else a.scenes.split(",")
    repeats = 1 if a.quick else a.repeats
    load = os.getloadavg()
    (ROOT / "build").mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory(dir=ROOT / "build") as tmp:
        tmp = Path(tmp)
        this = ROOT / "build" / "bin" / "driver"
        drivers = {study.THIS: (this, ())}
        if a.elementary:
            drivers["this tree, elementary controller"] = (this, ("-step_alpha", "1", "-step_beta", "0"))
        if a.against:
            drivers[f"before ({a.against})"] = (build_revision(a.against, tmp / "before"), ())
        try:
            rows = measure(scenes, drivers, repeats, a.long, tmp)
        finally:
            if a.against:
                subprocess.run(["git", "worktree", "remove", "--force", str(tmp / "before" / "src")], cwd=ROOT,
                               capture_output=True, timeout=600)
    flags = ["--quick"] if a.quick else [f"--repeats {a.repeats}", f"--long {a.long:g}",
                                         *([f"--scenes {a.scenes}"] if a.scenes != ",".join(SCENES) else [])]
    flags += [*([f"--against {a.against}"] if a.against else []), *(["--elementary"] if a.elementary else [])]
    store = {"provenance": {"command": " ".join(["bench/indent_speed_bench.py", *flags]), "date": time.strftime("%Y-%m-%d"),
                            "rev": results_store.revision(ROOT), "machine": a.machine,
                            "load": {"start": list(load), "end": list(os.getloadavg())}, "repeats": repeats, "long": a.long,
                            "umat_case": UMAT_CASE}, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not (a.no_doc or a.quick))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
