#!/usr/bin/env python3
"""Meshes made for the answer (issue 32; docs/adapt.md): each case adapted from a coarse start, every level's
reported quantities against the case's converged answer, the mesh error each level states beside its true error
(the effectivity), cells, unknowns and CPU. --doc writes the cases of --cases into the results store
docs/results/adapt_bench.json and, from it, the section "Adapted meshes" of docs/performance.md (camclay9.adapt_study).

    bench/adapt_bench.py [--cases lr1,sector,axi,sphere,bn] [--levels N] [--results out/adapt_bench.json] [--no-run] [--doc]
                         [--keep-references]

Converged answers (where each comes from):
- lr1: loading_rate_a1 with an unload to zero in 20 s added: the 2D study's P2 ladder to h_tip 0.0071 (docs/performance.md,
  "2D indentation: mesh and element study"): depth at the end of loading 194.91 nm and residual depth 125.64 nm (its finest
  rung, 302 k unknowns), creep depth 35.47 nm (that rung and an independent P2 run at h_tip 0.011 with a wider fine zone
  agree to 0.03 %).
- lr01: loading_rate_a0.1 likewise, against the 2D study's answer for alpha = 0.1 (its P2 ladder to h_tip 0.0071, which
  has not settled: creep depth 15.18 nm, its Richardson limit with p = 0.90, +- 4.3 %; depth at the end of loading
  216.24 nm and residual depth 129.93 nm, the mean of its finest three rungs): errors against it, no effectivity
  ("converged": false), the creep depth's error within that uncertainty.
- sector: nanoindent_kerogen_sector: its own level 5 (about 70 k unknowns; run --levels 5), whose load, creep depth and
  residual depth lie within 0.1 % of level 4's. Until 2026-11-30 it was the uniform P2 sector ladder's converged answer
  (to h_tip 0.0354, 169 692 unknowns: P 537.5 uN, creep depth 15.35 nm, residual depth 137.3 nm), whose creep depth,
  the finest rung ± its last change of 0.2 %, levels 4 and 5 put about 0.4 % low (docs/performance.md, "Adapted meshes").
- axi, sphere: a fine run in the same invocation: the case on P2 with its size field four levels finer than the last adapted
  level of P1 ("reference" rows), i.e. another element order on its own meshes. sphere_coarse: the sphere from a coarse
  first mesh (h_tip 0.1 um, h_far 0.3 um), against the sphere's reference (run the sphere first).
- sector_p1: the same sector on P1 elements from the same coarse start, against the sector's level 5.
- bed0, bed30, bed45, bed60, bed90: bedding_theta*.yaml (Fig. 14) from the first mesh they ship, against their own
  level 3 (run --levels 3). At 45 degrees the 2D study's P2 ladder converges the creep depth to 800.2 nm +- 0.6 %
  (Richardson, p 0.85; docs/performance.md, "2D indentation: mesh and element study"), an independent check.
- bn, bp: microindent_BN_sector and microindent_BP: no 3D answer is known (no reference run: their rows give the levels'
  own changes); BN's axisymmetric twin converges to a residual depth of 2.112 um (docs/performance.md, the 3D mesh
  study), which BN's 3D value should approach.
- sector_fixed, bn_fixed: sector and bn on the fixed steps of the contact solver's uniform ladder (its
  contact_solver_study.FIXED_STEPS, Newton to 1e-6 of the load), against that ladder's finest rung on the same steps:
  uniform P2 at 1.03 M unknowns, the field split on 2 ranks (docs/results/contact_solver.json, rows fix0.019 and
  bnfix0.475 with the forcing term). The steps' error is the same in both, so the difference is the meshes' alone: the
  adapted levels against a uniform mesh of 13 to 600 times their unknowns (issue 33's cross-check of the two). That rung
  is not a converged answer (BN's residual depth still rises on the uniform rungs): errors against it, no effectivity.
"""
import argparse
import json
import time
from pathlib import Path
from typing import NamedTuple

import yaml
from camclay9 import read_summary, results_store, run_driver
from camclay9.contact_solver_study import FIXED_RTOL, FIXED_STEPS, FORCING
from camclay9.contact_solver_study import STORE as LADDER
from camclay9.adapt_study import STORE, TITLE, section
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]

