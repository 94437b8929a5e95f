#!/usr/bin/env python3
"""The data against the fitted curves of a calibration: reads OUT/curves.csv (written by scene: calibrate) and
draws one panel per run and block (loading and unloading: depth against load; hold: creep depth against
time; series: the model column against time; a block per stage), data as dots, the fitted model as a line (with a
fitted drift: the model plus the drift, drift: fit; the data less it, drift measured in a hold).

  post/calibrate_plot.py out/calibrate/NAME [-o fit.png]
"""
import argparse
import csv
import os
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_curves(path):
    blocks = OrderedDict()
    with open(path) as f:
        for r in csv.DictReader(f):
            name = r["block"] + (f" '{r['stage']}'" if r.get("stage") else "")  # two holds: each its panel
            b = blocks.setdefault((r["run"], name), {"x_name": r["x_name"], "y_name": r["y_name"], "x": [],
                                                     "data": [], "model": []})
            for k in ("x", "data", "model"):
                b[k].append(float(r[k]))
    return blocks


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("-o", "--output")
    a = ap.parse_args()
    blocks = read_curves(os.path.join(a.outdir, "curves.csv"))
    runs = list(OrderedDict.fromkeys(r for r, _ in blocks))
    ncol = max(sum(1 for r, _ in blocks if r == run) for run in runs)
    fig, axes = plt.subplots(len(runs), ncol, figsize=(4 * ncol, 3.2 * len(runs)), squeeze=False)
    for i, run in enumerate(runs):
        for j, ((_, block), b) in enumerate((k, v) for k, v in blocks.items() if k[0] == run):
            ax = axes[i][j]
            ax.plot(b["x"], b["data"], "o", ms=3, label="data")
            ax.plot(b["x"], b["model"], "-", label="fit")
            rel = " (less its mean)" if block.startswith("hold") else ""
            ax.set(title=f"{run}: {block}", xlabel=b["x_name"], ylabel=b["y_name"] + rel)
            ax.legend(fontsize=8)
        for j in range(sum(1 for r, _ in blocks if r == run), ncol):
            axes[i][j].axis("off")
    fig.tight_layout()
    out = a.output or os.path.join(a.outdir, "fit.png")
    fig.savefig(out, dpi=120)
    print(out)


if __name__ == "__main__":
    main()
