"""
Mesh convergence of the 3D Cam-Clay indentation scenes (issue 12, items 3-4; issue 25, item 5): how converged are
the 3D answers, and which model and element order reaches <= 2 % of the converged 3D answer at the least CPU time.

Each ladder (camclay9.indent3d_study.MODELS) is a scene of input/ as shipped (Cam-Clay IX; P = P0 exp(k t) up to the target
depth, hold 60 s, unload in 20 s; the shipped adaptive time-step settings, output measure tol 1.5e-2) on meshes of
h_tip at ratio about sqrt 2:
  kerogen (nanoindent_kerogen*.yaml, phi = 0, 200 nm):
    sector2    the 60-degree sector (meshes/indent_sector.geo), P2, h_far = 4 h_tip;
    sector2f8  the same with h_far = 8 h_tip: the shipped scene's family;
    sector1    the same, P1 (h_far 8 h_tip: the node spacing of sector2);
    half2      the half model (meshes/indent_cube.geo), P2: an independent mesh of the sector's density;
    old1       the sector on P1 with the mesh family of the scenes before (r_fine 0.4 um: the contact's rim, at
               0.56-0.87 um, in the graded zone);
    axi1/2     the axisymmetric twin (cone of equal area, meshes/indent_block2d.geo), P1 and P2;
  BN (microindent_BN_sector.yaml, phi = 0.5, bedding normal e_z, 5 um; the kerogen mesh scaled by 25):
    bn2, bn1   the 60-degree sector, P2 and P1, h_far = 8 h_tip;
    bnaxi2/1   BN's axisymmetric twin (microindent_BN_axi.yaml, the cone of equal area), P2 and P1;
  BP (microindent_BP.yaml, bedding normal e_x: no sector):
    bp2        the half model, P2, h_far = 8 h_tip.
The 3D family: h_tip within r_fine of the tip (0.9 um, x 25 for BN and BP: the whole contact), growing to h_far;
axisymmetric: r_fine as shipped, h_far = 7.5 h_tip. Fields off, one rank, each rung under nice -n 10. Reported: the
indenter's whole load at the end of loading (the scenes say indenter.copies), the depth there, the creep depth over
the hold, the residual depth after unloading; steps, Newton iterations, UMAT calls, factorisations; CPU time (user +
system of the driver and its gmsh, from wait4: the machine is shared) and peak memory.

Results go to a JSON file as they come (--results, default docs/results/indent_convergence.json, the store kept in
git, each rung with its date and commit; rerunning skips the rungs already there), so a long ladder can be cut and
resumed. Before each rung its CPU time and memory are extrapolated
from the ladder's two rungs above it, and a rung above --max-cpu is skipped. --doc writes the section "## 3D
indentation: mesh convergence and the cheapest model" of docs/performance.md from that file
(camclay9.indent3d_study, which tools/doc_numbers.py also checks it against), followed by the reading of the tables
written by hand in bench/indent_convergence_conclusions.md (its numbers are quoted from the store:
camclay9.doc_quotes). The ladders are in camclay9.indent3d_study.MODELS.

Usage: bench/indent_convergence_bench.py [--models sector2,sector1,bn2,...] [--hmin H] [--rungs N] [--quick] [--doc]
"""
import argparse
import math
import re
import resource
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from camclay9 import driver_command, mesh_line, read_history, run_measured, summary_line
from camclay9 import results_store
from camclay9.results_store import revision
from camclay9.indent3d_study import MODELS, SHORT, TITLE, key, ladder, ladders, limits, section
from camclay9.performance_doc import replace_section
from step_control_bench import absolute, output_tol, outputs

ROOT = Path(__file__).resolve().parents[1]