UNLOAD = """  - name: unload
    duration: 20
    indenter: {load: 0}
    steps: {adaptive: true, first: 1, min: 1.0e-9, max: 1, error: {measure: output, tol: 0.1}}
"""

class LevelOf(NamedTuple):
    """A reference: level `level` of this bench's case `case` (level_reference)."""
    case: str
    level: int


class LadderRow(NamedTuple):
    """A reference: the uniform ladder's row (case, solver) in the contact solver's store (ladder_reference)."""
    case: str
    solver: str


# case: (scene in input/, parameter replacements for the coarse start, add an unload, the reference: a dict of outputs,
# a LevelOf, a LadderRow, the name of the case whose reference run is its reference, or None)
CASES = {
    # from the scene's own first mesh: the loading-rate scenes ship the coarse start (h_tip 0.04 um within 0.9 um,
    # h_far 0.3 um) since 875b37f
    "lr1": ("loading_rate_a1.yaml", {}, True,
            {"h_max": 194.91, "creep": 35.47, "h_res": 125.64}),
    # alpha = 0.1, whose uniform ladder has not settled (its answer an extrapolation, +- 4.3 % in the creep depth)
    "lr01": ("loading_rate_a0.1.yaml", {}, True,
             {"h_max": 216.24, "creep": 15.18, "h_res": 129.93, "converged": False,
              "from": "the 2D study's P2 ladder: creep its Richardson limit (p 0.90) +- 4.3 %, the others its finest three's mean"}),
    # against its own level 5 (the module's docstring)
    "sector": ("nanoindent_kerogen_sector.yaml", {"h_tip: 0.12, h_far: 0.48": "h_tip: 0.2, h_far: 0.8"}, False,
               LevelOf("sector", 5)),
    # the sector on P1 elements from the same coarse start: what the element order buys on adapted meshes
    "sector_p1": ("nanoindent_kerogen_sector.yaml", {"h_tip: 0.12, h_far: 0.48": "h_tip: 0.2, h_far: 0.8",
                                                     "order: 2": "order: 1"}, False, LevelOf("sector", 5)),
    "axi": ("nanoindent_kerogen_axi.yaml", {}, False, None),
    "sphere": ("nanoindent_kerogen_axi.yaml", {"indenter: {shape: cone, half_angle: 70.3, contact: contact}":
                                               "indenter: {shape: sphere, radius: 2, contact: contact}",
                                               "until: {depth: 0.2}": "until: {depth: 0.1}"}, False, None),
    # the same sphere from a coarse first mesh, so that the levels' errors (about 0.2 to 2 %) are above the reference's
    # own uncertainty and the effectivity can be measured; its reference is the sphere's
    "sphere_coarse": ("nanoindent_kerogen_axi.yaml", {"indenter: {shape: cone, half_angle: 70.3, contact: contact}":
                                                      "indenter: {shape: sphere, radius: 2, contact: contact}",
                                                      "until: {depth: 0.2}": "until: {depth: 0.1}",
                                                      "h_tip: 0.02, h_far: 0.15": "h_tip: 0.1, h_far: 0.3"}, False, "sphere"),
    # the bedding scenes from their shipped first mesh (P2, h_tip 0.7071 um within 10 um), against their own level 3
    **{f"bed{t}": (f"bedding_theta{t}.yaml", {}, False, LevelOf(f"bed{t}", 3)) for t in (0, 30, 45, 60, 90)},
    "bn": ("microindent_BN_sector.yaml", {"h_tip: 2.5, h_far: 20": "h_tip: 5, h_far: 20"}, False, None),
    "bp": ("microindent_BP.yaml", {"h_tip: 2.5, h_far: 20": "h_tip: 5, h_far: 20"}, False, None),
}
# the same cases on the uniform ladder's fixed steps: (case, the ladder's row (case, solver) that is their reference)
OWN_REFERENCE_RUN = ("axi", "sphere")   # cases whose reference is a P2 run on its own adapted meshes (the module docstring)
ON_FIXED_STEPS = {"sector_fixed": ("sector", LadderRow("fix0.019", FORCING)), "bn_fixed": ("bn", LadderRow("bnfix0.475", FORCING))}
CASES.update({c: CASES[of][:3] + (row,) for c, (of, row) in ON_FIXED_STEPS.items()})


