#!/usr/bin/env python3
"""The time-step error a run states (docs/adapt.md, "The time-step error"): each case at its shipped step control and
at finer ones; the stated error of each held stage's change against its true error. Keeps every number its table
prints in the results store docs/results/time_error.json and writes the section "Stated time-step error" of
docs/performance.md from it (camclay9.time_error_study, which tools/doc_numbers.py checks).

    bench/time_error_bench.py [--out out/time_error_bench] [--cases A,B] [--machine NOTE] [--no-doc]

The true error: backward Euler under these controls is first order (docs/performance.md, "Time-step error control":
the errors halve with the tol), so the value at the finest two controls, extrapolated to zero (2 v(c/2) - v(c)), is
the reference, and its uncertainty is the finest run's distance from it.
Cases:
- kerogen_axi: input/nanoindent_kerogen_axi.yaml, the output measure's tol 0.03, 0.015 (shipped), 0.005, 0.0025 on the
  load and the hold; the creep depth (the hold's depth change).
- kerogen_sector: input/nanoindent_kerogen_sector.yaml (3D, P2, the uniform zone as shipped), the same controls: the
  load stage's steps leave an error in the state the hold starts from, which the hold's own sum does not hold.
- kerogen_sector_load: the same scene with only the load stage's tol varied (the hold's stays 0.015): the error
  its steps leave in the state the hold starts from, which the stated error (the hold's own steps) does not hold.
- sphere: input/your_indent_axi.yaml (README, "Your own indentation scene"), tol 0.015 (shipped), 0.0075, 0.00375.
- triaxial: input/triaxial.yaml on one rank, the creep stage's largest step 2000 s (shipped), 500, 125 s (its step is
  set by the UMAT's control and that cap); the axial strain's change over the creep stage.
"""
import argparse
import json
import time
from pathlib import Path

from camclay9 import DriverError, read_summary, results_store, run_driver
from camclay9 import time_error_study as study
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]

# case: (scene, the text the control is in (with {} for its value), its values, finest last; the stage; the quantity)
CASES = {
    "kerogen_axi": ("nanoindent_kerogen_axi.yaml", "tol: {}", ["1.5e-2", "0.03", "0.005", "0.0025"], "hold", "depth"),
    "kerogen_sector": ("nanoindent_kerogen_sector.yaml", "tol: {}", ["1.5e-2", "0.03", "0.005", "0.0025"], "hold", "depth"),
    "kerogen_sector_load": ("nanoindent_kerogen_sector.yaml", "tol: {}", ["1.5e-2", "0.03", "0.005", "0.0025"], "hold", "depth"),
    "sphere": ("your_indent_axi.yaml", "tol: {}", ["1.5e-2", "0.0075", "0.00375"], "hold", "depth"),
    "triaxial": ("triaxial.yaml", "max: {}", ["2000", "500", "125"], "creep", "strain_axial"),
}


FIRST_ONLY = ("kerogen_sector_load",)  # the control's first place only: the load stage


def run(case, value, out):
    name, pattern, values, _, _ = CASES[case]
    text = (ROOT / "input" / name).read_text().replace("../meshes/", f"{ROOT}/meshes/")
    shipped = pattern.format(values[0])  # every stage controlled by it (not the unloads' looser tol)
    assert shipped in text, f"{case}: '{shipped}' not in {name}"
    text = text.replace(shipped, pattern.format(value), 1 if case in FIRST_ONLY else -1)
    out.mkdir(parents=True, exist_ok=True)
    scene = out.parent / f"{out.name}.yaml"
    scene.write_text(text)
    try:
        run_driver(scene, out, root=ROOT, timeout=3600)
    except DriverError as err:
        raise SystemExit(f"{case} at {value}: the driver failed: {err}")
    return read_summary(out)


def measure(case, root):
    _, _, values, stage, q = CASES[case]
    rows = []
    for v in values:
        js = run(case, v, root / f"{case}_{v}")
        st = next(s for s in js["stages"] if s["name"] == stage)
        rows.append({"control": v, "steps": js["counters"]["steps"], "cpu_s": js["cost"]["cpu_s"],
                     "value": st["change"][q], "stated": st["time_error"]["change"][q]})
    fine = sorted(rows, key=lambda r: float(r["control"]))
    ref = 2 * fine[0]["value"] - fine[1]["value"]
    for r in rows:
        r["true"] = r["value"] - ref
        r["effectivity"] = r["stated"] / abs(r["true"]) if r["true"] and case not in FIRST_ONLY else None
    return {"stage": stage, "quantity": q, "reference": ref, "uncertainty": abs(fine[0]["value"] - ref), "rows": rows}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(ROOT / "out" / "time_error_bench"))
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    ap.add_argument("--cases", default=",".join(CASES), help="run these; the others' results from OUT/results.json")
    ap.add_argument("--machine", default="a shared 2-core machine, one rank",
                    help="the machine note the store and the section carry (default: %(default)s)")
    a = ap.parse_args()
    root = Path(a.out)
    kept = json.loads((root / "results.json").read_text()) if (root / "results.json").is_file() else {}
    run_now = a.cases.split(",")
    results = {case: measure(case, root) if case in run_now else kept[case] for case in CASES if case in run_now or case in kept}
    (root / "results.json").write_text(json.dumps(results, indent=1) + "\n")
    earlier = [case for case in results if case not in run_now]
    provenance = {"command": "bench/time_error_bench.py" + (f" --cases {a.cases}" if earlier else ""),
                  "date": time.strftime("%Y-%m-%d", time.gmtime()), "machine": a.machine}
    if earlier:
        provenance["note"] = f"cases {', '.join(earlier)} from an earlier run's {root.name}/results.json"
    store = {"provenance": provenance, "cases": results}
    text = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(text)
    if not a.no_doc:
        replace_section(study.TITLE, text)
        results_store.save(study.STORE, store)


if __name__ == "__main__":
    main()
