"""Bad input refused when the scene is read, and options before anything runs (issue 35, items 1 and 2): each case
exits with status 2, its first line of stderr names the scene file, the line, the key and its value (or the option,
its value and its range), and the earlier run's results in the output directory stay byte for byte. Each case failed
on the driver before (noted at the case).

Conditions across keys and sections:
- material.bedding_angle 30 (or a normal with a radial part) in an axisymmetric scene with a hard frame (before: it
  ran to the end: the problem is not axisymmetric);
- output.times in a point scene's segment (before: accepted and ignored, exit 0);
- a stage with both indenter.until and until (before: refused only when that stage began, after the earlier stages
  ran, exit 1, no line), refused before the first stage;
- a key of one scene kind in another (control in an FE stage, pressure in a point segment: before, "unknown key");
- steps.max below steps.min, with min's value (before: "expected >= min, got 1").
Options, each with its range, checked before the run and named in every message about it:
- -indent_ksp_rtol 0, 1 and -1 (before: 0 ended in "the linear solver failed"; 1 was silently unused on fixed steps;
  -1 gave PETSc's "Relative tolerance -1. must be non-negative" and a warning about -indent_mat_mumps_icntl_14);
- -step_alpha and -step_beta, each by its own range, and beta below alpha (before: one message for both);
- an option the driver sets as a default (-indent_mat_mumps_icntl_14) is never reported as given but unused.
"""
import os
import re
import subprocess
from pathlib import Path

import pytest

from test_input_classes import BOX, DRIVER, DRIVER_ELASTIC, ROOT  # the elastic box scene and the drivers, named once
from test_input_classes import earlier  # noqa: F401  (the fixture: an earlier run's results, its own per module)

CONE = f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_block2d.geo
  parameters: {{W: 2, H: 2, half: 1, h_tip: 0.1, h_far: 0.4, r_fine: 0.4, r_contact: 0.9}}
  kinematics: axisymmetric
material:
  props: woodford
  set: {{phi: 0.5}}
  bedding_angle: 0
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {{shape: cone, half_angle: 70.3, contact: contact}}
stages:
  - {{name: load, duration: 10, indenter: {{load: 20}}, steps: {{count: 2}}}}
"""

POINT = """scene: point
material: {props: woodford, bedding_angle: 0}
initial: {stress: [-35, -35, -35, 0, 0, 0]}
segments:
  - name: load
    duration: 10
    control: {33: {strain: -0.001}, others: {stress: -35}}
    steps: {count: 2}
"""


def bad(earlier, text, args=(), exe=None):
    """Run a bad scene into the earlier run's directory: exit 2, the project's message first, nothing touched."""
    tmp, out, files = earlier
    scene = tmp / "bad.yaml"
    scene.write_text(text)
    proc = subprocess.run([exe or DRIVER_ELASTIC, "-input", str(scene), "-output_dir", str(out), *args], capture_output=True, text=True,
                          timeout=300)
    first = proc.stderr.splitlines()[0] if proc.stderr else ""
    print(f"exit {proc.returncode}: {first}")
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert first.startswith("driver: ") and "Traceback" not in proc.stderr, proc.stderr
    assert {n: (out / n).read_bytes() for n in files} == files, "an earlier result was changed"
    assert not list(out.glob("*.part")) and not list(out.glob("*.part.*")), "the bad run wrote files"
    return first, proc.stderr


def line_of(text, word):
    return next(i for i, l in enumerate(text.splitlines(), 1) if word in l)


@pytest.mark.parametrize("material,key,value", [
    ("bedding_angle: 30", "material.bedding_angle", "30"),
    ("bedding_angle: 90", "material.bedding_angle", "90"),
    ("normal: [1, 1, 0]", "material.normal", r"\[1, 1, 0\]"),
])
def test_axisymmetric_bedding(earlier, material, key, value):
    """An axisymmetric Cam-Clay IX body with a hard frame whose bedding normal has a radial part: not the problem
    stated (main: it ran to the end)."""
    text = CONE.replace("bedding_angle: 0", material)
    first, _ = bad(earlier, text, exe=DRIVER)
    line = line_of(text, material.split(":")[0] + ":")
    assert re.search(rf"bad\.yaml:{line}: key '{re.escape(key)}': {value} in an axisymmetric scene \(mesh\.kinematics: axisymmetric, "
                     rf"line 5\): the bedding normal \[[-0-9.e, ]+\] does not lie along the axis", first), first


def test_axisymmetric_bedding_by_option(earlier):
    """The normal given by -material_set: the option named."""
    first, _ = bad(earlier, CONE.replace("  bedding_angle: 0\n", ""), ["-material_set", "n1=1,n2=0,n3=0"], exe=DRIVER)
    assert re.search(r"option -material_set \(scene \S*bad\.yaml\): the normal n1, n2, n3 = 1, 0, 0 in an axisymmetric scene", first), first


def test_point_segment_has_no_output_times(earlier):
    """A point scene writes no fields: its segment's output.times was accepted and ignored (main: exit 0)."""
    text = POINT.replace("    steps: {count: 2}\n", "    steps: {count: 2}\n    output: {times: [5]}\n")
    first, _ = bad(earlier, text, exe=DRIVER)
    assert re.search(rf"bad\.yaml:{line_of(text, 'output:')}: key 'segments\[0\]\.output' is a key of fe scenes, not of point scenes "
                     r"\(output: fields at chosen stage times\): allowed keys here are name, duration, load, creep, steps, until, "
                     r"control, constraints, axis, table", first), first


