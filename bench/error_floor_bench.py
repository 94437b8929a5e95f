#!/usr/bin/env python3
"""The output measure's floor (steps.error.floor, docs/driver.md "Error measures") on shipped indentation scenes: each
scene as shipped (no floor) and with the floor in every stage the output measure controls, --repeats runs of each,
--jobs at once, and one reference run at tol 5e-3 (the time-step reference on the same mesh). Per run: CPU (user +
system of the driver and its gmsh, from wait4), wall, the driver's counts and the scene's outputs
(indent_convergence_bench.run). Keeps every number in docs/results/error_floor.json (camclay9.error_floor_study) and
writes the section "Time-step error: the floor" of docs/performance.md from it.

    bench/error_floor_bench.py [--scenes loading_rate_a10] [--repeats 3] [--jobs 2] [--out DIR] [--machine NOTE] [--no-doc]
"""
import json
import re
from pathlib import Path

from camclay9 import error_floor_study as study
from camclay9 import read_summary
from camclay9.performance_doc import publish
from indent_convergence_bench import repeat_args, repeat_provenance, repeated, run
from step_control_bench import output_tol

ROOT = Path(__file__).resolve().parents[1]
ERROR = re.compile(r"error: \{measure: output, ([^}]*)\}")
FLOOR = 1e-3   # the floor measured (docs/driver.md: of the stage's change so far)


def scene_text(scene, variant, floor):
    """The scene's text for a variant (error_floor_study.VARIANTS)."""
    text = (ROOT / "input" / f"{scene}.yaml").read_text().replace("geometry: ../meshes/", f"geometry: {ROOT}/meshes/")
    if "floor:" in text or not ERROR.search(text):
        raise SystemExit(f"input/{scene}.yaml: expected the output measure and no floor")
    if variant == "floor":
        text = ERROR.sub(lambda m: f"error: {{measure: output, {m.group(1)}, floor: {floor:g}}}", text)
    if variant == "reference":
        text = output_tol(text, 5e-3)
    return text


def one_run(scene, variant, floor, k, out):
    path = Path(out) / f"{scene}_{variant}_{k}"
    r = run(scene_text(scene, variant, floor), path)
    c = read_summary(path)["counters"]
    row = {"scene": scene, "variant": variant, "steps": r["steps"], "newton": r["newton"], "rejected": c["rejected_by_error"],
           "stalled": c["rejected_stalled"], "umat_calls": r["umat_calls"], "cpu_s": r["cpu"], "wall_s": r["wall"],
           "outputs": {o: r["o"][o] for o in study.OUTPUTS if o in r["o"]}}
    print(f"{scene} {variant} #{k}: CPU {row['cpu_s']:.1f} s, {row['steps']} steps, " +
          ", ".join(f"{o} {v:.6g}" for o, v in row["outputs"].items()), flush=True)
    return row


def main(argv=None):
    floor = FLOOR
    a = repeat_args(argv, __doc__.splitlines()[0], "loading_rate_a10", "error_floor")
    scenes = a.scenes.split(",")
    todo = [(s, "reference", floor, 0, a.out) for s in scenes]
    todo += [(s, v, floor, k, a.out) for k in range(a.repeats) for s in scenes for v in ("shipped", "floor")]
    rows = repeated(todo, one_run, a.jobs, [(s, v) for s in scenes for v in study.VARIANTS], lambda r: (r["scene"], r["variant"]),
                    ("steps", "outputs"))
    (Path(a.out) / "rows.json").write_text(json.dumps(rows, indent=1))   # kept should the section fail
    store = {"provenance": repeat_provenance("error_floor_bench.py", a), "floor": floor, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
