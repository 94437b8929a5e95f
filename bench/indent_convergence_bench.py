"""
Mesh convergence of the Cam-Clay nanoindentation on kerogen (issue 12, items 3-4): how converged are the 3D
answers, and which model and element order reaches <= 2 % of the converged 3D answer at the least CPU time.

The scene is input/nanoindent_kerogen*.yaml as shipped (Cam-Clay IX, phi = 0; P = P0 exp(k t) up to 200 nm, hold
60 s, unload in 20 s; the shipped adaptive time-step settings, output measure tol 1.5e-2), on ladders of h_tip (ratio about sqrt 2, 0.12 between 0.1414 and 0.1: the shipped mesh):
  sector2  the 60-degree sector (meshes/indent_sector.geo), P2;
  sector2f8  the same with h_far = 8 h_tip: the shipped scene at h_tip 0.1;
  sector1  the same, P1;
  half2    the half model (meshes/indent_cube.geo), P2: an independent mesh of the sector's density;
  old1     the sector on P1 with the mesh family of the scenes before (r_fine 0.4 um, which leaves the contact's
           rim, at 0.56-0.87 um, in the graded zone): the shipped scene up to 2026-11-23 at h_tip 0.05;
  axi1/2   the axisymmetric twin (cone of equal area, meshes/indent_block2d.geo), P1 and P2.
The mesh family (3D): h_tip within r_fine = 0.9 um of the tip, which covers the whole contact at 200 nm (the
Berkovich's corners reach 2 h tan 65.27 = 0.87 um), growing to h_far = 4 h_tip (P2) or 8 h_tip (P1: the same
node spacing); axisymmetric: r_fine as shipped, h_far = 7.5 h_tip. Fields off, one rank. Reported: the
indenter's whole load at the end of loading (the scenes say indenter.copies, so the history holds it), the
depth there, the creep depth over the hold, the residual depth after unloading, steps, CPU time (user + system
of the driver: the machine is shared, 2 cores), unknowns. Richardson estimates from the last three rungs of each
ladder where they are monotone: observed order p and limit x_inf = x3 + (x3 - x2) / (r^p - 1).

Results go to a JSON file as they come (--results, default out/indent_convergence.json; rerunning skips the rungs
already there), so a long ladder can be cut and resumed; --doc writes the section "## 3D indentation: mesh
convergence and the cheapest model" of docs/performance.md from that file, followed by the reading of the tables
written by hand in bench/indent_convergence_conclusions.md (its numbers are those of the run in the section).

Usage: bench/indent_convergence_bench.py [--models sector2,sector2f8,sector1,half2,old1,axi1,axi2] [--rungs N] [--quick] [--doc]
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from performance_doc import replace_section  # noqa: E402
from step_control_bench import absolute, outputs  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DRIVER = Path(os.environ.get("DRIVER", ROOT / "build" / "bin" / "driver"))
CONCLUSIONS = ROOT / "bench" / "indent_convergence_conclusions.md"  # the section's reading, written by hand
TITLE = "## 3D indentation: mesh convergence and the cheapest model"
R2 = math.sqrt(2)
KEYS = ("load at end of loading", "depth at end of loading", "creep depth", "residual depth")
SHORT = {"load at end of loading": "P", "depth at end of loading": "h_max", "creep depth": "creep",
         "residual depth": "h_res"}
NOISY = {"sector2"}  # ladders whose finest rungs scatter without a trend (the reading says why)
SHIPPED = ("sector2f8", 0.1, None)  # input/nanoindent_kerogen_sector.yaml: (model, h_tip, tol)
# model: (label, scene, order, far-field ratio, r_fine (None: as shipped), ladder of h_tip)
MODELS = {
    "sector2": ("60° sector, P2", "nanoindent_kerogen_sector", 2, 4, 0.9, [0.2, 0.1414, 0.12, 0.1, 0.07071, 0.05]),
    "sector1": ("60° sector, P1", "nanoindent_kerogen_sector", 1, 8, 0.9, [0.1, 0.07071, 0.05, 0.03536]),
    "sector2f8": ("60° sector, P2, h_far 8 h_tip", "nanoindent_kerogen_sector", 2, 8, 0.9, [0.12, 0.1]),
    "half2": ("half model (cube), P2", "nanoindent_kerogen", 2, 4, 0.9, [0.12]),
    "old1": ("60° sector, P1, r_fine 0.4 (the scenes before)", "nanoindent_kerogen_sector", 1, 8, 0.4, [0.1, 0.07071, 0.05]),
    "axi1": ("axisymmetric cone, P1", "nanoindent_kerogen_axi", 1, 7.5, None,
             [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01, 0.01 / R2, 0.005]),
    "axi2": ("axisymmetric cone, P2", "nanoindent_kerogen_axi", 2, 7.5, None, [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01]),
}


def scene(model, h_tip, tol=None):
    _, name, order, far, r_fine, _ = MODELS[model]
    t = absolute((ROOT / "input" / f"{name}.yaml").read_text())
    if tol:  # the load and hold stages' output tolerance (shipped: 1.5e-2; the unload stage's 0.1 kept)
        t = t.replace("measure: output, tol: 1.5e-2}", f"measure: output, tol: {tol:g}}}")
    t = re.sub(r"h_tip: [0-9.e-]+", f"h_tip: {h_tip:.6g}", t, count=1)
    t = re.sub(r"h_far: [0-9.e-]+", f"h_far: {far * h_tip:.6g}", t, count=1)
    if r_fine:
        t = re.sub(r"r_fine: [0-9.e-]+", f"r_fine: {r_fine:g}", t, count=1)
    t = re.sub(r"\n  order: \d+", "", t, count=1)
    return re.sub(r"(\n  kinematics: \w+)", rf"\1\n  order: {order}", t, count=1)


def run(text, out):
    out.parent.mkdir(parents=True, exist_ok=True)
    path = out.parent / (out.name + ".yaml")
    path.write_text(text)
    t0, c0 = time.perf_counter(), os.times()
    proc = subprocess.run([str(DRIVER), "-input", str(path), "-output_dir", str(out)], capture_output=True, text=True,
                          cwd=out.parent)
    wall, c1 = time.perf_counter() - t0, os.times()
    if proc.returncode:
        raise RuntimeError(f"{path}: the driver failed:\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}")
    steps = re.search(r": (\d+) steps, (\d+) Newton iterations", proc.stdout)
    n = re.search(r"(\d+) unknowns", proc.stdout)
    h = np.atleast_1d(np.genfromtxt(out / "history.csv", delimiter=",", names=True, dtype=None, encoding="utf-8"))
    return dict(wall=wall, cpu=(c1.children_user - c0.children_user) + (c1.children_system - c0.children_system),
                steps=int(steps.group(1)), newton=int(steps.group(2)), unknowns=int(n.group(1)) if n else None,
                o={k: float(v) for k, v in outputs(h).items()})


def richardson(hs, xs):
    """The last three rungs (constant ratio): observed order and limit; None where not monotone or contracting."""
    if len(xs) < 3:
        return None, None
    (h1, h2, _), (x1, x2, x3) = hs[-3:], xs[-3:]
    r = h1 / h2
    d1, d2 = x1 - x2, x2 - x3
    if d1 * d2 <= 0 or abs(d2) >= abs(d1):
        return None, None
    p = math.log(d1 / d2) / math.log(r)
    if not 0.5 <= p <= 4:  # erratic: the rungs' differences are the time step's or the contact's noise
        return p, None
    return p, x3 + (x3 - x2) / (r ** p - 1)


def bracket(hs, xs):
    """The limits that the last two rungs give if the order is 1 and if it is 2 (a band for erratic ladders)."""
    if len(xs) < 2:
        return None
    r = hs[-2] / hs[-1]
    lims = [xs[-1] + (xs[-1] - xs[-2]) / (r ** p - 1) for p in (1, 2)]
    return min(lims), max(lims)


def load(path):
    return json.loads(path.read_text()) if path.exists() else {}


def key(model, h, tol=None):
    return f"{model}{'@' + format(tol, 'g') if tol else ''}:{h:.6g}"


def ladder(res, model, tol=None):
    rows = sorted((r for r in res.values() if r["model"] == model and r.get("tol") == tol and "failed" not in r),
                  key=lambda r: -r["h_tip"])
    return rows


def ladders(res):
    """(model, tol) of every ladder in res, in MODELS' order, the shipped tolerance first."""
    return sorted({(r["model"], r.get("tol")) for r in res.values() if "failed" not in r}, key=lambda mt: (list(MODELS).index(mt[0]), mt[1] is not None, mt[1] or 0))


