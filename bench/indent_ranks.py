#!/usr/bin/env python3
"""The 3D indentation scenes on 1 and 2 ranks (issue 25, item 6; once a shell script): each shipped scene
as it is (fields as shipped), on one rank and on two (mpiexec), one run each: wall and CPU time (user + system of
mpiexec and the ranks) and the residual depth (the depth at the run's end), 2 ranks against 1 (relative). Keeps every
number in the results store docs/results/indent_ranks.json (camclay9.indent_ranks_study; full digits, with command,
date, the driver's commit and a machine note) and writes the section "3D indentation on 1 and 2 ranks" of
docs/performance.md from it, which tools/doc_numbers.py checks. Run it on an otherwise idle machine: the section
compares wall times.

    bench/indent_ranks.py [--scenes a,b] [--out DIR] [--machine NOTE] [--no-doc]
"""
import argparse
import time
from pathlib import Path

from camclay9 import DriverError, read_history, results_store, run_driver
from camclay9 import indent_ranks_study as study
from camclay9.performance_doc import publish

ROOT = Path(__file__).resolve().parents[1]
SCENES = "nanoindent_kerogen_sector,microindent_BN_sector,microindent_BP"


def one_run(scene, ranks, out):
    """One run of the shipped scene on `ranks` ranks: the store's row."""
    try:
        proc = run_driver(ROOT / "input" / f"{scene}.yaml", out, root=ROOT, ranks=ranks, timeout=3 * 3600)
    except DriverError as err:
        raise SystemExit(f"input/{scene}.yaml on {ranks} rank(s): the driver failed: {err}")
    row = {"scene": scene, "ranks": ranks, "wall_s": proc.wall, "cpu_s": proc.cpu,
           "h_res": float(read_history(out, need=("depth",))["depth"][-1])}
    print(f"{scene} on {ranks}: wall {row['wall_s']:.1f} s, CPU {row['cpu_s']:.1f} s, h_res {row['h_res']:.9g}", flush=True)
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scenes", default=SCENES)
    ap.add_argument("--out", default=str(ROOT / "out" / "indent_ranks"), help="the runs' folders (default: %(default)s)")
    ap.add_argument("--machine", default="2 cores, the machine otherwise idle",
                    help="the machine note the store and the section carry (default: %(default)s)")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    rows = [one_run(s, n, Path(a.out) / f"{s}_{n}") for s in a.scenes.split(",") for n in (1, 2)]
    for one, two in zip(rows[0::2], rows[1::2]):
        two["h_res_vs_1"] = two["h_res"] / one["h_res"] - 1
    rev = results_store.revision(ROOT)
    provenance = {"command": "bench/indent_ranks.py" + (f" --scenes {a.scenes}" if a.scenes != SCENES else ""),
                  "date": time.strftime("%Y-%m-%d", time.gmtime()), "rev": rev or "unknown", "machine": a.machine}
    store = {"provenance": provenance, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
