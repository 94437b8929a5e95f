#!/usr/bin/env python3
"""Time steps across contact kinks (docs/driver.md, "Stages, steps and error control"): the kerogen sector on the
meshes of its own adaptation, each run by this tree's driver and by an earlier one (--before), from the same mesh
file. Keeps every number in docs/results/kink_steps.json (camclay9.kink_steps_study) and writes the section "Time
steps across contact kinks" of docs/performance.md from it.

    bench/kink_steps_bench.py --before OLD/build/bin/driver --before-rev REV [--levels 0,2] [--jobs 2] [--out DIR]
                              [--machine NOTE] [--no-doc]

The meshes: nanoindent_kerogen_sector.yaml run with -adapt_levels (the largest of --levels) by this tree's driver into
OUT/adapt (kept: a later run of the bench reuses them). The earlier driver: build the revision in a worktree, e.g.
`git worktree add /tmp/old REV && cmake -S /tmp/old -B /tmp/old/build -DCMAKE_BUILD_TYPE=Release && cmake --build
/tmp/old/build --target driver`. The reference: the sector adapted to level 5 (docs/results/adapt_bench.json).
"""
import argparse
import statistics
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from camclay9 import driver_command, read_history, read_summary, results_store, run_command
from camclay9 import kink_steps_study as study
from camclay9.performance_doc import publish
from camclay9.results_store import revision
from indent_convergence_bench import run

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "input" / "nanoindent_kerogen_sector.yaml"


def meshes(out, levels):
    """The adapted levels' meshes (OUT/adapt/adapt/level<k>/mesh.msh), made by this tree's driver unless there."""
    adapt = out / "adapt"
    paths = {k: adapt / "adapt" / f"level{k}" / "mesh.msh" for k in levels}
    done = (adapt / "summary.json").is_file() and read_summary(adapt)["completed"]
    if not (done and all(p.is_file() for p in paths.values())):
        print(f"meshes: {SCENE.name} -adapt_levels {max(levels)} into {adapt}", flush=True)
        run_command(driver_command(SCENE, adapt, options=["-adapt_levels", max(levels)], root=ROOT), timeout=7200,
                    cwd=out)
    return paths


def scene_on(mesh):
    """The scene's text on a mesh file instead of its geometry."""
    lines = []
    for line in SCENE.read_text().splitlines():
        if line.startswith("  geometry:"):
            lines.append(f"  file: {mesh}")
        elif not line.startswith("  parameters:"):
            lines.append(line)
    return "\n".join(lines) + "\n"


def one_run(driver, exe, level, mesh, out):
    r = run(scene_on(mesh), out / f"{driver}_level{level}", driver=exe)
    h = read_history(out / f"{driver}_level{level}")
    load = h[h["stage_name"] == "load"][1:]
    o = r["o"]
    row = {"driver": driver, "level": level, "unknowns": r["unknowns"], "steps": r["steps"], "load_steps": len(load),
           "load_kinks": int((load["active_changes"] > 0).sum()), "load_dt_median": float(statistics.median(load["dt"])),
           "umat_calls": r["umat_calls"], "cpu_s": r["cpu"],
           "outputs": {"P": o["load at end of loading"], "creep": o["creep depth"] * 1e3, "h_res": o["residual depth"] * 1e3}}
    print(f"{driver} level {level}: {row['steps']} steps ({row['load_kinks']} of {row['load_steps']} loading steps across "
          f"a kink), CPU {row['cpu_s']:.0f} s, " + ", ".join(f"{k} {v:.6g}" for k, v in row["outputs"].items()), flush=True)
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, help="the earlier driver's executable")
    ap.add_argument("--before-rev", required=True, help="its revision (for the store)")
    ap.add_argument("--levels", default="0,2", help="the adapted levels to run (default: %(default)s)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at once (default: %(default)s)")
    ap.add_argument("--out", default=str(ROOT / "out" / "kink_steps"), help="the runs' folders (default: %(default)s)")
    ap.add_argument("--machine", default="2 cores, two runs at once, the machine otherwise idle")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    levels = [int(k) for k in a.levels.split(",")]
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    paths = meshes(out, levels)
    todo = [(d, exe, k, paths[k], out) for k in sorted(levels, reverse=True)
            for d, exe in (("before", Path(a.before).resolve()), ("after", None))]
    with ThreadPoolExecutor(a.jobs) as pool:
        rows = list(pool.map(lambda t: one_run(*t), todo))
    sector = results_store.load("adapt_bench")["cases"]["sector"]["levels"][5]
    reference = {k: sector["q"][k] for k in ("P", "creep", "h_res")}
    reference["from"] = f"the sector adapted to level 5 ({sector['unknowns']} unknowns; docs/results/adapt_bench.json)"
    cmd = f"bench/kink_steps_bench.py --before BEFORE/build/bin/driver --before-rev {a.before_rev}" + \
        (f" --levels {a.levels}" if a.levels != "0,2" else "")
    store = {"provenance": {"command": cmd, "date": time.strftime("%Y-%m-%d", time.gmtime()),
                            "rev": revision(ROOT) or "unknown", "machine": a.machine},
             "before_rev": a.before_rev, "reference": reference, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
