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
time; differences against the 3D half model (the converged 3D reference is issue 12's item 2, not yet there).
The scenes run as shipped (the output error measure, tol 1.5e-2), fields off. Wall and CPU times are medians of
--repeats runs on a shared, loaded machine (2 cores, several users): read the CPU time.

Writes the section "## Indentation: 3D half model, sector and axisymmetric twin" of docs/performance.md.
Usage: bench/indent_models_bench.py [--repeats 2] [--models half,sector,hexhalf,mirrored,axi] [--no-table]
"""
import argparse
import re
import tempfile
from pathlib import Path

import numpy as np

from camclay9.performance_doc import replace_section
from camclay9.sector_mesh import mesh_sector, mirrored_half, msh41
from step_control_bench import absolute, outputs, run


ROOT = Path(__file__).resolve().parents[1]
TITLE = "## Indentation: 3D half model, sector and axisymmetric twin"
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
    ap.add_argument("--no-table", action="store_true")
    a = ap.parse_args()
    res = {}
    with tempfile.TemporaryDirectory() as d:
        tmp = Path(d)
        for m in a.models.split(","):
            label, text = MODELS[m]
            t = text(tmp)
            runs = [run(t, tmp / f"{m}{k}") for k in range(a.repeats)]
            o = outputs(runs[0]["hist"])
            res[m] = dict(label=label, o=o, steps=runs[0]["steps"], wall=np.median([r["wall"] for r in runs]),
                          cpu=np.median([r["cpu"] for r in runs]), n=len(runs))
            print(f"{m}: P = {o['load at end of loading']:.4f} uN, creep {o['creep depth'] * 1e3:.3f} nm, residual "
                  f"{o['residual depth'] * 1e3:.2f} nm, {runs[0]['steps']} steps, wall {res[m]['wall']:.1f} s, "
                  f"CPU {res[m]['cpu']:.1f} s", flush=True)
    ref = res.get("half")
    rows = []
    for m, r in res.items():
        o = r["o"]
        diff = (lambda k: f"{o[k] / ref['o'][k] - 1:+.1%}") if ref and m != "half" else (lambda k: "ref.")
        rows.append(f"| {r['label']} | {o['load at end of loading']:.2f} ({diff('load at end of loading')}) | "
                    f"{o['creep depth'] * 1e3:.2f} ({diff('creep depth')}) | {o['residual depth'] * 1e3:.1f} "
                    f"({diff('residual depth')}) | {r['steps']} | {r['wall']:.0f} / {r['cpu']:.0f} |")
    table = ("| model | P at h = 200 nm [µN] | creep depth [nm] | residual depth [nm] | steps | wall / CPU [s] |\n"
             "|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n")
    print(table)
    if a.no_table:
        return
    n = min(r["n"] for r in res.values())
    exact = ""
    if "sector" in res and "mirrored" in res:
        d = {k: abs(res["sector"]["o"][k] / res["mirrored"]["o"][k] - 1) for k in res["sector"]["o"]}
        exact = (f"- **The sector is exact for this scene.** Against the half model made of three mirror images of its mesh "
                 f"(tip held on the axis), it differs by {d['load at end of loading']:.0e} in P, "
                 f"{d['creep depth']:.0e} in the creep depth and {d['residual depth']:.0e} in the residual depth "
                 f"(the time-step control takes the same steps), at "
                 f"{res['sector']['cpu'] / res['mirrored']['cpu']:.2f} of its CPU time.\n")
    three = [m for m in ("sector", "hexhalf") if m in res]
    keys = next(iter(res.values()))["o"]
    spread = {k: max([abs(res[m]["o"][k] / ref["o"][k] - 1) for m in three] or [np.nan]) if ref else np.nan for k in keys}
    section = f"""{TITLE}

`bench/indent_models_bench.py` (issue 12, item 3): the nanoindentation on kerogen (Cam-Clay IX, φ = 0; load
to 200 nm, hold 60 s, unload in 20 s) as shipped (the output error measure, tol 1.5e-2), on each model,
against the 3D half model (the converged 3D answer and each model's error against it: "3D indentation: mesh
convergence and the cheapest model"). P is the indenter's whole load (the scenes' indenter.copies). Times: medians of {n} runs each on a shared,
loaded machine (2 cores, several users at once); the CPU time is the one to compare.

{table}
{exact}- **The 3D models' differences are their meshes'.** The cube, the hexagon's half and the sector are meshed
  independently with the same grading (the shipped sector's mesh parameters). P agrees within {spread['load at end of loading']:.1%} and the
  residual depth within {spread['residual depth']:.1%}, but the creep depth (a 10–14 nm difference of two depths near 200 nm) differs by
  up to {spread['creep depth']:.0%} from one mesh to the next: at h_tip 0.05 the 3D creep depth is not converged in the mesh,
  whatever the model. Its time-step error is smaller: the sector at tol 5e-3 instead of 1.5e-2 gives a creep
  depth 2.7 % larger (10.45 nm; P +0.5 %, measured once by hand). The sector makes the refinement that
  this needs about three times cheaper.
- **The axisymmetric twin** differs by the tip's shape (Berkovich against the cone of its projected area) and by
  the 3D meshes' stiffness (P1 tetrahedra this coarse are 10–15 % stiff, docs/contact.md); which is which is
  issue 12's item 2.
"""
    replace_section(TITLE, section)


if __name__ == "__main__":
    main()