def scene(model, h_tip, tol=None, work=None):
    """The scene of one rung; a nested ladder's mesh is made in work (nested_mesh)."""
    m = MODELS[model]
    order, far, r_fine, base = m["order"], m["far"], m["r_fine"], m.get("nested")
    t = absolute((ROOT / "input" / f"{m['scene']}.yaml").read_text())
    if tol:  # the load and hold stages' output tolerance (shipped: 1.5e-2; the unload stage's 0.1 kept)
        t = output_tol(t, tol)
    t = re.sub(r"h_tip: [0-9.e-]+", f"h_tip: {base or h_tip:.6g}", t, count=1)
    t = re.sub(r"h_far: [0-9.e-]+", f"h_far: {far * (base or h_tip):.6g}", t, count=1)
    if r_fine:
        t = re.sub(r"r_fine: [0-9.e-]+", f"r_fine: {r_fine:g}", t, count=1)
    t = re.sub(r"\n  order: \d+", "", t, count=1)
    t = re.sub(r"(\n  kinematics: \w+)", rf"\1\n  order: {order}", t, count=1)
    return nested_mesh(t, round(math.log2(base / h_tip)), work) if base else t


def nested_mesh(text, n, work):
    """Mesh the scene's geometry with its parameters as the driver would (gmsh -3), split every tetrahedron into
    eight n times (gmsh -refine: the edges' midpoints, so each mesh holds the one before it), and point the scene's
    mesh.file at the result."""
    geo = re.search(r"\n  geometry: (\S+)", text).group(1)
    params = dict(kv.split(": ") for kv in re.search(r"\n  parameters: \{([^}]*)\}", text).group(1).split(", "))
    msh = Path(work) / f"{Path(geo).stem}_{'_'.join(f'{k}{v}' for k, v in params.items())}_r{n}.msh"
    if not msh.exists():
        cmd = ["gmsh", "-3", "-format", "msh41", "-v", "2", geo] + [x for k, v in params.items() for x in
                                                                      ("-setnumber", k, v)] + ["-o", str(msh)]
        subprocess.run(cmd, check=True, capture_output=True, timeout=3600)
        for _ in range(n):
            subprocess.run(["gmsh", str(msh), "-refine", "-format", "msh41", "-v", "2", "-o", str(msh)], check=True,
                           capture_output=True, timeout=3600)
    return re.sub(r"\n  geometry: \S+\n  parameters: \{[^}]*\}", f"\n  file: {msh}", text, count=1)


TIMEOUT = 24 * 3600  # s, one rung (the finest 3D rungs take hours)


def run(text, out, driver=None):
    """One rung under nice -n 10: its outputs, and the driver's CPU (user + system, gmsh's meshing included) and
    peak memory (camclay9.run_measured, wait4), counts from its summary line. driver: another executable than this
    tree's build/bin/driver."""
    out.parent.mkdir(parents=True, exist_ok=True)
    path = out.parent / (out.name + ".yaml")
    path.write_text(text)
    log = out.parent / (out.name + ".log")
    rc, cpu, rss_mb, wall = run_measured(driver_command(path, out, driver=driver, root=ROOT, prefix=["nice", "-n", "10"]), log,
                                         timeout=TIMEOUT, cwd=out.parent)
    stdout = log.read_text()
    if rc:
        raise RuntimeError(f"{path}: the driver failed:\n{stdout[-2000:]}")
    s = summary_line(stdout, index=0)
    h = read_history(out)
    return dict(wall=wall, cpu=cpu, rss_mb=rss_mb, steps=s["steps"], solver=s["linear_solver"],  # the one auto chose
                newton=s["newton_iterations"], umat_calls=s["umat_calls"], solve_s=s["linear_solves_s"],
                krylov=s["krylov_iterations"], factorisations=s["factorisations"],
                unknowns=mesh_line(stdout)["unknowns"], o={k: float(v) for k, v in outputs(h).items()})


