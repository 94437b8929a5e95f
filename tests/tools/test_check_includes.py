"""tools/check_includes.py: the driver's include graph follows its folders' order (issue 24), and the check fails on
an include that runs upward, on one between siblings and on camclay9.h outside material/ (a check that cannot
fail would prove nothing)."""
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TOOL = ROOT / "tools" / "check_includes.py"


def check(src):
    return subprocess.run([sys.executable, str(TOOL), str(src)], capture_output=True, text=True, timeout=600)


def test_driver_sources_follow_the_layers():
    r = check(ROOT / "driver" / "src")
    assert r.returncode == 0, r.stdout
    assert ", 0 against the layers" in r.stdout


def test_each_kind_of_violation_is_caught(tmp_path):
    src = tmp_path / "src"
    shutil.copytree(ROOT / "driver" / "src", src)
    bad = {"fe/fe_scene.h": '#include "../stepping/step_control.h"\n',      # upward
           "point/point_scene.h": '#include "../fe/fe_problem.h"\n',       # sibling
           "fe/fe_state.c": '#include "camclay9.h"\n'}                      # the contract outside material/
    for f, line in bad.items():
        p = src / f
        p.write_text(line + p.read_text())
    r = check(src)
    assert r.returncode == 1
    for f in bad:
        assert f.split("/")[1] in r.stdout, r.stdout
    assert ", 3 against the layers" in r.stdout
