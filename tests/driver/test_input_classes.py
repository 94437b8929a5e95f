"""Bad input refused as classes (issue 23), each with its exit status, its message (the scene file or the
option, the key path, the value) and the earlier run's results in the output directory untouched byte for
byte:

- integers that do not fit their key or option are refused, not cut: -max_steps 4294967297 (32-bit wrap: it
  ran 1 step), steps.count, output.fields_every, -indent_max_it outside 1 to 10000;
- a misspelt option of the driver's stops the run before it starts (-checkpoint_evry), also in a scene's
  solver.options; a bad value of one of its options names the option;
- key paths name the key whose value is wrong (stages[0].steps.count, not stages[0].steps), an unknown word
  under indenter.until is named, -material_set names itself when the UMAT refuses its value, a run-time stage
  error names the scene file and the key;
- every group is checked against what its key needs: a mirror plane on a volume group (it ran, holding every
  node of the volume), a pressure on a point group, fixed components on a volume group.
"""
import os
import re
import subprocess
from pathlib import Path

import pytest
from camclay9 import run_driver

ROOT = Path(__file__).resolve().parents[2]
DRIVER = os.environ.get("DRIVER", str(ROOT / "build" / "bin" / "driver"))
DRIVER_ELASTIC = str(Path(DRIVER).parent / "driver_elastic")

BOX = f"""scene: fe
mesh: {{geometry: {ROOT}/meshes/box.geo, parameters: {{size: 0.6}}}}
material: {{umat: elastic, props: [1000, 0.25], nstatv: 0}}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}, {{group: z0, components: [z]}}]
  pressure: [z1]
stages:
  - {{name: load, duration: 1, pressure: {{z1: 2}}, steps: {{count: 2}}}}
"""

CONE = f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_block2d.geo
  parameters: {{W: 2, H: 2, half: 1, h_tip: 0.1, h_far: 0.4, r_fine: 0.4, r_contact: 0.9}}
  kinematics: axisymmetric
material: {{props: woodford, set: {{phi: 0}}}}
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {{shape: cone, half_angle: 70.3, contact: contact}}
stages:
  - {{name: load, duration: 10, indenter: {{load: 20, until: {{depth: 0.05}}}}, steps: {{count: 2}}}}
"""


@pytest.fixture(scope="module")
def earlier(tmp_path_factory):
    """An earlier run's results: every bad run below writes into this directory and must leave them."""
    tmp = tmp_path_factory.mktemp("classes")
    out = tmp / "out"
    scene = tmp / "good.yaml"
    scene.write_text(BOX)
    run_driver(scene, out, driver=DRIVER_ELASTIC, timeout=600)  # DriverError: the good run failed
    files = {f.name: f.read_bytes() for f in out.iterdir() if f.name in ("history.csv", "fields.h5", "fields.xmf", "mesh.msh")}
    assert len(files) == 4
    return tmp, out, files


def bad(earlier, text, args=(), status=2, exe=None, name="bad"):
    tmp, out, files = earlier
    scene = tmp / f"{name}.yaml"
    scene.write_text(text)
    proc = subprocess.run([exe or DRIVER_ELASTIC, "-input", str(scene), "-output_dir", str(out), *args], capture_output=True, text=True,
                          timeout=300)
    first = proc.stderr.splitlines()[0] if proc.stderr else ""
    print(f"exit {proc.returncode}: {first}")
    assert proc.returncode == status, proc.stdout + proc.stderr
    assert first.startswith("driver: ") and "Traceback" not in proc.stderr, proc.stderr
    assert {n: (out / n).read_bytes() for n in files} == files, "an earlier result was changed"
    return first


INTEGERS = [
    ((), ["-max_steps", "4294967297"], r"option -max_steps 4294967297: expected an integer >= -1 \(at most 2147483647\)"),
    (("count: 2", "count: 4294967297"), [], r"bad\.yaml:\d+: key 'stages\[0\]\.steps\.count': expected an integer from -2147483648 to 2147483647, got '4294967297'"),
    (("steps: {count: 2}}", "steps: {count: 2}}\noutput: {fields_every: -3}"), [],
     r"bad\.yaml:\d+: key 'output\.fields_every': expected an integer >= 0 \(at most 2147483647\), got '-3'"),
    ((), ["-checkpoint_every", "99999999999"], r"option -checkpoint_every 99999999999: expected an integer >= 0"),
    ((), ["-indent_max_it", "0"], r"option -indent_max_it 0: expected an integer from 1 to 10000"),
]


@pytest.mark.parametrize("edit,args,message", INTEGERS)
def test_integers_are_range_checked(earlier, edit, args, message):
    text = BOX.replace(*edit) if edit else BOX
    assert re.search(message, bad(earlier, text, args))


