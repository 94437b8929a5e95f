#!/usr/bin/env python3
"""Calibration benchmark (issues 15, 22): each example of input/calibrate/ run as a user would, one forward run at a
time (separate driver processes): TAO iterations, forward and full-model runs, CPU (the driver and its forward
processes: user + system) and wall time, the forward model's fit, the quoted value and the forward model's bias
(first estimate, measured by the refinement), each against the value the synthetic data were made with
(eta_soft 1.3e10, eta_hard 1.3e13 MPa s). Variants run an example with another forward model (own_curve_fast:
own_curve.yaml with nano_fast instead of nano_mid). Keeps every number its table prints in the results store
docs/results/calibrate_bench.json (camclay9.calibrate_study: fit.yaml's numbers at full digits, CPU and wall time,
command, date and machine note) and writes the section "## Calibration" of docs/performance.md from it, which
tools/doc_numbers.py checks.

  bench/calibrate_bench.py [--examples a,b,...] [--make-data] [--machine NOTE] [--no-doc]

--examples runs only those; every other example keeps its row from the store as it stood, with that run's
provenance (the section names it), or is listed as not run.

--make-data makes an example's missing record first (micro_BP_3d_eta_hard_bias: one full 3D run, some 20 min);
without it such an example is skipped and said so. Long: about 40 min on the shared machine (run it under nice).
"""
import argparse
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml
from camclay9 import DriverError, driver_path, results_store, run_driver
from camclay9 import calibrate_study as study
from camclay9.performance_doc import publish

ROOT = Path(__file__).resolve().parents[1]
CAL = ROOT / "input" / "calibrate"
TRUE = {"eta_soft": 1.3e10, "eta_hard": 1.3e13}
EXAMPLES = ("own_curve,own_curve_fast,nano_eta_soft,micro_BN_eta_hard,nano_micro_joint,triaxial_creep_lab,"
            "nano_eta_soft_noise1,nano_eta_soft_bias,nano_eta_soft_bias_mid,micro_BN_eta_hard_bias,"
            "micro_BN_eta_hard_bias_mid,micro_BP_3d_eta_hard")
VARIANTS = {"own_curve_fast": ("own_curve", "forward/nano_mid.yaml", "forward/nano_fast.yaml")}
RECORDS = {  # records not shipped: made by --make-data
    "micro_BP_3d_reference_synthetic.csv": ["--scene", str(CAL / "forward" / "micro_BP_3d_reference.yaml"), "--set",
                                            "eta_soft=1.3e10,eta_hard=1.3e13", "--instrument", "1"],
}


def scene_of(name, tmp):
    """The example's scene, or a variant's (written into tmp with absolute paths and its forward model)."""
    if name not in VARIANTS:
        return CAL / f"{name}.yaml"
    base, old, new = VARIANTS[name]
    text = (CAL / f"{base}.yaml").read_text().replace(old, new)
    text = re.sub(r"(scene|file): (forward|data)/", lambda m: f"{m.group(1)}: {CAL}/{m.group(2)}/", text)
    path = Path(tmp) / f"{name}.yaml"
    path.write_text(text.replace(f"name: {base}", f"name: {name}"))
    return path


def missing_record(scene, make):
    """A record the scene needs that is not there: made (make) or named (the example is skipped)."""
    for data, args in RECORDS.items():
        if f"data/{data}" in scene.read_text() and not (CAL / "data" / data).exists():
            if not make:
                return data
            subprocess.run([sys.executable, str(CAL / "make_synthetic.py"), "--driver", str(driver_path(root=ROOT)), *args,
                            "--out", str(CAL / "data" / data)], check=True, timeout=3600)
    return None


def record(name, fit, cpu, wall):
    """The store's entry for one example (camclay9.calibrate_study): fit.yaml's numbers at full digits."""
    cost = fit["cost"]
    ex = {"name": name,
          "models": [{"scene": Path(m["scene"]).stem, "drive": m.get("drive", "scene"),
                      "reference": Path(m["reference"]).stem if m.get("reference") else None}
                     for m in fit.get("forward_models", [])],
          "iterations": cost["iterations"], "forward_runs": cost["forward_runs"],
          "full_model_runs": cost["full_model_runs"], "cpu_s": cpu, "wall_s": wall,
          "parameters": {k: {"value": p["value"], "relative_std_error": p["relative_std_error"]}
                         for k, p in fit["parameters"].items()},
          "quote": {k: {"value": fit["quote"][k]["value"], "relative_std_error": fit["quote"][k]["relative_std_error"]}
                    for k in fit["parameters"]},
          "bias": {k: {"relative": b["relative"], "value": b.get("value")}
                   for k, b in (fit.get("bias") or {}).items() if b},
          "refined": bool(fit.get("refinement", {}).get("refined"))}
    print(study.row(ex, TRUE), flush=True)
    return ex


def run_examples(names, make_data):
    """{name: store entry} for the examples run now; the texts of those skipped for a missing record."""
    done, skipped = {}, []
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            scene = scene_of(name, tmp)
            need = missing_record(scene, make_data)
            if need:
                skipped.append(f"{name} (its record data/{need} is not made: --make-data)")
                print(f"{name}: skipped, data/{need} missing (--make-data makes it)", flush=True)
                continue
            out = Path(tmp) / name
            try:
                proc = run_driver(scene, out, root=ROOT, timeout=6 * 3600)
            except DriverError as err:
                raise SystemExit(f"{scene}: failed: {err}")
            done[name] = record(name, yaml.safe_load((out / "fit.yaml").read_text()), proc.cpu, proc.wall)
    return done, skipped


def kept_from(old, name):
    """An example not run now, from the store as it stood: with its own provenance (that run's, unless it has one)."""
    for ex in old.get("examples", []):
        if ex["name"] == name:
            pv = old["provenance"]
            return {**ex, "provenance": ex.get("provenance")
                    or {"note": f"from the run of {pv['date']} (`{pv['command']}`), kept in the store"}}
    return None


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", default=EXAMPLES, help="run these; the others' rows kept from the store if it has them")
    ap.add_argument("--make-data", action="store_true", help="make the records an example needs that are not shipped")
    ap.add_argument("--machine", default="a shared 2-core machine",
                    help="the machine note the store and the section carry (default: %(default)s)")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    names = a.examples.split(",")
    done, skipped = run_examples(names, a.make_data)
    old = results_store.load(study.STORE)
    examples, not_run = [], list(skipped)
    for name in EXAMPLES.split(","):
        ex = done.get(name) or (None if name in names else kept_from(old, name))
        if ex:
            examples.append(ex)
        elif name not in names:
            not_run.append(name)
    provenance = {"command": "bench/calibrate_bench.py" + (f" --examples {a.examples}" if a.examples != EXAMPLES else ""),
                  "date": time.strftime("%Y-%m-%d", time.gmtime()), "machine": a.machine}
    store = {"provenance": provenance, "true": TRUE, "examples": examples, "not_run": not_run}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    sys.exit(main())
