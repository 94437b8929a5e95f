#!/usr/bin/env python3
"""The loading-rate scenes as half models against the whole block (issue 32): each scene as shipped (the half x >= 0,
the mirror plane x = 0, indenter.copies 2) and on the whole block it is half of (camclay9.indent2d_study.whole_block),
on the same mesh parameters, fields as shipped, one rank, --repeats runs of each, --jobs at once. Per run: CPU (user +
system of the driver and its gmsh, from wait4), wall, unknowns, steps, UMAT calls, the depth at the end of loading
and the creep depth (indent_convergence_bench.run, as the mesh studies measure their rungs); these against the scene's converged 2D answer (the 2D mesh and element study's store,
docs/results/indent2d_convergence.json). Keeps every number in docs/results/half_model.json
(camclay9.half_model_study) and writes the section "2D indentation: the half model" of docs/performance.md from it.

    bench/half_model_bench.py [--scenes loading_rate_a1,...] [--repeats 3] [--jobs 2] [--out DIR] [--machine NOTE] [--no-doc]
"""
from pathlib import Path

from camclay9 import half_model_study as study
from camclay9 import indent2d_study as i2d
from camclay9 import results_store
from camclay9.performance_doc import publish
from indent_convergence_bench import repeat_args, repeat_provenance, repeated, run

ROOT = Path(__file__).resolve().parents[1]
SKEY = {name: k for k, (name, *_rest) in i2d.SCENES.items() if k in i2d.REFERENCE}   # scene -> the 2D study's key


def scene_text(scene, model):
    text = (ROOT / "input" / f"{scene}.yaml").read_text().replace("geometry: ../meshes/", f"geometry: {ROOT}/meshes/")
    assert i2d.half_model_scene(text), f"input/{scene}.yaml is not a half model"
    return text if model == "half" else i2d.whole_block(text)


def one_run(scene, model, k, out):
    """One run (indent_convergence_bench.run: CPU from wait4, its counts, its outputs): the store's row, cpu_s and
    wall_s as single values."""
    r = run(scene_text(scene, model), Path(out) / f"{scene}_{model}_{k}")
    row = {"scene": scene, "model": model, "unknowns": r["unknowns"], "steps": r["steps"], "umat_calls": r["umat_calls"],
           "cpu_s": r["cpu"], "wall_s": r["wall"], "h_max": r["o"]["depth at end of loading"], "creep": r["o"]["creep depth"]}
    print(f"{scene} {model} #{k}: CPU {row['cpu_s']:.1f} s, {row['unknowns']} unknowns, h_max {row['h_max']:.6g}, "
          f"creep {row['creep']:.6g}", flush=True)
    return row


def references(scenes):
    store = results_store.load(i2d.STORE, ROOT / "docs" / "results")
    out = {}
    for s in scenes:
        ref = i2d.reference(store["rungs"], SKEY[s]) if s in SKEY else None
        if not ref:
            raise SystemExit(f"{s}: no converged 2D answer in docs/results/{i2d.STORE}.json")
        out[s] = {"h_max": ref["h_max"]["value"], "creep": ref["creep"]["value"], "hw_h_max": ref["h_max"]["hw"],
                  "hw_creep": ref["creep"]["hw"], "from": f"{i2d.REFERENCE[SKEY[s]][0]} ({ref['creep']['rule']})"}
    return out


def main(argv=None):
    a = repeat_args(argv, __doc__.splitlines()[0], "loading_rate_a1", "half_model")
    scenes = a.scenes.split(",")
    ref = references(scenes)
    todo = [(s, m, k, a.out) for k in range(a.repeats) for s in scenes for m in ("whole", "half")]   # interleaved
    rows = repeated(todo, one_run, a.jobs, [(s, m) for s in scenes for m in ("half", "whole")], lambda r: (r["scene"], r["model"]),
                    ("creep",))
    store = {"provenance": repeat_provenance("half_model_bench.py", a), "reference": ref, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
