"""tools/check_includes.py: the driver's include graph follows its folders' order (issue 24) and its files depend on
one another without a cycle (issue 35), and the check fails on an include that runs upward, on one between siblings,
on camclay9.h outside material/, and on a cycle of calls behind one shared header or of headers (a check that cannot
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
    assert ", 0 dependency cycles" in r.stdout


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


def test_cycles_are_caught(tmp_path):
    """Main's calibration had it: one header declared the functions of several files, so their includes made no
    cycle while their calls did (calibrate.c called cal_report, calibrate_report.c called cal_dparam)."""
    src = tmp_path / "src"
    shutil.copytree(ROOT / "driver" / "src", src)
    files = {"io/cyc.h": "int cyc_a(int n);\nint cyc_b(int n);\n",              # one header for two sources
             "io/cyc_a.c": '#include "cyc.h"\nint cyc_a(int n) { return n ? cyc_b(n - 1) : 0; }\n',
             "io/cyc_b.c": '#include "cyc.h"\nint cyc_b(int n) { return n ? cyc_a(n - 1) : 1; }\n',
             "scene/cyc_x.h": '#include "cyc_y.h"\n',                            # headers that include each other
             "scene/cyc_y.h": '#include "cyc_x.h"\n'}
    for f, text in files.items():
        (src / f).write_text(text)
    r = check(src)
    assert r.returncode == 1, r.stdout
    assert ", 0 against the layers" in r.stdout and ", 2 dependency cycles" in r.stdout, r.stdout
    assert "cycle: io/cyc_a.c -> io/cyc_b.c -> io/cyc_a.c" in r.stdout, r.stdout
    assert "io/cyc_a.c calls cyc_b (io/cyc_b.c)" in r.stdout and "io/cyc_b.c calls cyc_a (io/cyc_a.c)" in r.stdout
    assert "cycle: scene/cyc_x.h -> scene/cyc_y.h -> scene/cyc_x.h" in r.stdout, r.stdout
    (src / "io/cyc_b.c").write_text('#include "cyc.h"\nint cyc_b(int n) { return n; }\n')  # one way only: no cycle
    r = check(src)
    assert ", 1 dependency cycles" in r.stdout and "io/cyc_a.c ->" not in r.stdout, r.stdout