def repeated(todo, one, jobs, keys, key, same):
    """Whole runs of a bench that repeats them: one(*t) for each t of todo, jobs at once (the runs' CPU from wait4,
    each its own process). The store's rows: for each of keys (in that order) that ran, its first run's row with cpu_s
    and wall_s the lists over its repeats, which must agree in the fields same (one rank: the same answer)."""
    with ThreadPoolExecutor(jobs) as pool:
        runs = list(pool.map(lambda t: one(*t), todo))
    rows = []
    for k in keys:
        mine = [r for r in runs if key(r) == k]
        if mine:
            for f in same:
                assert all(r[f] == mine[0][f] for r in mine), f"{k}: the repeats differ in {f}"
            rows.append(dict(mine[0], cpu_s=[r["cpu_s"] for r in mine], wall_s=[r["wall_s"] for r in mine]))
    return rows


def repeat_args(argv, description, scenes, out):
    """The options of a bench that repeats whole runs of shipped scenes (repeated): --scenes (default scenes), --repeats,
    --jobs, --out (default out/<out>), --machine, --no-doc; parsed from argv."""
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument("--scenes", default=scenes)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=2, help="runs at once (default: %(default)s)")
    ap.add_argument("--out", default=str(ROOT / "out" / out), help="the runs' folders (default: %(default)s)")
    ap.add_argument("--machine", default="2 cores, two runs at once, the machine otherwise idle")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    a.defaults = {"scenes": scenes, "repeats": 3, "jobs": 2}
    return a


def repeat_provenance(script, a):
    """The store's provenance of such a bench's run (repeat_args): the command with the options that differ from
    their defaults, the date, the revision and the machine."""
    cmd = f"bench/{script}" + "".join(f" --{k} {getattr(a, k)}" for k, d in a.defaults.items() if getattr(a, k) != d)
    return {"command": cmd, "date": time.strftime("%Y-%m-%d", time.gmtime()), "rev": revision(ROOT) or "unknown",
            "machine": a.machine}


def estimate(res, model, h):
    """The rung's unknowns, CPU and memory extrapolated from the ladder's two finest finished rungs coarser than h
    (power laws in h_tip); None without two."""
    rows = [r for r in ladder(res, model) if r["h_tip"] > h * (1 + 1e-9)][-2:]
    if len(rows) < 2:
        return None
    a, b = rows
    x = math.log(h / b["h_tip"]) / math.log(b["h_tip"] / a["h_tip"])
    return {k: b[k] * (b[k] / a[k]) ** x for k in ("unknowns", "cpu", "rss_mb") if a.get(k) and b.get(k)}


def report(r):
    o, g = r["o"], MODELS[r["model"]]["group"]
    return (f"{r['model']}{' tol ' + format(r['tol'], 'g') if r.get('tol') else ''} h_tip {r['h_tip']:.4g}: "
            f"{r['unknowns']} unknowns, P {o['load at end of loading']:.6g} uN, h_max {o['depth at end of loading']:.6g} um, "
            f"creep {o['creep depth'] * 1e3:.5g} nm, residual {o['residual depth']:.6g} um, {r['steps']} steps, "
            f"{r['umat_calls']} UMAT calls, {r['factorisations']} factorisations, CPU {r['cpu']:.1f} s, "
            f"{r['rss_mb']:.0f} MB, wall {r['wall']:.1f} s ({g})")


