#!/usr/bin/env python3
"""Time-step error control (issue 10). Part 1: each scene of the paper that the issue names, before (the
UMAT's worst-point control, PROPS tol = 1e-5 as shipped until issue 10, or the triaxial job's 1e-6) and after
(the shipped scene), against a fine reference of the same mesh: the Richardson extrapolation of two runs
with the 'output' measure at tol 5e-3 and 2.5e-3 (first order: ref = 2 x(tol/2) - x(tol); their difference
is the reference's own uncertainty, printed). Part 2: nanoindentation (axisymmetric), each error measure at
three tolerances against the same reference (the output measure also with the load stage's error relative to the
stage, relative_to: stage): the trade of accuracy against cost.

Outputs compared: indentation: the load at the end of loading, the depth there, the creep depth over the
hold and the residual depth after unloading; triaxial creep: the axial creep strain 1 h and 10 h into the
creep stage. One rank (the triaxial main job: 2 ranks, as tools/run.sh runs it); fields off in every run
(fields_every 0 and no output times), so the times are the solver's. Wall times: medians of --repeats runs
of the shipped scenes, single runs otherwise; the machine is shared, so each row also gives the CPU time.

Keeps every number its tables print in the results store docs/results/step_control.json (camclay9.step_control_study;
full digits, with command, date and machine note) and writes from it the section "## Time-step error control" of
docs/performance.md (--part 3d: "## Time-step error control: 3D Berkovich half model") and docs/step_control.png,
which tools/doc_numbers.py checks. The figures the sections' hand-written text quotes from earlier runs stay in the
store's part as they stood (each with its note).
Usage: bench/step_control_bench.py [--repeats 3] [--scenes nano,micro,rate,bedding,triaxial] [--no-table] [--no-before]
       [--part axi|3d] [--machine NOTE] [--no-doc]
"""
import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from camclay9 import DriverError, read_history, results_store, run_driver, summary_line
from camclay9 import step_control_study as study
from camclay9.performance_doc import publish
from matplotlib.figure import Figure

ROOT = Path(__file__).resolve().parents[1]
BEFORE_COMMIT = "9e981b2"  # the scenes as shipped before issue 10
SCENES = {"nano": "nanoindent_kerogen_axi", "micro": "microindent_BN_axi", "rate": "loading_rate_a1",
          "bedding": "bedding_theta45", "triaxial": "triaxial", "nano3d": "nanoindent_kerogen",
          "micro3d": "microindent_BN", "bp3d": "microindent_BP"}
STEPS = re.compile(r"steps: \{adaptive: true, first: ([^,]+), min: ([^,]+), max: ([^,}]+)(, error: \{[^}]*\})?\}")


def absolute(text):
    """A shipped scene's text for a time-step study: absolute mesh paths, no fields, and one mesh for every control (a
    scene that adapts its mesh, mesh.adapt, runs on its first mesh: a rerun's mesh would follow each control's answer)."""
    for old in ("geometry: ../meshes/", "geometry: meshes/"):
        text = text.replace(old, f"geometry: {ROOT}/meshes/")
    text = re.sub(r"\n  adapt: \{[^}]*\}[^\n]*", "", text)
    text = re.sub(r"fields_every: \d+", "fields_every: 0", text)
    return re.sub(r"\n\s+output: \{times: \[[^]]*\]\}[^\n]*", "", text)


def shipped(name):
    return absolute((ROOT / "input" / f"{name}.yaml").read_text())


def before(name):
    return absolute(subprocess.run(["git", "show", f"{BEFORE_COMMIT}:input/{name}.yaml"], cwd=ROOT, capture_output=True,
                                   text=True, check=True, timeout=60).stdout)


STAGE = study.LOAD_PER_STAGE   # relative_to: stage on the load stage (docs/driver.md, Error measures)


def with_measure(text, measure, tol, unload_tol=None):
    """Every adaptive stage with this measure and tol (the unload stage: unload_tol if given); STAGE: the output
    measure, the load stage's relative to the stage."""
    out, stage = [], None
    for line in text.split("\n"):
        m = re.match(r"\s+- name: (\w+)", line)
        if m:
            stage = m.group(1)
        t = unload_tol if (stage == "unload" and unload_tol) else tol
        how = ("output, tol: {}" + (", relative_to: stage" if stage == "load" else "")) if measure == STAGE else measure + ", tol: {}"
        line = STEPS.sub(lambda m: f"steps: {{adaptive: true, first: {m.group(1)}, min: {m.group(2)}, max: {m.group(3)}, "
                                   f"error: {{measure: {how.format(t)}}}}}", line)
        out.append(line)
    return "\n".join(out)


def output_tol(text, tol):
    """The shipped indentation scene with the output measure's tol 1.5e-2 of its load and hold stages set to tol (the
    load's relative_to and the unload's tol kept)."""
    old = "measure: output, tol: 1.5e-2"
    assert text.count(old) == 2, "expected the load and hold stages at the output measure's tol 1.5e-2"
    return text.replace(old, f"measure: output, tol: {tol:g}")