def limits(res, model, tol=None):
    rows = ladder(res, model, tol)
    hs = [r["h_tip"] for r in rows]
    return {k: richardson(hs, [r["o"][k] for r in rows]) for k in KEYS}


def fmt(k, v):
    return f"{v:.2f}" if k == "load at end of loading" else f"{v * 1e3:.2f}"


def section(res, command, note, ref_model="two"):
    lines = [TITLE, "",
             f"Command: `{command}` ({time.strftime('%Y-%m-%d', time.gmtime())}; {note}).",
             "`bench/indent_convergence_bench.py` (issue 12, items 3-4): the nanoindentation on kerogen (Cam-Clay IX, φ = 0;",
             "exponential load to 200 nm, hold 60 s, unload in 20 s; the shipped time-step settings, output measure tol",
             "1.5e-2) on ladders of h_tip at ratio about √2. 3D: h_tip within r_fine = 0.9 µm of the tip (the whole contact at",
             "200 nm: the Berkovich's corners reach 0.87 µm), h_far = 4 h_tip (P2) or 8 h_tip (P1), r_contact 0.95 µm; 'r_fine",
             "0.4' is the family of the scenes before (the contact's rim in the graded zone). Axisymmetric: r_fine 0.4, h_far",
             "7.5 h_tip. Fields off, one rank, one run per rung. P: the indenter's whole",
             "load at h = 200 nm [µN]; creep: depth gained over the hold [nm]; h_res: residual depth [nm]. In brackets:",
             "the error against the Richardson limit of the model's own ladder (last three rungs). CPU: user + system of",
             "the driver [s], on a shared, loaded machine (2 cores, other users' jobs running): the wall time is not",
             "comparable, the CPU time roughly.", ""]
    for model, tol in ladders(res):
        label = MODELS[model][0] + (f", time steps at tol {tol:g}" if tol else "")
        rows = ladder(res, model, tol)
        lim = limits(res, model, tol)
        lines += [f"**{label}**", "", "| h_tip [µm] | unknowns | P [µN] | creep [nm] | h_res [nm] | steps | CPU [s] |",
                  "|---|---|---|---|---|---|---|"]
        for r in rows:
            cells = []
            for k in ("load at end of loading", "creep depth", "residual depth"):
                p, x = lim[k]
                cells.append(fmt(k, r["o"][k]) + (f" ({r['o'][k] / x - 1:+.1%})" if x and model not in NOISY else ""))
            lines.append(f"| {r['h_tip']:.4g} | {r['unknowns']} | {' | '.join(cells)} | {r['steps']} | {r['cpu']:.0f} |")
        lim_cells, band = [], []
        for k in ("load at end of loading", "creep depth", "residual depth"):
            p, x = lim[k]
            lim_cells.append(f"{fmt(k, x)} (p = {p:.2f})" if x else f"erratic (p = {p:.2f})" if p else "not monotone")
            b = bracket([r["h_tip"] for r in rows], [r["o"][k] for r in rows])
            band.append(f"{fmt(k, b[0])} – {fmt(k, b[1])}" if b else "")
        if len(rows) >= 3 and model in NOISY:  # no trend left: the scatter of the finest rungs, not an extrapolation
            cells = []
            for k in ("load at end of loading", "creep depth", "residual depth"):
                xs = [r["o"][k] for r in rows[-3:]]
                cells.append(f"{fmt(k, sum(xs) / 3)} ± {fmt(k, (max(xs) - min(xs)) / 2)}")
            lines += [f"| finest three: mean ± half-range | | {' | '.join(cells)} | | |"]
        elif len(rows) >= 3:
            lines += [f"| Richardson limit | | {' | '.join(lim_cells)} | | |",
                      f"| limit if p = 1 … 2 (last two rungs) | | {' | '.join(band)} | | |"]
        lines += [""]
    if ref_model == "two":
        ref, hw = reference_two(res)
        what = (f"the middle of the sector P2 ladder's finest three rungs (their mean) and the sector P1 ladder's "
                f"Richardson limit; ± {hw['load at end of loading']:.1%} in P, {hw['creep depth']:.1%} in creep, "
                f"{hw['residual depth']:.1%} in h_res" if ref else "")
    else:
        ref = reference(res, ref_model)
        what = (f"the {MODELS[ref_model][0]} ladder's limits, Richardson where its order is 0.5–4, else the middle of "
                f"the p = 1 … 2 band")
    if ref:
        out3 = ("load at end of loading", "creep depth", "residual depth")
        lines += [f"**Every rung against the converged 3D answer** ({what}: P = "
                  f"{ref['load at end of loading']:.1f} µN, creep = {ref['creep depth'] * 1e3:.2f} nm, h_res = "
                  f"{ref['residual depth'] * 1e3:.1f} nm), sorted by CPU time; ✓: all three within 2 %", "",
                  "| model | h_tip | unknowns | CPU [s] | P | creep | h_res | ≤ 2 % |", "|---|---|---|---|---|---|---|---|"]
        for r in sorted((r for r in res.values() if "failed" not in r), key=lambda r: r["cpu"]):
            e = [r["o"][k] / ref[k] - 1 for k in out3]
            label = MODELS[r["model"]][0] + (f", tol {r['tol']:g}" if r.get("tol") else "")
            if (r["model"], r["h_tip"], r.get("tol")) == SHIPPED:
                label = f"**{label}: the shipped scene**"
            lines.append(f"| {label} | {r['h_tip']:.4g} | {r['unknowns']} | {r['cpu']:.0f} | "
                         + " | ".join(f"{x:+.1%}" for x in e) + f" | {'✓' if max(map(abs, e)) <= 0.02 else ''} |")
        lines.append("")
    failed = sorted((r for r in res.values() if "failed" in r), key=lambda r: (r["model"], -r["h_tip"]))
    if failed:
        lines += ["Rungs that did not run: " + "; ".join(f"{MODELS[r['model']][0]} at h_tip {r['h_tip']:.4g} ({r['failed']})"
                                                        for r in failed) + ".", ""]
    if CONCLUSIONS.exists():
        lines += [CONCLUSIONS.read_text()]
    return "\n".join(lines) + "\n"