def run_rungs(todo, store, others, path, tol, max_cpu):
    """Run the rungs (model, h_tip) in order, skipping those in the store's rungs or others and those estimated above
    max_cpu; each result (or failure) is written to path at once."""
    res = store["rungs"]
    with tempfile.TemporaryDirectory() as d:
        for m, h in todo:
            k = key(m, h, tol)
            if k in res or k in others:
                continue
            est = estimate({**others, **res}, m, h)
            if est:
                print(f"{k}: estimated " + ", ".join(f"{n} {v:.3g}" for n, v in est.items()), flush=True)
                if est.get("cpu", 0) > max_cpu:
                    print(f"{k}: skipped (estimated CPU above --max-cpu {max_cpu:g} s)", flush=True)
                    continue
            try:
                c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
                text = scene(m, h, tol, d)
                c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
                r = run(text, Path(d) / k.replace(":", "_").replace("@", "_"))
                r["cpu"] += (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)  # a nested ladder's meshing
            except (RuntimeError, subprocess.CalledProcessError) as e:
                print(e, flush=True)
                why = [line for line in str(e).splitlines() if line.startswith("driver:")]
                r = dict(failed=why[-1] if why else str(e)[-300:])
            r.update(model=m, h_tip=h, tol=tol, date=time.strftime("%Y-%m-%d"), rev=revision(ROOT))  # the run's provenance
            res[k] = r
            results_store.save(path.stem, store, path.parent)
            if "failed" not in r:
                print(report(r), flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--models", default="sector2,sector1,sector2f8,bn2,bn1,bp2", help=f"comma-separated, of {','.join(MODELS)}")
    ap.add_argument("--rungs", type=int, default=0, help="at most this many rungs per ladder (0: all)")
    ap.add_argument("--tol", type=float, default=None, help="the load and hold stages' output tolerance (shipped 1.5e-2)")
    ap.add_argument("--hmin", type=float, default=0, help="only the rungs with h_tip >= this")
    ap.add_argument("--hmax", type=float, default=1e9, help="only the rungs with h_tip <= this")
    ap.add_argument("--quick", action="store_true", help="a 2-rung smoke run of each model (coarsest rungs), no document")
    ap.add_argument("--results", default=str(ROOT / "docs" / "results" / "indent_convergence.json"),
                    help="JSON file of the results (written); more files after commas are read too (e.g. parallel runs)")
    ap.add_argument("--doc", action="store_true", help="write the section of docs/performance.md from --results "
                    "(camclay9.indent3d_study), the command and date into its provenance")
    ap.add_argument("--command", default=None, help="the command(s) to name in the section (default: this one)")
    ap.add_argument("--max-cpu", type=float, default=7200,
                    help="skip a rung whose CPU time, extrapolated from its ladder's two rungs above it, exceeds this [s]")
    ap.add_argument("--note", default="shared machine, 2 cores, loaded", help="machine load, for the section")
    a = ap.parse_args(argv)
    models = [m for m in a.models.split(",") if m]
    rungs = 2 if a.quick else a.rungs
    files = [Path(f) for f in a.results.split(",")]
    quick_dir = tempfile.TemporaryDirectory() if a.quick else None
    path = Path(quick_dir.name) / "quick.json" if a.quick else files[0]
    path.parent.mkdir(parents=True, exist_ok=True)
    store = results_store.load(path.stem, path.parent)   # {provenance, rungs}, or {}
    res = store.setdefault("rungs", {})
    others = {} if a.quick else {k: v for f in files[1:] for k, v in results_store.load(f.stem, f.parent).get("rungs", {}).items()}
    # rung by rung across the models, coarsest first: a cut run has every model's coarse rungs
    todo = [(i, list(MODELS).index(m), m, h) for m in models for i, h in enumerate(MODELS[m]["hs"][:rungs or None])
            if a.hmin * (1 - 1e-9) <= h <= a.hmax * (1 + 1e-9)]
    run_rungs([(m, h) for _, _, m, h in sorted(todo)], store, others, path, a.tol, a.max_cpu)
    res = store["rungs"] = {**others, **res}
    for m, tol in ladders(res):
        lim = limits(res, m, tol)
        print(m + (f" tol {tol:g}" if tol else "") + ": " + ", ".join(
            f"{SHORT[k]} -> {lim[k][1]:.6g} (p {lim[k][0]:.2f})" if lim[k][1] else f"{SHORT[k]}: no limit" for k in lim))
    if a.doc:
        command = a.command or "bench/indent_convergence_bench.py " + " ".join(argv or sys.argv[1:])
        store["provenance"] = dict(command=command, note=a.note, date=time.strftime("%Y-%m-%d", time.gmtime()))
        results_store.save(path.stem, store, path.parent)
        replace_section(TITLE, section(store))
        print(f"written: {path} (its provenance), docs/performance.md")


if __name__ == "__main__":
    sys.exit(main())