def scene_text(case, order=None):
    name, repl, unload, _ = CASES[case]
    text = (ROOT / "input" / name).read_text().replace("../meshes/", f"{ROOT}/meshes/")
    for a, b in repl.items():
        assert a in text, f"{case}: '{a}' not in {name}"
        text = text.replace(a, b)
    if unload:
        text = text.replace("output:\n  directory", UNLOAD + "output:\n  directory", 1)
    if order:
        text = text.replace("  kinematics:", f"  order: {order}\n  kinematics:", 1) if "order:" not in text else \
            text.replace("order: 1", f"order: {order}").replace("order: 2", f"order: {order}")
    if case in ON_FIXED_STEPS:
        d = yaml.safe_load(text)
        assert len(d["stages"]) == len(FIXED_STEPS), f"{case}: {len(d['stages'])} stages, the fixed steps are for 3"
        for stage, steps in zip(d["stages"], FIXED_STEPS):
            stage["steps"] = dict(steps)
        text = yaml.safe_dump(d, sort_keys=False)
    return text


def level_reference(results, base, case, n):
    """Level n of a case of this bench as the reference of others (and of its own levels below n): its outputs from
    its run in base, else from results (the store's levels); None where it has not run that far. Against a level of
    the same case the levels from n on have no measurable error, so no effectivity (adapt_study.effectivity)."""
    done = [lv for lv in (levels_of(base / case) if (base / case / "adapt").is_dir() else results.get(case, {}).get("levels", []))
            if lv["level"] == n]
    if not done:
        return None
    return dict(done[0]["q"], **{"from": f"{case} adapted to level {n}, {done[0]['unknowns']} unknowns"})


def ladder_reference(case, solver):
    """The outputs of the uniform ladder's row (case, solver) in the contact solver's store, with where they come from."""
    rows = [r for r in results_store.load(LADDER).get("rows", []) if (r["case"], r["solver"]) == (case, solver)]
    if not rows or "outputs" not in rows[-1]:
        raise SystemExit(f"docs/results/{LADDER}.json: no row {case}, '{solver}' with outputs (run "
                         f"bench/contact_solver_bench.py --cases {case} --solvers '{solver}' --merge first)")
    return dict(rows[-1]["outputs"], **{"from": f"uniform P2, {rows[-1]['unknowns']} unknowns, the same steps ({case}, {solver})",
                                        "converged": False})


def run(case, out, levels, order=None, extra=()):
    out.mkdir(parents=True, exist_ok=True)
    scene = out.parent / f"{out.name}.yaml"
    scene.write_text(scene_text(case, order))
    t0 = time.time()
    extra = (*extra, *FIXED_RTOL) if case in ON_FIXED_STEPS else extra   # Newton stopped as on the ladder's rungs
    proc = run_driver(scene, out, ["-adapt_levels", levels, *extra], root=ROOT, timeout=7200, check=False)
    (out.parent / f"{out.name}.log").write_text(proc.stdout + proc.stderr)
    if proc.returncode:
        raise SystemExit(f"{case}: driver failed ({proc.returncode}): {proc.stderr[-2000:]}")
    print(f"{case}: {time.time() - t0:.0f} s wall", flush=True)


def quantities(summary):
    """depth at the end of the first stage (h_max, nm), the load then (P), the depth change over the second (creep, nm)
    and the depth at the end of the last (h_res, nm) when the scene unloads to zero."""
    st = summary["stages"]
    q = {"h_max": 1000 * st[1]["end"]["depth"], "P": st[1]["end"]["load"], "creep": 1000 * st[2]["change"]["depth"]}
    e = {"h_max": 1000 * st[1].get("mesh_error", {}).get("end", {}).get("depth", float("nan")),
         "P": st[1].get("mesh_error", {}).get("end", {}).get("load", float("nan")),
         "creep": 1000 * st[2].get("mesh_error", {}).get("change", {}).get("depth", float("nan"))}
    if len(st) > 3 and abs(st[-1]["end"]["load"]) < 1e-9:
        q["h_res"] = 1000 * st[-1]["end"]["depth"]
        e["h_res"] = 1000 * st[-1].get("mesh_error", {}).get("end", {}).get("depth", float("nan"))
    return q, e


