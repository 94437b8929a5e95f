#!/usr/bin/env python3
"""Mesh and element study of the paper's 2D indentation scenes (issue 26, items 1-3): how converged the loading-rate
and bedding studies are, why P1 and P2 differ, and the cheapest model within 1 % of its own converged answer on the
depths and the creep depth and 5 % on the stress under the tip.

The scenes are input/loading_rate_a1.yaml and input/bedding_theta45.yaml as shipped (plane strain, the wedge of the
Berkovich's section; the shipped time-step settings), the loading-rate scene on the whole block its half model is half of
(camclay9.indent2d_study.whole_block: the model the ladders ran on), with an unload stage added (to zero in 20 s, as the 3D
scenes) for the residual depth, on ladders of
  h_tip   the element size within r_fine of the tip (ratio about sqrt 2; h_far = FAR h_tip: the whole mesh refined);
  r_fine  the fine zone's radius at a fixed h_tip (the shipped 0.4 um ends inside the loading-rate contact);
each with P1 and P2 triangles. Reported per rung: the depth at the end of loading, the creep depth over the hold,
the residual depth, the mean of |sigma| over a fixed region under the tip (|x| < a/4, -a/2 < y < 0 of the undeformed
mesh, a the contact half-width at the end of loading rounded: the cells clipped to it, camclay9.indent_fields) at the
end of the load and of the hold and its change over the hold (Fig. 13's quantity), the checkerboard of |sigma| within
a of the tip, steps, CPU (user + system of the driver), UMAT calls, and the ratio CPU / (UMAT calls x the UMAT
benchmark's time per viscoplastic plane-strain call, measured by build/bench/umat_bench at the start of the same
invocation).

Results go to a JSON file as each rung finishes (--results, default out/indent2d_convergence.json; rerunning skips
the rungs already there, from any ladder), so the study can be cut and resumed. --doc writes the section "## 2D
indentation: mesh and element study" of docs/performance.md from that file, followed by the reading written by hand
in bench/indent2d_convergence_conclusions.md (the ladders and the section: camclay9.indent2d_study).

Usage: bench/indent2d_convergence_bench.py [--ladders lr2,lr1,...] [--hmin H] [--max-unknowns N] [--doc [--no-run]] [--quick]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import read_history, results_store
from camclay9.indent2d_study import (LADDERS, R2, SCENES, STORE, TITLE, key, ratio_cell, rungs, section,
                                     store_data, whole_block)
from indent_convergence_bench import run
from camclay9.performance_doc import replace_section
from step_control_bench import absolute, output_tol

ROOT = Path(__file__).resolve().parents[1]
UMAT_BENCH = ROOT / "build" / "bench" / "umat_bench"
FAR = 7.5   # h_far / h_tip, as shipped (0.15 / 0.02)
UNLOAD = ("  - name: unload\n    duration: 20\n    indenter: {load: 0}\n"
          "    steps: {adaptive: true, first: 1, min: 1.0e-9, max: 1, error: {measure: output, tol: 0.1}}\n")


def scene_text(skey, order, h_tip, r_fine, tol=None, far=FAR):
    """The scene as shipped with this mesh (one uniform mesh: step_control_bench.absolute drops a mesh.adapt), fields at the stages' ends only, and the unload stage; tol: the load and
    hold stages' output error tolerance (shipped 1.5e-2)."""
    name, scale, _, change = SCENES[skey]
    t = whole_block(absolute((ROOT / "input" / f"{name}.yaml").read_text()))   # the ladders' model: the whole block
    if change:
        assert change[0] in t, f"{name}.yaml: no '{change[0]}' to change"
        t = t.replace(change[0], change[1])
    if tol:
        t = output_tol(t, tol)
    t = re.sub(r"h_tip: [0-9.e-]+", f"h_tip: {h_tip:.6g}", t, count=1)
    t = re.sub(r"h_far: [0-9.e-]+", f"h_far: {far * h_tip:.6g}", t, count=1)
    t = re.sub(r"r_fine: [0-9.e-]+", f"r_fine: {r_fine:.6g}", t, count=1)
    t = re.sub(r"\n  order: \d+", "", t, count=1)
    t = re.sub(r"(\n  kinematics: \w+)", rf"\1\n  order: {order}", t, count=1)
    return t.replace("\noutput:", "\n" + UNLOAD.rstrip("\n") + "\noutput:", 1)


