#!/usr/bin/env python3
"""The direct contact solve's package and the loading stage's step control, measured on shipped indentation scenes
(issue 32): each scene as shipped and as it was before (MUMPS; the loading steps relative to each step), and with UMFPACK
(METIS' ordering) alone, --repeats runs of each, --jobs at once, and one reference run at tol 5e-3 (the time-step reference
on the same mesh). Per run: CPU (user + system of the driver and its gmsh, from wait4), wall, the driver's counts and
the scene's outputs (indent_convergence_bench.run, as the mesh studies measure their rungs). Keeps every number in
docs/results/loading_steps.json (camclay9.loading_steps_study) and writes the section "Indentation: the direct solver
and the loading steps" of docs/performance.md from it.

    bench/loading_steps_bench.py [--scenes loading_rate_a1,nanoindent_kerogen_sector] [--repeats 3] [--jobs 2]
                                 [--out DIR] [--machine NOTE] [--no-doc]
"""
import json
import re
from pathlib import Path

from camclay9 import loading_steps_study as study
from camclay9.performance_doc import publish
from indent_convergence_bench import repeat_args, repeat_provenance, repeated, run
from step_control_bench import output_tol

ROOT = Path(__file__).resolve().parents[1]
STAGE = ", relative_to: stage"


def scene_text(scene, variant):
    """The scene's text for a variant (loading_steps_study.VARIANTS)."""
    text = (ROOT / "input" / f"{scene}.yaml").read_text().replace("geometry: ../meshes/", f"geometry: {ROOT}/meshes/")
    if STAGE not in text or re.search(r"^solver:", text, re.M):
        raise SystemExit(f"input/{scene}.yaml: expected its loading steps relative to the stage and no solver key")
    if variant in ("before", "UMFPACK"):   # the loading relative to each step, the package named whatever the default
        text = text.replace(STAGE, "")
        text += f'solver: {{options: "-indent_pc_factor_mat_solver_type {"mumps" if variant == "before" else "umfpack"}"}}\n'
    if variant == "reference":
        text = output_tol(text, 5e-3)
    return text


def one_run(scene, variant, k, out):
    r = run(scene_text(scene, variant), Path(out) / f"{scene}_{variant}_{k}")
    row = {"scene": scene, "variant": variant, "unknowns": r["unknowns"], "steps": r["steps"], "newton": r["newton"],
           "krylov": r["krylov"], "factorisations": r["factorisations"], "umat_calls": r["umat_calls"],
           "solve_s": r["solve_s"], "cpu_s": r["cpu"], "wall_s": r["wall"],
           "outputs": {o: r["o"][o] for o in study.OUTPUTS if o in r["o"]}}
    print(f"{scene} {variant} #{k}: CPU {row['cpu_s']:.1f} s, {row['steps']} steps, " +
          ", ".join(f"{o} {v:.6g}" for o, v in row["outputs"].items()), flush=True)
    return row


def main(argv=None):
    a = repeat_args(argv, __doc__.splitlines()[0], "loading_rate_a1,nanoindent_kerogen_sector", "loading_steps")
    scenes = a.scenes.split(",")
    variants = {s: ["before", "UMFPACK", "shipped"] for s in scenes}
    todo = [(s, "reference", 0, a.out) for s in scenes]
    todo += [(s, v, k, a.out) for k in range(a.repeats) for s in scenes for v in variants[s]]   # interleaved
    rows = repeated(todo, one_run, a.jobs, [(s, v) for s in scenes for v in study.VARIANTS], lambda r: (r["scene"], r["variant"]),
                    ("steps", "outputs"))
    (Path(a.out) / "rows.json").write_text(json.dumps(rows, indent=1))   # kept should the section fail
    store = {"provenance": repeat_provenance("loading_steps_bench.py", a), "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)

if __name__ == "__main__":
    main()