def levels_of(out):
    rows = []
    for d in sorted((out / "adapt").glob("level*"), key=lambda p: int(p.name[5:])):
        if (d / "summary.json").exists():
            s = read_summary(d)
            q, e = quantities(s)
            rows.append({"level": int(d.name[5:]), "cells": s["mesh"]["cells"], "unknowns": s["mesh"]["unknowns"],
                         "cpu": s["levels"][-1]["cpu_s"], "umat_calls": s["levels"][-1]["umat_calls"], "q": q, "e": e})
    return rows


def reference(case, results, base):
    """A case's reference (CASES): its outputs, or None where the runs it comes from are neither here nor in results."""
    ref = CASES[case][3]
    if isinstance(ref, LevelOf):
        return level_reference(results, base, *ref)
    if isinstance(ref, LadderRow):   # on the same fixed steps
        return ladder_reference(*ref)
    if isinstance(ref, str) or (ref is None and case in OWN_REFERENCE_RUN):   # a reference run's answer, its last level done
        done = [d / "summary.json" for d in sorted((base / f"{ref or case}_ref" / "adapt").glob("level*"), key=lambda p: int(p.name[5:]))
                if (d / "summary.json").exists()]
        if not done:
            return None
        s = read_summary(done[-1])
        return dict(quantities(s)[0], **{"from": f"P2, {s['mesh']['unknowns']} unknowns"})
    return ref


def run_info(out, note):
    """When a case's levels in `out` ran (the date of its first level's summary) and on what machine (`note`); the
    section gives it beside the case where it differs from the store's first runs."""
    first = out / "adapt" / "level0" / "summary.json"
    return {"date": time.strftime("%Y-%m-%d", time.gmtime(first.stat().st_mtime)), "note": note} if first.exists() else None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", default="lr1,sector,axi,sphere")
    ap.add_argument("--levels", type=int, default=3)
    ap.add_argument("--results", default="out/adapt_bench.json")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--doc", action="store_true", help="write docs/results/adapt_bench.json and the section of docs/performance.md")
    ap.add_argument("--note", default="shared 2-core machine, CPU of one rank", help="machine load, for the section")
    ap.add_argument("--keep-references", action="store_true",
                    help="axi, sphere: take the reference runs already in out/adapt_bench (their answers do not depend on the estimate)")
    a = ap.parse_args()
    base = Path("out/adapt_bench")
    # the levels of earlier runs: --results, else the store's (so that --no-run --doc over every case keeps them)
    results = json.loads(Path(a.results).read_text()) if Path(a.results).exists() else results_store.load(STORE).get("cases", {})
    for case in a.cases.split(","):
        out = base / case
        if not a.no_run:
            run(case, out, a.levels)
            if CASES[case][3] is None and case in OWN_REFERENCE_RUN and not a.keep_references:   # the reference: P2 on its own meshes, a level more
                run(case, base / f"{case}_ref", a.levels + 1, order=2)
        if a.no_run and case in results and not (out / "adapt").is_dir():   # its runs are not here: the levels kept in --results,
            results[case]["reference"] = reference(case, results, base) or results[case]["reference"]   # the reference as CASES says
            continue
        results[case] = {"levels": levels_of(out), "reference": reference(case, results, base), "run": run_info(out, a.note)}
    Path(a.results).parent.mkdir(parents=True, exist_ok=True)
    Path(a.results).write_text(json.dumps(results, indent=1))
    kept = results_store.load(STORE)   # the cases run before the indicator's contact term, which the reading compares
    first = kept.get("provenance", {"date": time.strftime("%Y-%m-%d", time.gmtime()), "note": a.note})   # the store's first runs
    store = {"provenance": {"command": "`bench/adapt_bench.py --cases CASE --levels N` for each case, N its table's last level, "
                                       f"then `bench/adapt_bench.py --cases {a.cases} --no-run --doc`",
                            "date": first["date"], "note": first["note"]},
             "cases": {c: results[c] for c in a.cases.split(",")}}
    if "before_contact_term" in kept:
        store["before_contact_term"] = kept["before_contact_term"]
        for c, r in store["before_contact_term"].get("cases", {}).items():   # one reference for both, where it is a level
            if c in store["cases"] and isinstance(CASES[c][3], LevelOf):
                r["reference"] = store["cases"][c]["reference"]
    text = section(store, ROOT)
    print(text)
    if a.doc:
        print(f"written: {results_store.save(STORE, store)}")
        replace_section(TITLE, text)


if __name__ == "__main__":
    main()
