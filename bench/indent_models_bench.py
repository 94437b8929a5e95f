#!/usr/bin/env python3
"""Nanoindentation on kerogen (Cam-Clay IX, phi = 0) on three models of the same scene (issue 12, item 3):
the 3D Berkovich half model (input/nanoindent_kerogen.yaml, a 2 um cube), the 60-degree sector
(input/nanoindent_kerogen_sector.yaml, a hexagonal prism of apothem 1 um) and the axisymmetric cone twin
(input/nanoindent_kerogen_axi.yaml, a cylinder of radius 1 um); and the half of the sector's hexagonal prism
(the sector scene with span 180: three sectors, meshed on their own), which separates the sector's reduction
from the change of the block's shape; and that half meshed as three mirror images of the sector's mesh, its tip
held on the axis (the sector's exact counterpart: the same elements).

Reported: the load at the end of loading (h = 200 nm, the indenter's whole load: the scenes say indenter.copies),
the creep depth over the 60 s hold, the residual depth after unloading, steps, wall and CPU
time; differences against the 3D half model (each model against the converged 3D answer: bench/indent_convergence_bench.py).
The scenes run as shipped (the output error measure, tol 1.5e-2), fields off. Wall and CPU times are medians of
--repeats runs on a shared, loaded machine (2 cores, several users): read the CPU time.

Writes its numbers into the results store docs/results/indent_models.json and the section "## Indentation: 3D half
model, sector and axisymmetric twin" of docs/performance.md from it (camclay9.indent_models_study; tools/doc_numbers.py
checks the section against the store).
Usage: bench/indent_models_bench.py [--repeats 2] [--models half,sector,hexhalf,mirrored,axi] [--no-doc]
"""
import argparse
import re
import tempfile
import time
from pathlib import Path

import numpy as np

from camclay9 import results_store
from camclay9 import indent_models_study as study
from camclay9.performance_doc import replace_section
from camclay9.sector_mesh import mesh_sector, mirrored_half, msh41
from step_control_bench import absolute, outputs, run


ROOT = Path(__file__).resolve().parents[1]
S3 = "0.8660254037844386"


def scene(name):
    return absolute((ROOT / "input" / f"{name}.yaml").read_text())


def hex_half():
    """The sector scene on the whole half x >= 0 of its hexagonal prism: mirror x = 0, rollers on three faces."""
    t = scene("nanoindent_kerogen_sector").replace("span: 60", "span: 180").replace("copies: 6", "copies: 2")
    mirrors = (f"  mirror:\n    - {{group: mirror_a, normal: [1, 0, 0]}}\n    - {{group: mirror_b, normal: [1, 0, 0]}}\n"
               f"    - {{group: side1, normal: [0.5, -{S3}, 0]}}\n    - {{group: side2, normal: [1, 0, 0]}}\n"
               f"    - {{group: side3, normal: [0.5, {S3}, 0]}}\n")
    return re.sub(r"  mirror:\n(    - .*\n)+", mirrors, t)


def mirrored(tmp):
    """The half model meshed as three mirror images of the sector's mesh (the shipped sector's parameters), its
    tip held in x and y (docs/contact.md, "The Berkovich's edges and apex"): the sector's reference on its own
    elements."""
    text = scene("nanoindent_kerogen_sector")
    par = dict(kv.split(": ") for kv in re.search(r"parameters: \{([^}]*)\}", text).group(1).split(", "))
    sector = mesh_sector(tmp / "sector.msh", ROOT, **par)
    half = mirrored_half(sector, tmp / "half.msh")
    t = re.sub(r"  geometry: \S+indent_sector.geo\n  parameters: \{[^}]*\}\n", f"  file: {msh41(half)}\n",
               text).replace("copies: 6", "copies: 2")
    mirrors = (f"  fixed:\n    - {{group: bottom, components: [x, y, z]}}\n    - {{group: tip, components: [x, y]}}\n"
               f"  mirror:\n    - {{group: x0, normal: [1, 0, 0]}}\n    - {{group: side_m60, normal: [0.5, -{S3}, 0]}}\n"
               f"    - {{group: side_0, normal: [1, 0, 0]}}\n    - {{group: side_60, normal: [0.5, {S3}, 0]}}\n")
    return re.sub(r"  fixed:\n    - .*\n  mirror:\n(    - .*\n)+", mirrors, t)


MODELS = {  # name: (label, scene text); the scenes say indenter.copies: their loads are the indenter's whole load
    "half": ("3D half model (cube), as shipped", lambda tmp: scene("nanoindent_kerogen")),
    "sector": ("60° sector (hexagon), as shipped", lambda tmp: scene("nanoindent_kerogen_sector")),
    "hexhalf": ("half of the sector's hexagon, meshed on its own", lambda tmp: hex_half()),
    "mirrored": ("half of the hexagon, three mirrored sector meshes, tip held", mirrored),
    "axi": ("axisymmetric cone 70.3° (cylinder), as shipped", lambda tmp: scene("nanoindent_kerogen_axi")),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--models", default="half,sector,hexhalf,mirrored,axi")
    ap.add_argument("--no-doc", action="store_true", help="print only; leave the store and docs/performance.md")
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for m in a.models.split(","):
            label, text = MODELS[m]
            t = text(tmp)
            runs = [run(t, tmp / f"{m}{k}") for k in range(a.repeats)]
            o = outputs(runs[0]["hist"])
            rows.append(dict(model=m, label=label, P=float(o["load at end of loading"]), creep=float(o["creep depth"]) * 1e3,
                             h_res=float(o["residual depth"]) * 1e3, steps=runs[0]["steps"],
                             wall=float(np.median([r["wall"] for r in runs])), cpu=float(np.median([r["cpu"] for r in runs]))))
            print(f"{m}: P = {rows[-1]['P']:.4f} uN, creep {rows[-1]['creep']:.3f} nm, residual {rows[-1]['h_res']:.2f} nm, "
                  f"{rows[-1]['steps']} steps, wall {rows[-1]['wall']:.1f} s, CPU {rows[-1]['cpu']:.1f} s", flush=True)
    rev = results_store.revision(ROOT)
    command = "bench/indent_models_bench.py" + (f" --repeats {a.repeats}" if a.repeats != 2 else "") + (
        f" --models {a.models}" if a.models != ap.get_default("models") else "")
    store = {"provenance": {"command": command, "date": time.strftime("%Y-%m-%d"), "rev": rev, "repeats": a.repeats}, "rows": rows}
    section = study.section(store)
    print(section)
    if not a.no_doc:
        results_store.save(study.STORE, store)
        replace_section(study.TITLE, section)


if __name__ == "__main__":
    main()
