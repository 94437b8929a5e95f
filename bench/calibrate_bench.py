#!/usr/bin/env python3
"""Calibration benchmark (issue 15): each example of input/calibrate/ run as a user would, one forward run at a
time (separate driver processes): TAO iterations, forward runs, wall time, and the recovered viscosities against
the values the synthetic data were made with (eta_soft 1.3e10, eta_hard 1.3e13 MPa^3 s). Writes the section
"## Calibration" of docs/performance.md. Usage: bench/calibrate_bench.py [--examples a,b,...]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import yaml

sys.path.insert(0, str(Path(__file__).resolve().parent))
from performance_doc import replace_section  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
DRIVER = Path(os.environ.get("DRIVER", ROOT / "build" / "bin" / "driver"))
TRUE = {"eta_soft": 1.3e10, "eta_hard": 1.3e13}
TITLE = "## Calibration"
EXAMPLES = "nano_eta_soft,micro_BN_eta_hard,nano_micro_joint,triaxial_creep_lab,nano_eta_soft_noise1"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--examples", default=EXAMPLES)
    a = ap.parse_args(argv)
    lines = ["| example | forward model | TAO its | forward runs | wall [s] | recovered (error against the truth) |",
             "|---|---|---|---|---|---|"]
    with tempfile.TemporaryDirectory() as tmp:
        for name in a.examples.split(","):
            scene = ROOT / "input" / "calibrate" / f"{name}.yaml"
            out = Path(tmp) / name
            t0 = time.perf_counter()
            proc = subprocess.run([str(DRIVER), "-input", str(scene), "-output_dir", str(out)], capture_output=True, text=True)
            wall = time.perf_counter() - t0
            if proc.returncode:
                raise SystemExit(f"{scene}: failed:\n{proc.stdout[-1500:]}\n{proc.stderr[-1500:]}")
            fit = yaml.safe_load((out / "fit.yaml").read_text())
            cost = fit["cost"]
            models = ", ".join(Path(m["scene"]).stem for m in fit.get("forward_models", []))
            rec = "; ".join(f"{k} {v['value']:.5g} ({v['value'] / TRUE[k] - 1:+.2%}, s.e. {v['relative_std_error']:.1%})"
                            for k, v in fit["parameters"].items() if k in TRUE)
            print(f"{name}: {cost['iterations']} TAO its, {cost['forward_runs']} forward runs, {wall:.1f} s; {rec}", flush=True)
            lines.append(f"| {name} | {models} | {cost['iterations']} | {cost['forward_runs']} | {wall:.1f} | {rec} |")
    section = (f"{TITLE}\n\nCommand: `bench/calibrate_bench.py`. The examples of `input/calibrate/` (docs/calibrate.md), TAO "
               "POUNDERS, one forward\nrun at a time; synthetic data made by the driver with eta_soft 1.3e10 and eta_hard "
               "1.3e13 (the noise example:\n1 % noise, so its error is to be read against its standard error). One run "
               "each on a shared machine.\n\n" + "\n".join(lines) + "\n")
    replace_section(TITLE, section)
    print("written: docs/performance.md")


if __name__ == "__main__":
    sys.exit(main())