def umat_time_per_call():
    """The UMAT benchmark's time per viscoplastic plane-strain call [s] (median, min), measured now. The benchmark
    times with the wall clock; on a shared machine each is scaled by the benchmark process's CPU / wall share, so
    that it compares with the driver's CPU time."""
    if not UMAT_BENCH.is_file():
        return None, None
    t0, c0 = time.perf_counter(), os.times()
    out = subprocess.run([str(UMAT_BENCH), "200000", "5"], capture_output=True, text=True, timeout=600).stdout
    wall, c1 = time.perf_counter() - t0, os.times()
    share = min(1.0, ((c1.children_user - c0.children_user) + (c1.children_system - c0.children_system)) / wall)
    m = re.search(r"viscoplastic, both frames yield \| 4 \|\s*([0-9.]+) \|\s*([0-9.]+)", out)
    return (float(m.group(1)) * 1e-9 * share, float(m.group(2)) * 1e-9 * share) if m else (None, None)


def field_numbers(out, region):
    """Region means of |sigma| at the end of the load and of the hold; within a of the tip at the end of the hold,
    the checkerboard of |sigma| and how far the viscoplastic flow is from isochoric (|tr evp| / |dev evp|, area
    weighted: near 0 is the incompressibility that locks linear triangles)."""
    from camclay9.fields import Fields, dev_norm, tensor_norm, trace
    from camclay9.indent_fields import cell_areas, checkerboard, clipped_areas, region_mean, six
    from camclay9.indent_plots import History, STAGE_COLUMNS
    t0, t1 = History(out, need=STAGE_COLUMNS).hold_times()
    with Fields(out) as F:
        w = clipped_areas(F, region)
        s0 = tensor_norm(six(F, "stress", F.nearest(t0)), False)
        s1 = tensor_norm(six(F, "stress", F.nearest(t1)), False)
        a = 4 * (region[1] - region[0]) / 2
        near = (np.hypot(F.centroids[:, 0], F.centroids[:, 1]) < a) & (F.centroids[:, 1] < 0)
        e, A = six(F, "evp", F.nearest(t1)), cell_areas(F) * near
        return dict(sig_load=region_mean(s0, w), sig_hold=region_mean(s1, w), dsig=region_mean(s1 - s0, w),
                    checker=checkerboard(F, s1, near), vol=float(np.sum(A * np.abs(trace(e))) / np.sum(A * dev_norm(e, True))))


def run_rung(skey, order, h_tip, r_fine, tol, tmp, t_call):
    out = Path(tmp) / key(skey, order, h_tip, r_fine, tol).replace(":", "_")
    r = run(scene_text(skey, order, h_tip, r_fine, tol), out)
    h = read_history(out, need=("umat_calls",))
    o = r.pop("o")
    r["o"] = dict(h_max=o["depth at end of loading"], creep=o["creep depth"], h_res=o["residual depth"],
                  **field_numbers(out, SCENES[skey][2]))
    r["checker"], r["vol"] = r["o"].pop("checker"), r["o"].pop("vol")
    r.update(scene=skey, order=order, h_tip=h_tip, r_fine=r_fine, tol=tol, h_far=FAR * h_tip, umat_calls=int(h["umat_calls"][-1]),
             t_call=t_call[0], t_call_min=t_call[1])
    return r


def load(path):
    return json.loads(path.read_text()) if path.exists() else {}




