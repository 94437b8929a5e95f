#!/usr/bin/env python3
"""Synthetic measured data for the calibrate examples: run a forward scene with the driver at known PROPS
(-material_set), then sample its history like a measurement and optionally add noise.

Indentation (history with load, depth): N points on loading at evenly spaced loads, N on the hold at evenly
spaced times, N on unloading at evenly spaced loads; columns time_s, load_uN, depth_um. Point scene: N points
evenly spaced in time over the segment (--segment, 0-based); columns time_<unit> (--time-unit s|min|h),
axial_strain_percent (compression positive); --from-start: time and strain from the segment's start.

  make_synthetic.py --driver build/bin/driver --scene forward/nano_fast.yaml --set eta_soft=1.3e10 \\
      --out data/nano_synthetic.csv [--noise 0.01 --seed 1] [--points 15]
Noise: each depth (strain) times (1 + noise * N(0, 1)), a fixed seed.

An instrument's record (--instrument RATE): the indentation history sampled every 1/RATE s from its start, with
the columns an instrument might write, in its order and units: depth_nm, load_mN, time_s, segment (the stage,
from 1). --protocol FILE: the forward scene's stages replaced by FILE's (name, duration, indenter; each keeps the
step control of the scene's stage of the same index), e.g. protocols/ramp600_hold30.yaml.
"""
import argparse
import copy
import csv
import os
import subprocess
import sys
import tempfile

import numpy as np
import yaml


def read_history(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0] if k != "stage_name"}


def sample_indentation(h, n):
    """Rows (time, load, depth) on loading, hold, unloading, interpolated in the history."""
    stage = h["stage"].astype(int)
    out = []
    for s, by in ((0, "load"), (1, "time"), (2, "load")):
        idx = np.nonzero(stage == s)[0]
        if s > 0:
            idx = np.concatenate([[idx[0] - 1], idx])
        x = h[by][idx]
        lo, hi = (x.min(), x.max())
        if s == 0:
            targets = np.linspace(lo + 0.1 * (hi - lo), hi, n)
        elif s == 1:
            targets = np.linspace(lo, hi, n + 1)[1:]  # after the hold's start
        else:
            targets = np.linspace(hi, lo, n + 1)[1:-1]  # decreasing loads, not the first nor the final zero
        order = np.argsort(x)
        for v in targets:
            t = np.interp(v, x[order], h["time"][idx][order])
            d = np.interp(v, x[order], h["depth"][idx][order])
            load = np.interp(v, x[order], h["load"][idx][order])
            out.append((t, load, d))
    out.sort()
    return ["time_s", "load_uN", "depth_um"], out


def sample_instrument(h, rate):
    """The history every 1/rate s from 0 to its end, as an instrument writes it: depth in nm, load in mN, time in
    s, the segment (stage + 1: the stage of the step that ends at or after the time)."""
    t = h["time"]
    times = np.arange(0.0, t[-1] + 0.5 / rate, 1.0 / rate)
    times = times[times <= t[-1] + 1e-9]
    seg = h["stage"].astype(int)[np.minimum(np.searchsorted(t, times - 1e-9 * max(t[-1], 1.0)), len(t) - 1)] + 1
    depth, load = np.interp(times, t, h["depth"]), np.interp(times, t, h["load"])
    return ["depth_nm", "load_mN", "time_s", "segment"], [(1e3 * d, 1e-3 * p, tt, float(s))
                                                          for d, p, tt, s in zip(depth, load, times, seg)]


