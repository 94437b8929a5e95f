#!/usr/bin/env python3
"""Time-step error control (issue 10). Part 1: each scene of the paper that the issue names, before (the
UMAT's worst-point control, PROPS tol = 1e-5 as shipped until issue 10, or the triaxial job's 1e-6) and after
(the shipped scene), against a fine reference of the same mesh: the Richardson extrapolation of two runs
with the 'output' measure at tol 5e-3 and 2.5e-3 (first order: ref = 2 x(tol/2) - x(tol); their difference
is the reference's own uncertainty, printed). Part 2: nanoindentation (axisymmetric), each error measure at
three tolerances against the same reference: the trade of accuracy against cost.

Outputs compared: indentation: the load at the end of loading, the depth there, the creep depth over the
hold and the residual depth after unloading; triaxial creep: the axial creep strain 1 h and 10 h into the
creep stage. One rank (the triaxial main job: 2 ranks, as tools/run.sh runs it); fields off in every run
(fields_every 0 and no output times), so the times are the solver's. Wall times: medians of --repeats runs
of the shipped scenes, single runs otherwise; the machine is shared, so each row also gives the CPU time.

Writes the section "## Time-step error control" of docs/performance.md and docs/step_control.png.
Usage: bench/step_control_bench.py [--repeats 3] [--scenes nano,micro,rate,bedding,triaxial] [--no-table]
"""
import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import DriverError, read_history, run_driver, summary_line
from matplotlib.figure import Figure
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
TITLE = "## Time-step error control"
BEFORE_COMMIT = "9e981b2"  # the scenes as shipped before issue 10
SCENES = {"nano": "nanoindent_kerogen_axi", "micro": "microindent_BN_axi", "rate": "loading_rate_a1",
          "bedding": "bedding_theta45", "triaxial": "triaxial", "nano3d": "nanoindent_kerogen",
          "micro3d": "microindent_BN", "bp3d": "microindent_BP"}
STEPS = re.compile(r"steps: \{adaptive: true, first: ([^,]+), min: ([^,]+), max: ([^,}]+)(, error: \{[^}]*\})?\}")


def absolute(text):
    text = text.replace("geometry: ../meshes/", f"geometry: {ROOT}/meshes/").replace("geometry: meshes/", f"geometry: {ROOT}/meshes/")
    text = re.sub(r"fields_every: \d+", "fields_every: 0", text)
    return re.sub(r"\n\s+output: \{times: \[[^]]*\]\}[^\n]*", "", text)


def shipped(name):
    return absolute((ROOT / "input" / f"{name}.yaml").read_text())


def before(name):
    return absolute(subprocess.run(["git", "show", f"{BEFORE_COMMIT}:input/{name}.yaml"], cwd=ROOT, capture_output=True,
                                   text=True, check=True).stdout)


def with_measure(text, measure, tol, unload_tol=None):
    """Every adaptive stage with this measure and tol (the unload stage: unload_tol if given)."""
    out, stage = [], None
    for line in text.split("\n"):
        m = re.match(r"\s+- name: (\w+)", line)
        if m:
            stage = m.group(1)
        t = unload_tol if (stage == "unload" and unload_tol) else tol
        line = STEPS.sub(lambda m: f"steps: {{adaptive: true, first: {m.group(1)}, min: {m.group(2)}, max: {m.group(3)}, "
                                   f"error: {{measure: {measure}, tol: {t}}}}}", line)
        out.append(line)
    return "\n".join(out)


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
    if "stage_name" not in h.dtype.names:  # triaxial: axial creep strain 1 h and 10 h into the creep stage
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


def fmt_err(e):
    return ", ".join(f"{k} {v:+.2%}" for k, v in e.items())


def part1(keys, tmp, repeats, lines, no_before=False):
    lines += ["| scene | variant | steps | Newton its | UMAT calls | wall [s] | CPU [s] | errors against the reference |",
              "|---|---|---|---|---|---|---|---|"]
    for key in keys:
        name, ranks = SCENES[key], 2 if key == "triaxial" else 1
        text = shipped(name)
        ref, unc, _ = reference(text if key != "triaxial" else text, tmp, key, ranks, triaxial=key == "triaxial")
        print(f"{name}: reference {', '.join(f'{k} {v:.6g}' for k, v in ref.items())} (uncertainty {max(unc.values()):.2e})", flush=True)
        rows = ([] if no_before else [("before", before(name), 1)]) + [("shipped", text, repeats)]
        for label, t, reps in rows:
            r = median_run(t, tmp, f"{key}_{label}", reps, ranks)
            e = errors(outputs(r["hist"]), ref)
            print(f"  {label}: {r['steps']} steps, {r['newton']} Newton, {r['calls']} UMAT calls, wall {r['wall']:.1f} s, "
                  f"CPU {r['cpu']:.1f} s; {fmt_err(e)}", flush=True)
            lines.append(f"| {name} | {label} | {r['steps']} | {r['newton']} | {r['calls']:,} | {r['wall']:.1f} | {r['cpu']:.1f} | {fmt_err(e)} |")
        lines.append(f"| {name} | reference (uncertainty) | | | | | | {max(unc.values()):.2e} |")