def run(text, out, ranks=1, args=()):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    try:
        proc = run_driver(scene, out, args, root=ROOT, ranks=ranks, cwd=out.parent, timeout=6 * 3600)
    except DriverError as err:
        raise SystemExit(f"{scene}: the driver failed: {err}")
    s = summary_line(proc.stdout, index=0)
    return dict(wall=proc.wall, cpu=proc.cpu, steps=s["steps"], newton=s["newton_iterations"], calls=s["umat_calls"],
                hist=read_history(out))


def outputs(h):
    """The numbers a scene reports (see the module's docstring)."""
    if "depth" not in h.dtype.names:  # triaxial: axial creep strain 1 h and 10 h into the creep stage
        start = h[h["stage"] == 0][-1]
        creep = h[h["stage"] == 1]
        return {f"creep {T // 3600} h": np.interp(start["time"] + T, creep["time"], creep["eps_33"]) - start["eps_33"]
                for T in (3600, 36000)}
    load, hold = h[h["stage_name"] == "load"], h[h["stage_name"] == "hold"]
    o = {"load at end of loading": load["load"][-1], "depth at end of loading": load["depth"][-1],
         "creep depth": hold["depth"][-1] - load["depth"][-1]}
    if "unload" in set(h["stage_name"]):
        o["residual depth"] = h["depth"][-1]
    return o


def reference(text, tmp, tag, ranks=1, triaxial=False):
    """Richardson from two 'output' runs at tol 5e-3 and 2.5e-3 (first order), and the uncertainty."""
    runs = []
    for tol in (5e-3, 2.5e-3):
        t = with_measure(text, "output", tol) if not triaxial else text.replace("tol: 1.0e-6", "tol: 1.0e-8")
        runs.append(run(t, tmp / f"{tag}_ref{tol:g}", ranks))
        if triaxial:
            break
    if triaxial:
        return outputs(runs[0]["hist"]), {k: 0.0 for k in outputs(runs[0]["hist"])}, runs
    a, b = outputs(runs[0]["hist"]), outputs(runs[1]["hist"])
    ref = {k: 2 * b[k] - a[k] for k in a}
    return ref, {k: abs(b[k] / ref[k] - 1) for k in a}, runs


def errors(o, ref):
    return {k: o[k] / ref[k] - 1 for k in ref}


def median_run(text, tmp, tag, repeats, ranks=1):
    runs = [run(text, tmp / f"{tag}_{r}", ranks) for r in range(repeats)]
    r = runs[0]
    r["wall"] = float(np.median([x["wall"] for x in runs]))
    r["cpu"] = float(np.median([x["cpu"] for x in runs]))
    return r


def same_mesh(a, b):
    """Whether two scenes' texts give the same mesh (its geometry, parameters and element order)."""
    mesh = re.compile(r"^\s*(?:geometry|parameters|order):.*$", re.M)
    return mesh.findall(a) == mesh.findall(b)


def scene_runs(key, tmp, repeats, no_before):
    """Part 1, one scene: its reference, then its runs before and shipped (camclay9.step_control_study's scene)."""
    name, ranks = SCENES[key], 2 if key == "triaxial" else 1
    text = shipped(name)
    ref, unc, _ = reference(text, tmp, key, ranks, triaxial=key == "triaxial")
    print(f"{name}: reference {', '.join(f'{k} {v:.6g}' for k, v in ref.items())} (uncertainty {max(unc.values()):.2e})",
          flush=True)
    rows = []
    for label, t, reps in ([] if no_before else [("before", before(name), 1)]) + [("shipped", text, repeats)]:
        r = median_run(t, tmp, f"{key}_{label}", reps, ranks)
        rows.append({"variant": label, "steps": r["steps"], "newton": r["newton"], "calls": r["calls"], "wall_s": r["wall"],
                     "cpu_s": r["cpu"], "errors": errors(outputs(r["hist"]), ref)})
        print(f"  {study.scene_lines({'name': name, 'rows': rows[-1:], 'uncertainty': unc})[0]}", flush=True)
    return {"name": name, "reference": ref, "uncertainty": unc, "rows": rows,
            "before_mesh_differs": not no_before and not same_mesh(before(name), text)}


def table_row(r, ref, **what):
    return {**what, "steps": r["steps"], "newton": r["newton"], "wall_s": r["wall"], "cpu_s": r["cpu"],
            "errors": errors(outputs(r["hist"]), ref)}