def test_keys_of_another_scene_kind(earlier):
    first, _ = bad(earlier, BOX.replace("steps: {count: 2}}", "steps: {count: 2}, control: {others: {stress: 0}}}"))
    assert re.search(r"bad\.yaml:8: key 'stages\[0\]\.control' is a key of point scenes, not of fe scenes", first), first
    first, _ = bad(earlier, POINT.replace("    steps: {count: 2}\n", "    steps: {count: 2}\n    pressure: {top: 1}\n"), exe=DRIVER)
    assert re.search(r"bad\.yaml:9: key 'segments\[0\]\.pressure' is a key of fe scenes, not of point scenes", first), first
    first, _ = bad(earlier, POINT + "boundary: {fixed: []}\n", exe=DRIVER)
    assert re.search(r"bad\.yaml:9: key 'boundary' is a key of fe scenes, not of point scenes", first), first


def test_two_end_events_refused_before_the_first_stage(earlier):
    """Stage 1 with both indenter.until and until: refused when the scene is read, before stage 0 runs (main: after
    stage 0 ran, exit 1, and the earlier run's history was replaced)."""
    text = CONE + ("  - {name: more, duration: 10, indenter: {load: 30, until: {load: 25}}, until: {q_above: 1},\n"
                   "     steps: {count: 2}}\n")
    first, _ = bad(earlier, text, exe=DRIVER)
    assert re.search(rf"bad\.yaml:{line_of(text, 'name: more')}: key 'stages\[1\]\.indenter\.until': load 25, and the stage's until "
                     rf"\(line {line_of(text, 'name: more')}\) q_above 1: give one end event, not both", first), first


@pytest.mark.parametrize("steps,message", [
    ("{adaptive: true, min: 2, max: 1}", r"key 'stages\[0\]\.steps\.max': expected >= min \(2\), got 1"),
    ("{adaptive: true, max: 1.0e-13}", r"key 'stages\[0\]\.steps\.max': expected >= min \(1e-12, its default 1e-12 max\(duration, 1\)\), "
                                       r"got 1e-13"),
])
def test_max_below_min_gives_min(earlier, steps, message):
    first, _ = bad(earlier, BOX.replace("{count: 2}", steps))
    assert re.search(r"bad\.yaml:8: " + message, first), first


@pytest.mark.parametrize("args,message", [
    (["-indent_ksp_rtol", "0"], r"option -indent_ksp_rtol 0: expected a number > 0 and < 1"),
    (["-indent_ksp_rtol", "1"], r"option -indent_ksp_rtol 1: expected a number > 0 and < 1"),
    (["-indent_ksp_rtol", "-1"], r"option -indent_ksp_rtol -1: expected a number > 0 and < 1"),
    (["-indent_rtol", "0"], r"option -indent_rtol 0: expected a number > 0 and < 1"),
    (["-step_alpha", "3"], r"option -step_alpha 3: expected a number > 0 and <= 2"),
    (["-step_alpha", "0"], r"option -step_alpha 0: expected a number > 0 and <= 2"),
    (["-step_beta", "-0.1"], r"option -step_beta -0\.1: expected a number >= 0 and < 2"),
    (["-step_alpha", "0.4", "-step_beta", "0.5"], r"option -step_beta 0\.5: expected a number below -step_alpha \(0\.4\): the controller would not damp "
     r"the steps' ratio"),
    (["-indent_check_tangent_part", "v"], r"option -indent_check_tangent_part v: expected one of all, u, r, lambda"),
])
@pytest.mark.parametrize("scene", ["box", "cone"])
def test_option_ranges_before_the_run(earlier, args, message, scene):
    """Each option by its own range, before the scene is read (an FE box and an indentation alike); no other option
    named (main: -indent_ksp_rtol -1 warned about -indent_mat_mumps_icntl_14, which the user never gave)."""
    first, stderr = bad(earlier, BOX if scene == "box" else CONE, args, exe=DRIVER_ELASTIC if scene == "box" else DRIVER)
    assert re.search("^driver: " + message + "; nothing was run$", first), first
    assert "mumps" not in stderr and "PETSc" not in stderr, stderr


def test_driver_defaults_are_not_reported_as_unused(tmp_path):
    """A run that stops before its first solve (-max_steps 0) leaves the driver's own default
    -indent_mat_mumps_icntl_14 unread: not a warning about an option the user gave (main: warned)."""
    scene = tmp_path / "cone.yaml"
    scene.write_text(CONE.replace("set: {phi: 0.5}", "set: {phi: 0}"))
    proc = subprocess.run([DRIVER, "-input", str(scene), "-output_dir", str(tmp_path / "out"), "-max_steps", "0", "-indent_ksp_rtol", "1e-3",
                           "-snes_tpyo", "x"], capture_output=True, text=True, timeout=300)
    print(proc.stderr)
    assert proc.returncode == 0, proc.stderr
    assert "mumps" not in proc.stderr, proc.stderr
    assert re.search(r"warning: option -snes_tpyo x was given but never used", proc.stderr), proc.stderr  # the user's: still warned
