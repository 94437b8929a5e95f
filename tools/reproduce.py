#!/usr/bin/env python3
"""Reproduce Yin, Liu & Borja (2021) in one command: run every scene of the paper, draw its figures, write
the comparison with the paper (docs/paper.md), and check the trends the paper states.

Usage: tools/reproduce.py [--quick] [--out DIR] [--driver PATH] [--jobs 2] [--docs | --no-docs]

  full (default)  the shipped scenes (input/*.yaml) as they are (the loading-rate scenes with fields every
                  FIELDS_EVERY steps besides); output in out/paper; writes docs/paper.md and its images
                  (docs/paper/), its numbers into the results store (docs/results/paper.json) and the run times
                  into docs/performance.md ("Reproducing the paper").
  --quick         coarse variants of the same scenes (meshes coarsened, the UMAT's step tolerance 1e-3, the
                  same loads, durations and materials), written as scene files into DIR/scenes; output in
                  out/paper_quick; writes DIR/paper.md (docs/ only with --docs). Exits 1 unless the four
                  trends the paper states hold (camclay9.paper_numbers, check_trends).

Scenes run two at a time (--jobs), each driver on one core; the triaxial cylinders of the full run use
`mpiexec -n 2` and take both slots. One progress line per scene as it starts and as it ends.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import yaml
from camclay9 import paper_doc, paper_figures, paper_numbers, results_store
from camclay9.blas import openblas_core
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parent.parent

# key: (scene file in input/, quick overrides). Quick: mesh parameters, a looser step control (the stages'
# output error measure at QUICK_OUTPUT_TOL, or the UMAT's tol where a scene has none), fields_every. Order: longest first in the full run (the 3D microindentation).
IND2 = {"tol": 1.0e-3, "fields_every": 20, "order": 1}  # quick 2D: P1 (the shipped scenes are P2)
# The full run's loading-rate scenes write their fields every FIELDS_EVERY steps as well (output.fields_every: the
# steps do not land on them, and fields written for output.fields_every alone do not enter the error indicator's
# history (docs/adapt.md), so the run adapts to the shipped scene's meshes and is its run step for step): Fig. 13's stress under the tip is
# then sampled through the hold (about 20 outputs, the hold's steps growing about geometrically), not at its four
# output times alone (issue 36, referee's defect 9).
FIELDS_EVERY = 25
LR_FULL = {"full": {"fields_every": FIELDS_EVERY}}
MESH_SCALED = ("h_tip", "r_fine")  # a variant's mesh_scale: the sizes near the tip (a "full" mesh's sizes override it in the full run)
QUICK_OUTPUT_TOL = 0.05  # quick: the output error measure's tol (the shipped scenes: 1.5e-2)
SCENES = {
    # the 3D scenes on their cheapest exact model (README, "Which model each scene uses"): kerogen and BN on the
    # 60-degree sector, BP (no sector: its bedding normal e_x) on the half model, each on meshes adapted by rerun
    # (docs/adapt.md): kerogen's within 1 % of the converged 3D answer in all three outputs, BN's and BP's residual
    # depths converged, each with its stated mesh error; quick: P1 on a coarse mesh
    "microindent_BN": {"file": "microindent_BN_sector_adapt", "mesh": {"h_tip": 5, "h_far": 20}, "order": 1, "tol": 1.0e-3},
    "microindent_BP": {"file": "microindent_BP_adapt", "mesh": {"h_tip": 5, "h_far": 20}, "order": 1, "tol": 1.0e-3},
    "nanoindent_kerogen": {"file": "nanoindent_kerogen_sector_adapt", "mesh": {"h_tip": 0.2, "h_far": 0.8}, "order": 1, "tol": 1.0e-3},
    "loading_rate_a0.1": dict(IND2, mesh={"h_tip": 0.05, "h_far": 0.3, "r_fine": 0.4}, **LR_FULL),
    "loading_rate_a1": dict(IND2, mesh={"h_tip": 0.05, "h_far": 0.3, "r_fine": 0.4}, **LR_FULL),
    "loading_rate_a10": dict(IND2, mesh={"h_tip": 0.05, "h_far": 0.3, "r_fine": 0.4}, **LR_FULL),
    "bedding_theta0": dict(IND2, mesh={"h_tip": 1.25, "h_far": 7.5}),
    "bedding_theta30": dict(IND2, mesh={"h_tip": 1.25, "h_far": 7.5}),
    "bedding_theta45": dict(IND2, mesh={"h_tip": 1.25, "h_far": 7.5}),
    "bedding_theta60": dict(IND2, mesh={"h_tip": 1.25, "h_far": 7.5}),
    "bedding_theta90": dict(IND2, mesh={"h_tip": 1.25, "h_far": 7.5}),
    # Fig. 14's sensitivity to the plane-strain thickness (the paper gives none): 3 um, about the Berkovich-equivalent
    # thickness at 15 mN (t = 4.9 h_B, h_B = 0.62 um), the indent about a third as wide: the fine zone scaled by 1/3
    # (r_fine 3.33 um, about 1.5 times the contact's half-width), its cells h_tip 0.125 um (half the 0.25 um of the 1 um scene's uniform mesh before it adapted), the
    # far field coarser than at 1 um (h_far 3.75 um: the block is the same 50 um, the fine zone a third as wide).
    # Measured (2026-12-01, one rank; the scenes this writes, out/paper/scenes/bedding_theta*_t3.yaml, run by the
    # driver with their mesh parameters changed) against a fine mesh, h_tip 0.059 um and h_far 0.625 um: depth at the
    # end of loading and creep depth. theta = 45 (208 k unknowns; 0.87825 and 0.29121 um): h_far 0.625 um as well
    # (158 k) -0.02 % and -0.19 %; h_far 1.875 um (52 k) -0.02 % and -0.37 %; h_tip 0.083 um, the fine zone's cells
    # scaled by 1/3 too (35.9 k unknowns, 73 s CPU) -0.02 % and +0.04 %; as here (19.6 k, 45 s, two runs at once)
    # -0.03 % and -0.58 %; h_tip 0.167 um (13.5 k) -0.04 % and -0.61 %; 0.25 um (8.6 k) -0.15 % and -0.56 %.
    # theta = 90, the half model (104 k unknowns; 0.84590 and 0.30734 um): h_tip 0.083 um -0.03 % and -0.15 %; as here
    # (9.8 k, 13 s) -0.08 % and -0.22 %; 0.167 um -0.09 % and -0.69 %; 0.25 um -0.22 % and -1.48 %. The 1 um scene's
    # uniform mesh was -0.8 % in creep depth against its converged 2D answer (docs/performance.md, "2D indentation: mesh
    # and element study"). One mesh each ("adapt": False): the 1 um scenes rerun on an adapted mesh, these do not.
    **{f"bedding_theta{t}_t3": dict(IND2, file=f"bedding_theta{t}", mesh={"h_tip": 1.25, "h_far": 7.5}, thickness=3,
                                    mesh_scale=1 / 3, full={"mesh": {"h_tip": 0.125, "h_far": 3.75}, "adapt": False})
       for t in (0, 30, 45, 60, 90)},
    "triaxial_theta0": {"mesh": {"size": 12.0}, "mpi": 2},
    "triaxial_theta90": {"mesh": {"size": 12.0}, "mpi": 2},
}


def scene_file(key):
    """The shipped scene that runs the paper's scene key (its own name, or the cheaper exact model's)."""
    return ROOT / "input" / f"{SCENES[key].get('file', key)}.yaml"


def variant_scene(key, dest, quick):
    """Write the scene of key to dest: input/<file>.yaml with an absolute mesh path and the key's variant (a
    plane-strain thickness, the mesh's lengths scaled; in the full run, then the outputs and mesh sizes of "full"), and with --quick
    its coarse variant (quick_scene)."""
    q = SCENES[key]
    d = yaml.safe_load(scene_file(key).read_text(encoding="utf-8"))
    geo = Path(d["mesh"]["geometry"])
    d["mesh"]["geometry"] = str((ROOT / "meshes" / geo.name).resolve())
    if quick:
        quick_scene(q, d)
    if "thickness" in q:
        d["mesh"]["thickness"] = q["thickness"]
        d["name"] = key
    if "mesh_scale" in q:
        for k in MESH_SCALED:
            d["mesh"]["parameters"][k] *= q["mesh_scale"]
    if not quick and "full" in q:  # the full run's outputs and mesh sizes, as given (after the scale)
        full = q["full"]
        if "fields_every" in full:
            d["output"]["fields_every"] = full["fields_every"]
        d["mesh"]["parameters"].update(full.get("mesh", {}))
        if full.get("adapt") is False:   # the mesh as given, no rerun on an adapted one
            d["mesh"].pop("adapt", None)
    what = "coarse variant" if quick else "variant"
    dest.write_text(f"# {what} of input/{scene_file(key).name} written by tools/reproduce.py{' --quick' if quick else ''}\n"
                    + yaml.safe_dump(d, sort_keys=False), encoding="utf-8")
    return dest


def quick_scene(q, d):
    """The coarse variant of a scene (its dict d, changed in place): coarser mesh, looser step control; loads,
    durations, materials and boundary conditions unchanged."""
    d["mesh"]["parameters"].update(q.get("mesh", {}))
    d["mesh"].pop("adapt", None)   # one coarse mesh: no reruns
    if "order" in q:
        d["mesh"]["order"] = q["order"]
    if "tol" in q:  # looser step control: the stages' error measure (output, relative), else the UMAT's tol
        stages = [st for st in d.get("stages", []) if isinstance(st.get("steps"), dict) and "error" in st["steps"]]
        for st in stages:
            st["steps"]["error"]["tol"] = max(st["steps"]["error"]["tol"], QUICK_OUTPUT_TOL)
        if not stages:
            d["material"].setdefault("set", {})["tol"] = q["tol"]
    if "fields_every" in q:
        d["output"]["fields_every"] = q["fields_every"]


def mpiexec():
    exe = shutil.which("mpiexec")
    return [exe, "--allow-run-as-root", "--oversubscribe", "-n", "2"] if exe else None


class Job:
    def __init__(self, key, scene, out, driver, ranks, timeout=None):
        self.key, self.out, self.ranks, self.timeout = key, out, ranks, timeout
        cmd = [driver, "-input", str(scene), "-output_dir", str(out)]
        self.cmd = (mpiexec() + cmd) if ranks > 1 else cmd
        self.proc = self.log = None
        self.t0 = self.wall = self.cpu = None

    def start(self):
        self.out.mkdir(parents=True, exist_ok=True)
        self.log = open(self.out / "driver.log", "w", encoding="utf-8")
        self.t0 = time.monotonic()
        self.proc = subprocess.Popen(self.cmd, cwd=ROOT, stdout=self.log, stderr=subprocess.STDOUT)

    def reap(self, flags):
        """The exit status once the run has ended (None before), with its CPU seconds: user + system of the driver and
        of every process it waited for (gmsh; mpiexec's ranks), from wait4's resource usage."""
        pid, status, usage = os.wait4(self.proc.pid, flags)
        if pid == 0:
            return None
        self.proc.returncode = os.waitstatus_to_exitcode(status)
        self.cpu = usage.ru_utime + usage.ru_stime
        return self.proc.returncode

    def poll(self):
        rc = self.reap(os.WNOHANG)
        if rc is None and self.timeout and time.monotonic() - self.t0 > self.timeout:
            self.proc.kill()   # --job-timeout: a hung run fails instead of holding the whole reproduction
            rc = self.reap(0)
            print(f"{self.key}: killed after {self.timeout:g} s (--job-timeout)", flush=True)
        if rc is not None:
            self.wall = time.monotonic() - self.t0
            self.log.close()
        return rc


def last_line(path, prefix):
    lines = [ln for ln in path.read_text(encoding="utf-8", errors="replace").splitlines() if ln.strip()]
    hits = [ln for ln in lines if ln.startswith(prefix)]
    return (hits or lines or ["(no output)"])[-1]


def kept_levels(out):
    """The adapted levels a run reused from an earlier run into the same directory instead of running them (its
    summary.json, levels[].kept; docs/adapt.md, "Kept meshes"): its CPU and wall time leave them out."""
    path = out / "summary.json"
    levels = json.loads(path.read_text(encoding="utf-8")).get("levels", []) if path.is_file() else []
    return [k for k, lv in enumerate(levels) if lv.get("kept")]


def run_all(jobs, slots):
    """Run the jobs, at most `slots` cores busy (an MPI job of n ranks takes n). Returns {key: wall}, {key: CPU},
    the keys of the runs that failed and {key: adapted levels kept from an earlier run} (kept_levels)."""
    pending, running, walls, cpus, failed, kept = list(jobs), [], {}, {}, [], {}
    n, done = len(jobs), 0
    while pending or running:
        busy = sum(j.ranks for j in running)
        while pending and busy + min(pending[0].ranks, slots) <= slots:
            j = pending.pop(0)
            j.start()
            busy += j.ranks
            running.append(j)
            print(f"[{done:2d}/{n}] start {j.key} ({j.ranks} rank{'s' if j.ranks > 1 else ''})", flush=True)
        time.sleep(0.2)
        for j in list(running):
            rc = j.poll()
            if rc is None:
                continue
            running.remove(j)
            done += 1
            walls[j.key], cpus[j.key] = j.wall, j.cpu
            levels = kept_levels(j.out)
            if levels:
                kept[j.key] = levels
            summary = last_line(j.out / "driver.log", ("indentation", "fe scene"))
            status = "done" if rc == 0 else f"FAILED (exit {rc})"
            print(f"[{done:2d}/{n}] {status} {j.key} in {j.wall:.1f} s ({j.cpu:.1f} s CPU): {summary[:150]}", flush=True)
            if rc != 0:
                failed.append(j.key)
    return walls, cpus, failed, kept


def record_runs(prev, walls, cpus, kept, t_runs, rerun, today, only):
    """What runs.json keeps of this run. With --only the other scenes keep their runs, times and kept levels from
    prev (the previous runs.json), and the whole run's time stays the last full run's."""
    dates = {**prev.get("dates", {}), **{k: today for k in walls}}
    if only:
        return {**prev, "walls": {**prev.get("walls", {}), **walls}, "cpus": {**prev.get("cpus", {}), **cpus},
                "wall_runs": prev.get("wall_runs", float("nan")), "rerun": rerun, "dates": dates,
                "kept": {**{k: v for k, v in prev.get("kept", {}).items() if k not in walls}, **kept}}
    return {"walls": walls, "cpus": cpus, "wall_runs": t_runs, "rerun": [], "dates": dates, "whole_run_date": today,
            "load_note": f"load average {os.getloadavg()[0]:.1f} at the end of the runs; {blas_note()}", "kept": kept}


def blas_note():
    """Which OpenBLAS kernels the runs used (camclay9.blas; reproduce.sh names the core where OpenBLAS fell back)."""
    core = openblas_core()
    named = os.environ.get("OPENBLAS_CORETYPE")
    return (f"OpenBLAS' {core} kernels" + (" (OPENBLAS_CORETYPE)" if named else "")) if core else "the BLAS is not OpenBLAS"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="coarse variants, check the paper's trends")
    ap.add_argument("--out", help="output directory (default out/paper or out/paper_quick)")
    ap.add_argument("--driver", default=os.environ.get("DRIVER", str(ROOT / "build" / "bin" / "driver")))
    ap.add_argument("--jobs", type=int, default=2, help="cores to use (default 2)")
    ap.add_argument("--job-timeout", type=float, default=None, help="seconds after which a run is killed and fails")
    ap.add_argument("--docs", dest="docs", action="store_true", default=None,
                    help="write docs/paper.md and docs/paper/*.png (default: only in the full run)")
    ap.add_argument("--no-docs", dest="docs", action="store_false")
    ap.add_argument("--only", nargs="+", help="run only these scenes (the others' runs must exist in DIR)")
    ap.add_argument("--no-run", action="store_true", help="only plot and write, from the runs already in DIR")
    a = ap.parse_args(argv)
    mode = "quick" if a.quick else "full"
    out = Path(a.out or ROOT / "out" / ("paper_quick" if a.quick else "paper")).resolve()
    docs = (not a.quick) if a.docs is None else a.docs
    if not Path(a.driver).is_file():
        raise SystemExit(f"reproduce: no driver at {a.driver} (build it: cmake -S . -B build && cmake --build build)")
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.monotonic()
    keys = a.only or list(SCENES)
    jobs = []
    for key in keys:
        if key not in SCENES:
            raise SystemExit(f"reproduce: unknown scene '{key}' (known: {', '.join(SCENES)})")
        if a.quick or "thickness" in SCENES[key] or "full" in SCENES[key]:
            (out / "scenes").mkdir(exist_ok=True)
            scene, ranks = variant_scene(key, out / "scenes" / f"{key}.yaml", a.quick), 1
        else:
            scene, ranks = scene_file(key), SCENES[key].get("mpi", 1)
            ranks = ranks if (ranks > 1 and a.jobs >= ranks and mpiexec()) else 1
        jobs.append(Job(key, scene, out / key, a.driver, ranks, a.job_timeout))
    meta_path = out / "runs.json"
    prev = json.loads(meta_path.read_text(encoding="utf-8")) if meta_path.is_file() else {}
    rerun = sorted(set(prev.get("rerun", [])) | set(a.only)) if a.only else []
    today = time.strftime("%Y-%m-%d", time.gmtime())
    if a.no_run:
        walls, cpus = prev.get("walls", {}), prev.get("cpus", {})
        t_runs, rerun = prev.get("wall_runs", float("nan")), prev.get("rerun", [])
        runs = prev
    else:
        print(f"reproduce ({mode}): {len(jobs)} scenes, {a.jobs} at a time, driver {a.driver}, output {out}", flush=True)
        walls, cpus, failed, kept = run_all(jobs, max(1, a.jobs))
        t_runs = time.monotonic() - t_start
        if failed:
            print(f"reproduce: {len(failed)} scene(s) failed: {', '.join(failed)} (see DIR/<scene>/driver.log)")
            return 1
        runs = record_runs(prev, walls, cpus, kept, t_runs, rerun, today, bool(a.only))
        walls, cpus, t_runs = runs["walls"], runs["cpus"], runs["wall_runs"]
        meta_path.write_text(json.dumps(runs) + "\n", encoding="utf-8")
    print(f"runs: {t_runs:.1f} s wall; plotting", flush=True)
    t_plot = time.monotonic()
    numbers = paper_numbers.collect(out)
    images = paper_figures.draw_all(out, numbers)
    trends = paper_numbers.check_trends(numbers)
    t_all = time.monotonic() - t_start
    partial = bool(rerun) or a.no_run
    total = runs.get("wall_total") if partial and runs.get("wall_total") else (
        t_runs + (time.monotonic() - t_plot) if partial else t_all)
    if not partial:
        runs["wall_total"] = total
        meta_path.write_text(json.dumps(runs) + "\n", encoding="utf-8")
    meta = {"mode": mode, "date": today, "wall_runs": t_runs, "wall_total": total, "walls": walls, "cpus": cpus, "out": str(out),
            "rerun": rerun, "run_dates": runs.get("dates", {}), "whole_run_date": runs.get("whole_run_date", today),
            "load_note": runs.get("load_note", "load not recorded"), "kept": runs.get("kept", {}),
            "scene_source": "input/*.yaml as shipped" if not a.quick else "coarse variants (out/.../scenes)"}
    paper_doc.write(out / "paper.md", numbers, trends, images, meta, image_dir=out / "figures")
    if docs:
        paper_doc.write(ROOT / "docs" / "paper.md", numbers, trends, images, meta, image_dir=ROOT / "docs" / "paper")
        store = paper_doc.store_data(numbers, images, meta)
        print(f"written: {results_store.save('paper', store, ROOT / 'docs' / 'results')}")
        write_performance(meta)
    print(f"reproduce ({mode}): runs {t_runs:.1f} s, total {meta['wall_total']:.1f} s wall; {out / 'paper.md'}"
          + (f", {ROOT / 'docs' / 'paper.md'}" if docs else ""))
    for t in trends:
        print(f"trend {'PASS' if t['ok'] else 'FAIL'}: {t['name']}: {t['detail']}")
    if a.quick and not all(t["ok"] for t in trends):
        return 1
    return 0


def write_performance(meta):
    """The run times into docs/performance.md (section "## Reproducing the paper"), from the same meta data as
    docs/paper.md's (paper_doc.performance_section)."""
    replace_section(paper_doc.PERFORMANCE_TITLE, paper_doc.performance_section(meta), ROOT / "docs" / "performance.md")


if __name__ == "__main__":
    sys.exit(main())