OPTIONS = [
    (["-checkpoint_evry", "3"], BOX, r"option -checkpoint_evry: not an option of the driver \(misspelt -checkpoint_every\?\); nothing was run"),
    (["-indent_rtl", "1e-8"], BOX, r"option -indent_rtl: not an option of the driver \(misspelt -indent_rtol\?\)"),
    (["-fe_predictor", "maybe"], BOX, r"option -fe_predictor maybe: expected true or false"),
    (["-indent_solver", "lu"], BOX, r"option -indent_solver lu: expected one of direct, fieldsplit, auto"),
    (["-indent_rtol", "small"], BOX, r"option -indent_rtol small: expected a finite number"),
    ([], BOX + "solver: {options: '-snes_rtol 1e-9 -fe_refactor_itts 3'}\n",
     r"bad\.yaml: key 'solver\.options': option -fe_refactor_itts: not an option of the driver \(misspelt -fe_refactor_its\?\)"),
]


@pytest.mark.parametrize("args,text,message", OPTIONS)
def test_driver_options_are_checked_before_the_run(earlier, args, text, message):
    assert re.search(message, bad(earlier, text, args))


def test_key_paths_and_values(earlier):
    first = bad(earlier, BOX.replace("count: 2", "count: two"))
    assert re.search(r"bad\.yaml:\d+: key 'stages\[0\]\.steps\.count': expected an integer, got 'two'", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, error: {measure: output, tol: abc}}"))
    assert re.search(r"key 'stages\[0\]\.steps\.error\.tol': expected a finite number, got 'abc'", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, error: {measure: output, tol: 0.1, relative_to: all}}"))
    assert re.search(r"key 'stages\[0\]\.steps\.error\.relative_to': expected step or stage, got 'all'", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, error: {measure: volume, tol: 0.1, relative_to: stage}}"))
    assert re.search(r"key 'stages\[0\]\.steps\.error\.relative_to': only the output measure takes it \(this one is volume\)", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, error: {measure: volume, tol: 0.1, floor: 1e-3}}"))
    assert re.search(r"key 'stages\[0\]\.steps\.error\.floor': only the output measure takes it \(this one is volume\)", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, error: {measure: output, tol: 0.1, floor: 1}}"))
    assert re.search(r"key 'stages\[0\]\.steps\.error\.floor': expected 0 <= floor < 1, got 1", first)
    first = bad(earlier, BOX.replace("steps: {count: 2}", "steps: {adaptive: true, first: zero}"))
    assert re.search(r"key 'stages\[0\]\.steps\.first': expected a finite number, got 'zero'", first)
    first = bad(earlier, CONE.replace("until: {depth: 0.05}", "until: {force: 3}"), exe=DRIVER)
    assert re.search(r"unknown key 'stages\[0\]\.indenter\.until\.force': allowed keys here are depth, load", first)
    first = bad(earlier, CONE, ["-material_set", "phi=1.5"], exe=DRIVER)
    assert re.search(r"^driver: option -material_set: phi=1\.5 \(scene .*bad\.yaml\): .*PROPS\(1\)", first)


def test_run_time_stage_error_names_the_scene(tmp_path):
    """The load ramp to 20 ends before the depth 0.5 is reached: a run-time error (exit 1) naming the scene file
    and the key of the event. Its first step was done, so its own files are in place (the rule: a run replaces an
    earlier run's results once it has results of its own): a directory of its own here."""
    scene = tmp_path / "deep.yaml"
    scene.write_text(CONE.replace("until: {depth: 0.05}", "until: {depth: 0.5}"))
    proc = subprocess.run([DRIVER, "-input", str(scene), "-output_dir", str(tmp_path / "out")], capture_output=True, text=True, timeout=300)
    first = proc.stderr.splitlines()[0]
    print(f"exit {proc.returncode}: {first}")
    assert proc.returncode == 1 and re.search(r"^driver: \S*deep\.yaml: key 'stages\[0\]\.indenter\.until\.depth': stage 'load': depth = "
                                              r"0\.5 \(until\) was not reached", first), proc.stderr


GROUPS = [
    (("pressure: [z1]", "pressure: [z1]\n  mirror: [{group: body, normal: [1, 0, 0]}]"),
     r"key 'boundary\.mirror\[0\]\.group': the group 'body' is a group of 3D cells \(a gmsh Physical Volume\): a mirror plane needs a "
     r"group of faces on the body's boundary"),
    (("pressure: [z1]", "pressure: [z1, origin]"),
     r"key 'boundary\.pressure\[1\]': the group 'origin' is a group of points: a pressure needs a group of faces"),
    (("{group: z0, components: [z]}", "{group: body, components: [z]}"),
     r"key 'boundary\.fixed\[2\]\.group': the group 'body' is a group of 3D cells .*: fixed components act on points, edges or faces"),
]


@pytest.mark.parametrize("edit,message", GROUPS)
def test_groups_against_their_keys(earlier, edit, message):
    first = bad(earlier, BOX.replace(*edit))
    assert re.search(r"bad\.yaml:\d+: " + message, first), first