def part2(tmp):
    """Nanoindentation (axisymmetric): each measure at three tolerances, then Newton's stopping rule: the shipped one
    (stop at 1 % of the step tolerance, docs/driver.md) against the residual test alone (1e-10 of the load)."""
    text = shipped("nanoindent_kerogen_axi")
    ref, unc, _ = reference(text, tmp, "table")
    rows = []
    for measure, tols in (("worst_point", (3e-5, 1e-5, 3e-6)), ("volume", (0.2, 0.1, 0.05)), ("output", (6e-2, 3e-2, 1.5e-2)),
                          (STAGE, (3e-2, 1.5e-2, 7.5e-3))):
        for tol in tols:
            t = with_measure(text, measure, tol, None if measure == "worst_point" else 0.1)
            rows.append(table_row(run(t, tmp / f"table_{measure}_{tol:g}"), ref, measure=measure, tol=tol, newton_rule=None))
            print(f"  {study.table_lines({'rows': rows[-1:]})[-1]}", flush=True)
    for label, args in (("Newton stopped at 1 % of tol (shipped)", ()),
                        ("Newton to a residual of 1e-10 of the load", ("-indent_newton_estimate", "0"))):
        r = run(with_measure(text, "output", 1.5e-2, 0.1), tmp / f"table_newton{len(args)}", args=args)   # as labelled
        rows.append(table_row(r, ref, measure="output", tol=1.5e-2, newton_rule=label))
        print(f"  {study.table_lines({'rows': rows[-1:]})[-1]}", flush=True)
    return {"reference": ref, "uncertainty": unc, "rows": rows}


def plot(table):
    """docs/step_control.png: the largest error of each measure's runs against their CPU time, from the store's table."""
    fig = Figure(figsize=(6, 4))
    ax = fig.subplots()
    for measure, marker in (("worst_point", "s"), ("volume", "^"), ("output", "o"), (STAGE, "D")):
        pts = [(r["cpu_s"], max(abs(v) for v in r["errors"].values())) for r in table["rows"]
               if r["measure"] == measure and not r["newton_rule"]]
        ax.loglog([p[0] for p in pts], [max(p[1], 1e-5) for p in pts], marker + "-", label=measure)
    ax.set_xlabel("CPU time [s]")
    ax.set_ylabel("largest relative error of the outputs")
    ax.set_title("Nanoindentation (axisymmetric): accuracy against cost")
    ax.legend()
    fig.tight_layout()
    fig.savefig(ROOT / "docs" / "step_control.png", dpi=100)


def kept_note(old):
    pv = old.get("provenance", {})
    return {"note": f"from the run of {pv.get('date')} (`{pv.get('command')}`), kept in the store"}


def kept_scenes(old):
    """{name: scene} of the store's part as it stood, each with its own provenance (that run's, unless it has one):
    the scenes not run now keep their rows."""
    return {s["name"]: {**s, "provenance": s.get("provenance") or kept_note(old)} for s in old.get("scenes", [])}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scenes", default="nano,micro,rate,bedding,triaxial",
                    help="run these; the part's other scenes keep their rows from the store (default: %(default)s)")
    ap.add_argument("--no-table", action="store_true", help="skip part 2 (the store's table, if any, is kept)")
    ap.add_argument("--no-before", action="store_true", help="skip the 'before' runs (the 3D ones take 10 min each)")
    ap.add_argument("--part", choices=sorted(study.TITLES), default="axi",
                    help="the store's part and section to write (3d: the 3D half models' section)")
    ap.add_argument("--machine", default="a shared 2-core machine",
                    help="the machine note the store and the section carry (default: %(default)s)")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        done = {SCENES[k]: scene_runs(k, tmp, a.repeats, a.no_before) for k in a.scenes.split(",") if k}
        table = None if a.no_table else part2(tmp)
    store = results_store.load(study.STORE) or {"parts": {}}
    old = store["parts"].get(a.part, {})
    kept = kept_scenes(old)
    scenes = [done.get(n) or kept[n] for n in SCENES.values() if n in done or n in kept]
    if table is None and old.get("table"):   # --no-table: the part's table kept, with its run's provenance
        table = {**old["table"], "provenance": old["table"].get("provenance") or kept_note(old)}
    command = (f"bench/step_control_bench.py --repeats {a.repeats} --scenes {a.scenes or repr('')}{' --no-table' if a.no_table else ''}"
               f"{' --no-before' if a.no_before else ''}{' --part ' + a.part if a.part != 'axi' else ''}")
    part = {"provenance": {"command": command, "date": time.strftime("%Y-%m-%d", time.gmtime()), "machine": a.machine},
            "scenes": scenes, "table": table}
    part.update({k: v for k, v in old.items() if k not in part})   # the earlier runs' figures the text quotes
    store["parts"][a.part] = part
    publish(study.TITLES[a.part], study.section(store, part=a.part), study.STORE, store, write=not a.no_doc)
    if not a.no_table and not a.no_doc:   # the plot of this run's table (a kept one's stands)
        plot(table)
        print("written: docs/step_control.png")


if __name__ == "__main__":
    sys.exit(main())