def with_protocol(scene, protocol, tmp):
    """The scene with its stages replaced by the protocol's (each keeps the step control of the scene's stage of
    the same index); its mesh path made absolute; written into tmp."""
    with open(scene) as f:
        doc = yaml.safe_load(f)
    with open(protocol) as f:
        stages = yaml.safe_load(f)["stages"]
    for i, st in enumerate(stages):
        st.setdefault("steps", copy.deepcopy(doc["stages"][min(i, len(doc["stages"]) - 1)]["steps"]))  # no YAML alias
    doc["stages"] = stages
    for key in ("geometry", "file"):
        if key in doc.get("mesh", {}):
            doc["mesh"][key] = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(scene)), doc["mesh"][key]))
    path = os.path.join(tmp, "scene_with_protocol.yaml")
    with open(path, "w") as f:
        yaml.safe_dump(doc, f, sort_keys=False)
    return path


TIME_UNITS = {"s": 1.0, "min": 60.0, "h": 3600.0}


def sample_point(h, n, segment, column, unit="h", from_start=False):
    """N times evenly spaced over the segment (after its start); with from_start, time and strain counted from
    the segment's start (a lab creep record: the time since the load, the creep strain)."""
    idx = np.nonzero(h["stage"].astype(int) == segment)[0]
    idx = np.concatenate([[idx[0] - 1], idx]) if idx[0] > 0 else idx  # the segment's start: the row before it
    t = h["time"][idx]
    if from_start:  # the instant load's zero-time step: the creep strain counts from after it
        t0, y0 = t[0], h[column][idx][t == t[0]][-1]
    else:
        t0, y0 = 0.0, 0.0
    targets = np.linspace(t[0], t[-1], n + 1)[1:]
    y = np.interp(targets, t, h[column][idx])
    return ([f"time_{unit}", "axial_strain_percent"],
            [((tt - t0) / TIME_UNITS[unit], -100.0 * (yy - y0)) for tt, yy in zip(targets, y)])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--driver", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--set", required=True, help="NAME=VALUE[,NAME=VALUE]: the known parameters")
    ap.add_argument("--out", required=True)
    ap.add_argument("--points", type=int, default=15)
    ap.add_argument("--noise", type=float, default=0.0)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--segment", type=int, default=1, help="point scenes: the segment sampled")
    ap.add_argument("--column", default="eps_33", help="point scenes: the strain column sampled")
    ap.add_argument("--time-unit", choices=sorted(TIME_UNITS), default="h", help="point scenes: the time column's unit")
    ap.add_argument("--from-start", action="store_true",
                    help="point scenes: time and strain from the segment's start (a lab creep record)")
    ap.add_argument("--protocol", help="a YAML file whose stages replace the scene's")
    ap.add_argument("--instrument", type=float, metavar="RATE",
                    help="indentation: every 1/RATE s, as an instrument writes (depth_nm, load_mN, time_s, segment)")
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        scene = with_protocol(a.scene, a.protocol, tmp) if a.protocol else a.scene
        r = subprocess.run([a.driver, "-input", scene, "-output_dir", os.path.join(tmp, "out"), "-material_set", a.set],
                           capture_output=True, text=True, timeout=600)
        if r.returncode:
            sys.exit(f"make_synthetic: the driver failed:\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
        h = read_history(os.path.join(tmp, "out", "history.csv"))
    if a.instrument:
        header, rows = sample_instrument(h, a.instrument)
    elif "depth" in h:
        header, rows = sample_indentation(h, a.points)
    else:
        header, rows = sample_point(h, a.points, a.segment, a.column, a.time_unit, a.from_start)
    rng = np.random.default_rng(a.seed)
    ydepth = 0 if a.instrument else -1  # the column that carries the noise: the depth (strain)
    rows = [tuple(v * (1 + a.noise * rng.standard_normal()) if i == (ydepth % len(r)) else v for i, v in enumerate(r))
            for r in rows]
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        protocol = f", protocol {os.path.basename(a.protocol)}" if a.protocol else ""
        f.write(f"# synthetic: {os.path.basename(a.scene)}{protocol} with {a.set}, noise {a.noise} (seed {a.seed}); "
                "input/calibrate/make_synthetic.py\n")
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(f"{v:.10g}" for v in r) + "\n")
    print(f"{a.out}: {len(rows)} rows")


if __name__ == "__main__":
    main()
