#!/usr/bin/env python3
"""Run the shipped scenes and keep their histories, or compare them with kept ones: the check that a refactoring
changed no result ("every scene's history.csv bit for bit the one before", issue 24). Every column but wall and
umat_calls' neighbours that measure time is compared as text, so a difference in the last digit shows.

    tools/same_histories.py --save DIR [--driver build/bin/driver] [--scenes GLOB ...]
    tools/same_histories.py --compare DIR [--driver ...]

Scenes: input/*.yaml (FE and indentation; calibrate scenes excluded: their forward runs are these scenes'
kin and the calibrate tests cover them) and input/point/*.yaml, each on one rank.
"""
import argparse
import csv
import fnmatch
import sys
from pathlib import Path

from camclay9 import DriverError, run_driver

ROOT = Path(__file__).resolve().parents[1]
SKIP_COLUMNS = {"wall"}
# Columns renamed since the kept histories were written (issue 35's one layout: a point scene's segment is its
# stage): the kept one is compared with its new name's; columns new since then are not compared.
RENAMED = {"segment": "stage"}


def scenes(patterns):
    found = sorted(ROOT.glob("input/*.yaml")) + sorted(ROOT.glob("input/point/*.yaml"))
    found = [p for p in found if "scene: calibrate" not in p.read_text()]
    if patterns:
        found = [p for p in found if any(fnmatch.fnmatch(p.stem, pat) for pat in patterns)]
    return found


def run(driver, scene, out):
    try:
        return run_driver(scene, out, driver=driver, root=ROOT, cwd=ROOT, timeout=24 * 3600).wall
    except DriverError as err:
        sys.exit(f"{scene.name}: the driver failed: {err}")


def rows(path):
    """The rows as text (no reader that parses numbers: a difference in the last digit must show)."""
    with open(path) as f:
        return [{k: v for k, v in row.items() if k not in SKIP_COLUMNS} for row in csv.DictReader(f)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--save", type=Path)
    group.add_argument("--compare", type=Path)
    ap.add_argument("--driver", type=Path, default=None, help="the driver (default: $DRIVER or build/bin/driver)")
    ap.add_argument("--scenes", nargs="*", default=[], help="glob patterns of scene names (default: all)")
    a = ap.parse_args()
    bad = 0
    for scene in scenes(a.scenes):
        key = f"{scene.parent.name}_{scene.stem}"
        if a.save:
            wall = run(a.driver, scene, a.save / key)
            print(f"{key}: kept ({wall:.0f} s)", flush=True)
            continue
        kept = a.compare / key / "history.csv"
        if not kept.exists():
            print(f"{key}: nothing kept, skipped")
            continue
        out = a.compare / (key + "_now")
        wall = run(a.driver, scene, out)
        old, new = rows(kept), rows(out / "history.csv")
        diff = [(i, k, o[k], n.get(RENAMED.get(k, k))) for i, (o, n) in enumerate(zip(old, new)) for k in o
                if o[k] != n.get(RENAMED.get(k, k))]
        if len(old) != len(new) or diff:
            bad += 1
            first = diff[0] if diff else None
            print(f"{key}: DIFFERENT ({len(old)} against {len(new)} rows; first difference {first})", flush=True)
        else:
            print(f"{key}: the same, {len(new)} rows bit for bit ({wall:.0f} s)", flush=True)
    if a.compare:
        print(f"{bad} scene(s) differ")
        sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