def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--ladders", default="lr1r,lr2r,lr1,lr2,bed1,bed2,bed2r,lr1old", help=f"of {','.join(LADDERS)}")
    ap.add_argument("--hmin", type=float, default=0, help="only rungs with h_tip >= this (loading-rate units)")
    ap.add_argument("--max-unknowns", type=int, default=0, help="skip rungs whose mesh is estimated above this (0: all)")
    ap.add_argument("--results", default=str(ROOT / "out" / "indent2d_convergence.json"), help="JSON of the results")
    ap.add_argument("--doc", action="store_true", help="write the section of docs/performance.md from --results")
    ap.add_argument("--note", default="shared machine, 2 cores, loaded", help="machine load, for the section")
    ap.add_argument("--quick", action="store_true", help="the two coarsest P1 rungs of each scene, in a temporary file")
    ap.add_argument("--no-run", action="store_true", help="run no rung: with --doc, the section from the rungs in --results alone")
    a = ap.parse_args(argv)
    quick = tempfile.TemporaryDirectory() if a.quick else None
    path = Path(quick.name) / "quick.json" if a.quick else Path(a.results)
    path.parent.mkdir(parents=True, exist_ok=True)
    res = load(path) or ({} if a.quick else results_store.load(STORE).get("rungs", {}))
    if a.quick:
        todo = [("lr", 1, 0.04, 0.4, None), ("lr", 1, 0.04 / R2, 0.4, None), ("bed", 1, 1.0, 10.0, None)]
    else:
        todo = []
        for lad in a.ladders.split(","):
            s = SCENES[LADDERS[lad][1]][1]
            todo += [g for g in rungs(lad) if g[2] >= a.hmin * s * (1 - 1e-9) and g not in todo]
        todo.sort(key=lambda g: g[1] ** 2 * (g[3] / g[2]) ** 2)   # cheapest first: unknowns about order^2 (r_fine / h_tip)^2
    todo = [] if a.no_run else [g for g in todo if key(*g) not in res]
    t_call = umat_time_per_call() if todo else (0, 0)
    if todo:
        print(f"UMAT benchmark: {t_call[0] * 1e9:.0f} ns per viscoplastic plane-strain call (median; min {t_call[1] * 1e9:.0f})"
              if t_call[0] else "UMAT benchmark: not built (no ratio)", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        for g in todo:
            k = key(*g)
            try:
                r = run_rung(*g, tmp, t_call)
            except RuntimeError as e:
                why = [ln for ln in str(e).splitlines() if ln.startswith("driver:")]
                res[k] = dict(scene=g[0], order=g[1], h_tip=g[2], r_fine=g[3], tol=g[4], failed=why[-1] if why else str(e)[-300:])
                path.write_text(json.dumps(res, indent=1))
                print(f"{k}: failed: {res[k]['failed']}", flush=True)
                continue
            res[k] = r
            path.write_text(json.dumps(res, indent=1))
            o = r["o"]
            print(f"{k}: {r['unknowns']} unknowns, h_max {o['h_max'] * 1e3:.2f} nm, creep {o['creep'] * 1e3:.3f} nm, h_res "
                  f"{o['h_res'] * 1e3:.2f} nm, sigma load/hold {o['sig_load']:.1f}/{o['sig_hold']:.1f} MPa (change "
                  f"{o['dsig']:+.1f}), checker {r['checker']:.3f}, |tr|/|dev| evp {r['vol']:.3f}, {r['steps']} steps, CPU {r['cpu']:.1f} s, "
                  f"{r['umat_calls']} UMAT calls{', x' + ratio_cell(r) if ratio_cell(r) else ''}", flush=True)
    if a.doc and not a.quick:
        store = store_data(res, "bench/indent2d_convergence_bench.py " + " ".join(argv or sys.argv[1:]), a.note)
        print(f"written: {results_store.save(STORE, store)}")
        replace_section(TITLE, section(store, results_store.load("paper"), ROOT))
        print("written: docs/performance.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
