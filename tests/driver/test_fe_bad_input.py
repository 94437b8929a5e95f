"""Bad FE scene input (issue #4): each case exits non-zero with its own message naming the file (and
the line and key where there is one), and leaves the files of an earlier run intact."""
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DRIVER = os.environ.get("DRIVER", str(ROOT / "build" / "bin" / "driver"))

GOOD = f"""scene: fe
name: bad
mesh: {{geometry: {ROOT}/meshes/box.geo, parameters: {{size: 0.6}}, order: 1}}
material: {{props: woodford}}
initial: {{stress: [-35, -35, -35, 0, 0, 0], pressure: {{z1: 35}}}}
boundary:
  fixed: [{{group: z0, components: [z]}}, {{group: x0, components: [x]}}, {{group: y0, components: [y]}}]
  pressure: [z1]
stages:
  - {{name: s, duration: 1, pressure: {{z1: 36}}, steps: {{count: 1}}}}
"""

CASES = [
    ("unknown key", ("name: bad", "name: bad\ncolour: red"), r"unknown key 'colour'"),
    ("wrong type", ("order: 1", "order: one"), r"key 'mesh.order': expected an integer, got 'one'"),
    ("order out of range", ("order: 1", "order: 3"), r"key 'mesh.order': expected 1 or 2, got 3"),
    ("missing mesh file", (f"geometry: {ROOT}/meshes/box.geo", "geometry: meshes/nothere.geo"),
     r"key 'mesh.geometry': cannot open 'meshes/nothere.geo' \(as '.*/meshes/nothere.geo': paths in a scene are relative to the scene file's folder\)"),
    ("two meshes", ("box.geo,", "box.geo, file: x.msh,"), r"give exactly one of geometry"),
    ("missing physical group", ("{group: x0, components: [x]}", "{group: left, components: [x]}"), r"group 'left' is not a physical group"),
    ("bad component", ("components: [x]}", "components: [w]}"), r"expected x, y or z"),
    ("negative modulus", ("material: {props: woodford}", "material: {props: woodford, set: {muT_hard: -5}}"), r"PROPS\(3\)"),
    ("phi out of range", ("material: {props: woodford}", "material: {props: woodford}\nphi: {mean: 1.5}"), r"key 'phi': expected 0 <= min <= mean <= max <= 1"),
    ("empty stage list", ("stages:\n  - {name: s, duration: 1, pressure: {z1: 36}, steps: {count: 1}}", "stages: []"), r"key 'stages': expected 1 to"),
    ("negative duration", ("duration: 1,", "duration: -1,"), r"key 'stages\[0\]\.duration': expected a duration > 0 .*, got -1"),
    ("pressure on an unlisted group", ("pressure: {z1: 36}", "pressure: {x1: 36}"), r"'stages\[0\]\.pressure\.x1': not a group listed"),
    ("initial stress length", ("stress: [-35, -35, -35, 0, 0, 0]", "stress: [-35, -35]"), r"expected a list of 6 numbers, got 2"),
    ("bad steps", ("steps: {count: 1}", "steps: {count: 0}"), r"count': expected >= 1"),
    ("missing boundary", ("boundary:", "boundaryx:"), r"unknown key 'boundaryx'|key 'boundary' is missing"),
    ("bad load", ("steps: {count: 1}}", "steps: {count: 1}, load: sudden}"), r"load': expected instant or linear"),
    ("YAML syntax", ("name: bad", "name: [bad"), r"YAML syntax error"),
]


@pytest.mark.parametrize("name, edit, expected", CASES, ids=[c[0] for c in CASES])
def test_bad_scene(tmp_path, name, edit, expected):
    import re
    out = tmp_path / "out"
    out.mkdir()
    earlier = out / "history.csv"
    earlier.write_text("an earlier run's output\n")
    text = GOOD.replace(*edit)
    assert text != GOOD, name
    scene = tmp_path / "scene.yaml"
    scene.write_text(text)
    proc = subprocess.run([DRIVER, "-input", str(scene), "-output_dir", str(out)], capture_output=True, text=True,
                          cwd=ROOT, timeout=600)
    message = proc.stdout + proc.stderr
    assert proc.returncode != 0, message
    assert re.search(expected, message), message
    assert str(scene) in message, message
    assert earlier.read_text() == "an earlier run's output\n"


def test_unwritable_output(tmp_path):
    scene = tmp_path / "scene.yaml"
    scene.write_text(GOOD)
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    proc = subprocess.run([DRIVER, "-input", str(scene), "-output_dir", str(blocker / "sub")], capture_output=True,
                          text=True, cwd=ROOT, timeout=600)
    assert proc.returncode != 0 and ("cannot create" in proc.stdout + proc.stderr
                                     or "the output path is a file" in proc.stdout + proc.stderr)