def part2(tmp, lines, plot):
    text = shipped("nanoindent_kerogen_axi")
    ref, unc, _ = reference(text, tmp, "table")
    lines += ["", "Nanoindentation (axisymmetric), each measure at three tolerances (unload stage: output 0.1 for the relative",
              "measures), same reference:", "",
              "| measure | tol | steps | Newton its | wall [s] | CPU [s] | load at end of loading | creep depth | residual depth |",
              "|---|---|---|---|---|---|---|---|---|"]
    for measure, tols in (("worst_point", (3e-5, 1e-5, 3e-6)), ("volume", (0.2, 0.1, 0.05)), ("output", (6e-2, 3e-2, 1.5e-2))):
        for tol in tols:
            t = with_measure(text, measure, tol, None if measure == "worst_point" else 0.1)
            r = run(t, tmp / f"table_{measure}_{tol:g}")
            e = errors(outputs(r["hist"]), ref)
            print(f"  {measure} {tol:g}: {r['steps']} steps, wall {r['wall']:.1f} s; {fmt_err(e)}", flush=True)
            lines.append(f"| {measure} | {tol:g} | {r['steps']} | {r['newton']} | {r['wall']:.1f} | {r['cpu']:.1f} | "
                         f"{e['load at end of loading']:+.2%} | {e['creep depth']:+.2%} | {e['residual depth']:+.2%} |")
            plot.append((measure, tol, r["cpu"], max(abs(v) for v in e.values())))
    # Newton's stopping rule: the shipped one (stop at 1 % of the step tolerance, docs/driver.md) against the
    # residual test alone (1e-10 of the load): the iterations saved, and the outputs to four digits
    for label, args in (("Newton stopped at 1 % of tol (shipped)", ()),
                        ("Newton to a residual of 1e-10 of the load", ("-indent_newton_estimate", "0"))):
        r = run(text, tmp / f"table_newton{len(args)}", args=args)
        e = errors(outputs(r["hist"]), ref)
        print(f"  shipped, {label}: {r['steps']} steps, {r['newton']} Newton, wall {r['wall']:.1f} s; {fmt_err(e)}", flush=True)
        lines.append(f"| output, {label} | 1.5e-2 | {r['steps']} | {r['newton']} | {r['wall']:.1f} | "
                     f"{r['cpu']:.1f} | {e['load at end of loading']:+.4%} | {e['creep depth']:+.4%} | {e['residual depth']:+.4%} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--scenes", default="nano,micro,rate,bedding,triaxial")
    ap.add_argument("--no-table", action="store_true", help="skip part 2")
    ap.add_argument("--no-before", action="store_true", help="skip the 'before' runs (the 3D ones take 10 min each)")
    ap.add_argument("--title", default=TITLE, help="the section of docs/performance.md to write (e.g. for the 3D scenes)")
    a = ap.parse_args(argv)
    lines, plot = [], []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        part1([k for k in a.scenes.split(",") if k], tmp, a.repeats, lines, a.no_before)
        if not a.no_table:
            part2(tmp, lines, plot)
    section = (f"{a.title}\n\nCommand: `bench/step_control_bench.py --repeats {a.repeats} --scenes {a.scenes}"
               f"{' --no-table' if a.no_table else ''}{' --no-before' if a.no_before else ''}{' --title ...' if a.title != TITLE else ''}`. "
               "Before: the scene as shipped until\nissue 10 (the UMAT's worst-point control, PROPS tol). Shipped: the "
               "scene now (`steps.error`, docs/driver.md). The\nreference: the same mesh with the output measure at "
               "tol 5e-3 and 2.5e-3, extrapolated (first order); its\nuncertainty is the relative difference of the "
               "finer run from it. Fields off; one rank (triaxial: 2). Wall:\nmedian of the repeats for shipped rows; CPU: "
               "user + system of the driver processes.\n\n" + "\n".join(lines) + "\n")
    if plot:
        section += "\n![error against CPU time](step_control.png)\n"
        fig = Figure(figsize=(6, 4))
        ax = fig.subplots()
        for measure, marker in (("worst_point", "s"), ("volume", "^"), ("output", "o")):
            pts = [(c, e) for m, t, c, e in plot if m == measure]
            ax.loglog([p[0] for p in pts], [max(p[1], 1e-5) for p in pts], marker + "-", label=measure)
        ax.set_xlabel("CPU time [s]")
        ax.set_ylabel("largest relative error of the outputs")
        ax.set_title("Nanoindentation (axisymmetric): accuracy against cost")
        ax.legend()
        fig.tight_layout()
        fig.savefig(ROOT / "docs" / "step_control.png", dpi=100)
    replace_section(a.title, section)
    print("written: docs/performance.md" + (", docs/step_control.png" if plot else ""))


if __name__ == "__main__":
    sys.exit(main())