def reference_two(res, a="sector2", b="sector1", n=3):
    """The converged 3D answer from two ladders. The P2 ladder's finest n rungs lie within their meshes' noise
    of one another (no monotone trend): their mean, ± half their range. The P1 ladder still converges: its
    Richardson limit (last three rungs, order 0.5-4), else the middle of the p = 1 ... 2 band. The answer is the
    middle of the two, ± the larger of half their distance and the P2 rungs' half-range."""
    ra, rb = ladder(res, a), ladder(res, b)
    if len(ra) < n or len(rb) < 2:
        return None, None
    ref, hw = {}, {}
    limb = limits(res, b)
    for k in KEYS:
        xa = [r["o"][k] for r in ra[-n:]]
        ea, wa = sum(xa) / n, (max(xa) - min(xa)) / 2
        band = bracket([r["h_tip"] for r in rb], [r["o"][k] for r in rb])
        eb = limb[k][1] if limb[k][1] is not None else (band[0] + band[1]) / 2
        ref[k] = (ea + eb) / 2
        hw[k] = max(abs(ea - eb) / 2, wa) / abs(ref[k])
    return ref, hw


def reference(res, model="sector1"):
    """The converged 3D answer: the Richardson limits of a ladder at the shipped tolerance (--ref, default the sector
    P1), where its order is plausible (0.5 to 4), else the middle of the band that the last two rungs give for
    orders 1 to 2."""
    rows = ladder(res, model)
    if len(rows) < 2:
        return None
    lim, ref = limits(res, model), {}
    for k in ("load at end of loading", "creep depth", "residual depth"):
        b = bracket([r["h_tip"] for r in rows], [r["o"][k] for r in rows])
        ref[k] = lim[k][1] if lim[k][1] is not None else (b[0] + b[1]) / 2
    return ref


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--models", default="sector2,sector1,old1,axi1,axi2", help=f"comma-separated, of {','.join(MODELS)}")
    ap.add_argument("--rungs", type=int, default=0, help="at most this many rungs per ladder (0: all)")
    ap.add_argument("--tol", type=float, default=None, help="the load and hold stages' output tolerance (shipped 1.5e-2)")
    ap.add_argument("--hmin", type=float, default=0, help="only the rungs with h_tip >= this")
    ap.add_argument("--hmax", type=float, default=1e9, help="only the rungs with h_tip <= this")
    ap.add_argument("--quick", action="store_true", help="a 2-rung smoke run of each model (coarsest rungs), no document")
    ap.add_argument("--results", default=str(ROOT / "out" / "indent_convergence.json"),
                    help="JSON file of the results (written); more files after commas are read too (e.g. parallel runs)")
    ap.add_argument("--doc", action="store_true", help="write the section of docs/performance.md from --results")
    ap.add_argument("--command", default=None, help="the command(s) to name in the section (default: this one)")
    ap.add_argument("--ref", default="two", help="the converged 3D answer: a ladder's limits (sector1, ...) or 'two': "
                    "the middle of the sector P2 ladder's finest rungs and the sector P1 ladder's limit")
    ap.add_argument("--note", default="shared machine, 2 cores, loaded", help="machine load, for the section")
    a = ap.parse_args(argv)
    models = [m for m in a.models.split(",") if m]
    rungs = 2 if a.quick else a.rungs
    files = [Path(f) for f in a.results.split(",")]
    quick_dir = tempfile.TemporaryDirectory() if a.quick else None
    path = Path(quick_dir.name) / "quick.json" if a.quick else files[0]
    path.parent.mkdir(parents=True, exist_ok=True)
    res = load(path)
    others = {} if a.quick else {k: v for f in files[1:] for k, v in load(f).items()}
    # rung by rung across the models, coarsest first: a cut run has every model's coarse rungs
    todo = [(i, m, h) for m in models for i, h in enumerate(MODELS[m][5][:rungs or None]) 
            if a.hmin * (1 - 1e-9) <= h <= a.hmax * (1 + 1e-9)]
    with tempfile.TemporaryDirectory() as d:
        for i, m, h in sorted(todo):
            if key(m, h, a.tol) in res or key(m, h, a.tol) in others:
                continue
            try:
                r = run(scene(m, h, a.tol), Path(d) / f"{m}_{i}")
            except RuntimeError as e:
                print(e, flush=True)
                why = [line for line in str(e).splitlines() if line.startswith("driver:")]
                res[key(m, h, a.tol)] = dict(model=m, h_tip=h, tol=a.tol, failed=why[-1] if why else str(e)[-300:])
                path.write_text(json.dumps(res, indent=1))
                continue
            r.update(model=m, h_tip=h, tol=a.tol)
            res[key(m, h, a.tol)] = r
            path.write_text(json.dumps(res, indent=1))
            o = r["o"]
            print(f"{m}{' tol ' + format(a.tol, 'g') if a.tol else ''} h_tip {h:.4g}: {r['unknowns']} unknowns, P {o['load at end of loading']:.3f} uN, h_max "
                  f"{o['depth at end of loading'] * 1e3:.2f} nm, creep {o['creep depth'] * 1e3:.3f} nm, residual "
                  f"{o['residual depth'] * 1e3:.2f} nm, {r['steps']} steps, CPU {r['cpu']:.1f} s, wall {r['wall']:.1f} s",
                  flush=True)
    res = {**others, **res}
    for m, tol in ladders(res):
        lim = limits(res, m, tol)
        print(m + (f" tol {tol:g}" if tol else "") + ": " + ", ".join(f"{SHORT[k]} -> {lim[k][1]:.6g} (p {lim[k][0]:.2f})" if lim[k][1] else
                                   f"{SHORT[k]}: not monotone" for k in KEYS))
    if a.doc:
        command = a.command or "bench/indent_convergence_bench.py " + " ".join(argv or sys.argv[1:])
        replace_section(TITLE, section(res, command, a.note, a.ref))
        print("written: docs/performance.md")


if __name__ == "__main__":
    sys.exit(main())
