#!/usr/bin/env python3
"""Time CalculiX with the Cam-Clay IX UMAT on the triaxial cylinder (issue #6 benchmark).

    python3 tools/calculix/bench_ccx.py [--repeat 3] [--core 8 --layers 16] [--threads 1 2]

Builds CalculiX with tools/calculix/build_ccx.sh if needed (CAMCLAY9_BUILD as there), writes the
theta = 0 cylinder of camclay9.calculix_inputs with the requested mesh into a temporary folder, runs it with
OMP_NUM_THREADS = 1 and 2, and prints a Markdown table: wall time per increment and per Newton
iteration (median over the repetitions; CalculiX's own "Total CalculiX Time"), and UMAT calls.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile

from camclay9 import calculix_inputs

HERE = os.path.dirname(os.path.abspath(__file__))


def run(exe, workdir, threads):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([exe, "-i", "cyl"], cwd=workdir, env=env, capture_output=True, text=True, check=True,
                         timeout=6 * 3600).stdout
    seconds = float(out.split("Total CalculiX Time:")[1].split()[0])
    with open(os.path.join(workdir, "cyl.sta")) as f:
        rows = [line.split() for line in f.readlines()[2:]]
    return seconds, len(rows), sum(int(r[3]) for r in rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--core", type=int, default=8, help="core elements per side of the O-grid")
    ap.add_argument("--layers", type=int, default=16, help="element layers along the axis")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2])
    a = ap.parse_args()
    r = subprocess.run(["bash", os.path.join(HERE, "build_ccx.sh")], capture_output=True, text=True, timeout=4 * 3600)
    if r.returncode != 0:
        sys.exit(r.stderr)
    exe = os.path.join(r.stdout.strip().splitlines()[-1], "ccx_camclay9")
    calculix_inputs.CORE, calculix_inputs.LAYERS = a.core, a.layers
    elements = a.layers * len(calculix_inputs.disk()[1])
    with tempfile.TemporaryDirectory() as wd:
        with open(os.path.join(wd, "cyl.inp"), "w") as f:
            f.write(calculix_inputs.cylinder(0))
        with open(os.path.join(wd, calculix_inputs.CYL_INIT), "w") as f:
            f.write(calculix_inputs.initial_stress(range(1, elements + 1), 8).split("TYPE=STRESS\n")[1])
        print(f"cylinder theta = 0, {elements} C3D8 ({8 * elements} integration points), {a.repeat} runs each\n")
        print("| threads | increments | Newton iterations | total s (median) | ms per increment | ms per iteration |")
        print("|---|---|---|---|---|---|")
        for t in a.threads:
            runs = [run(exe, wd, t) for _ in range(a.repeat)]
            s = statistics.median(x[0] for x in runs)
            _, incs, its = runs[0]
            print(f"| {t} | {incs} | {its} | {s:.2f} | {1e3 * s / incs:.1f} | {1e3 * s / its:.1f} |")


if __name__ == "__main__":
    main()
