#!/usr/bin/env python3
"""Calibration benchmark (issues 15, 22): each example of input/calibrate/ run as a user would, one forward run at a
time (separate driver processes): TAO iterations, forward and full-model runs, CPU (the driver and its forward
processes: user + system) and wall time, the forward model's fit, the quoted value and the forward model's bias
(first estimate, measured by the refinement), each against the value the synthetic data were made with
(eta_soft 1.3e10, eta_hard 1.3e13 MPa s). Variants run an example with another forward model (own_curve_fast:
own_curve.yaml with nano_fast instead of nano_mid). Writes the section "## Calibration" of docs/performance.md.

  bench/calibrate_bench.py [--examples a,b,...] [--make-data]

--make-data makes an example's missing record first (micro_BP_3d_eta_hard_bias: one full 3D run, some 20 min);
without it such an example is skipped and said so. Long: about 40 min on the shared machine (run it under nice).
"""
import argparse
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import yaml
from camclay9 import DriverError, driver_path, run_driver
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]
CAL = ROOT / "input" / "calibrate"
TRUE = {"eta_soft": 1.3e10, "eta_hard": 1.3e13}
TITLE = "## Calibration"
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
                            "--out", str(CAL / "data" / data)], check=True)
    return None


def pct(x, sign="+"):
    """x as a percentage with two significant digits (0.00041 %, -11 %)."""
    return f"{100 * x:{sign}.2g} %"


def row(name, fit, cpu, wall):
    cost = fit["cost"]
    models = "; ".join(f"{Path(m['scene']).stem} ({m.get('drive', 'scene')})"
                       + (f", ref. {Path(m['reference']).stem}" if m.get("reference") else "")
                       for m in fit.get("forward_models", []))
    fwd, quote, bias = [], [], []
    for k, p in fit["parameters"].items():
        q = fit["quote"][k]
        fwd.append(f"{k} {p['value']:.5g} ({pct(p['value'] / TRUE[k] - 1)}, s.e. {pct(p['relative_std_error'], '')})")
        quote.append(f"{k} {q['value']:.7g} ({pct(q['value'] / TRUE[k] - 1)} ± {pct(q['relative_std_error'], '')})")
        b = fit.get("bias", {}).get(k)
        if b:
            measured = f", measured {pct(b['value'] / p['value'])}" if "value" in b else ""
            bias.append(f"first {pct(b['relative'])}{measured}")
    refined = fit.get("refinement", {}).get("refined")
    print(f"{name}: {cost['iterations']} TAO its, {cost['forward_runs']} forward + {cost['full_model_runs']} full-model "
          f"runs, CPU {cpu:.1f} s, wall {wall:.1f} s; {'; '.join(fwd)}; quote {'; '.join(quote)}", flush=True)
    return (f"| {name} | {models} | {cost['iterations']} | {cost['forward_runs']} | {cost['full_model_runs']} | {cpu:.0f} | "
            f"{wall:.0f} | {'; '.join(fwd)} | {'; '.join(quote)}{' (refined)' if refined else ''} | "
            f"{'; '.join(bias) or '—'} |")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", default=EXAMPLES)
    ap.add_argument("--make-data", action="store_true", help="make the records an example needs that are not shipped")
    a = ap.parse_args(argv)
    lines = ["| example | forward model (drive), full model | TAO its | forward runs | full-model runs | CPU [s] | wall [s] "
             "| forward fit (error, s.e.) | quoted (error ± s.e.) | bias: first estimate, measured |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    skipped = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.examples.split(","):
            scene = scene_of(name, tmp)
            need = missing_record(scene, a.make_data)
            if need:
                skipped.append(f"{name} (its record data/{need} is not made: --make-data)")
                print(f"{name}: skipped, data/{need} missing (--make-data makes it)", flush=True)
                continue
            out = Path(tmp) / name
            try:
                proc = run_driver(scene, out, root=ROOT, timeout=6 * 3600)
            except DriverError as err:
                raise SystemExit(f"{scene}: failed: {err}")
            lines.append(row(name, yaml.safe_load((out / "fit.yaml").read_text()), proc.cpu, proc.wall))
    note = f"\nNot run: {', '.join(skipped)}.\n" if skipped else ""
    section = (f"{TITLE}\n\nCommand: `bench/calibrate_bench.py` (docs/calibrate.md). The examples of `input/calibrate/`, "
               "TAO POUNDERS from a start 3x off, one forward\nrun at a time; synthetic data made by the driver with "
               "eta_soft 1.3e10 and eta_hard 1.3e13 (the noise example:\n1 % noise, so its error is to be read against "
               "its standard error). CPU: the driver and its forward processes\n(user + system). One run each on a "
               "shared machine (wall times vary by about 2x with its load). The forward fit is\nTAO's with the forward "
               "model; the quoted value is fit.yaml's `quote` (refined on the full model when the forward\nmodel's bias "
               "exceeds its standard error); the bias is relative to the forward fit.\n\n" + "\n".join(lines) + "\n" + note)
    replace_section(TITLE, section)
    print("written: docs/performance.md")


if __name__ == "__main__":
    sys.exit(main())
