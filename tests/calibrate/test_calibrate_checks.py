"""Issues 22 and 23: the checks that catch a wrong fit at its end (a parameter at a bound: an error unless
accepted; a failed full-model run), a curve of two cycles without a stage column, and the indentation table load
(a table of two rows is the ramp, to rounding), with its errors. The checks at the start (data rows outside the
forward run or in a block of another kind, a data scale a factor of 10 from the forward run's, zero or negative
factors and weights, the calibrate errors of issue 23) are test_calibrate.py's BAD and LAB_BAD. The fits here are
the shipped nano example's (nano_fast, about 1 s a run); about 25 s in all."""
import csv
import re
import subprocess

import pytest
import yaml
from camclay9 import run_driver

from test_calibrate import CAL, DRIVER, bad_scene, lab_scene, run

MESHES = CAL.parents[1] / "meshes"

def test_parameter_at_bound(tmp_path):
    """Bounds that exclude the truth (1.3e10): the fit ends at min; an error naming the bound, fit.yaml written; with
    accept: [bound] a warning and exit 0."""
    r = run(bad_scene(tmp_path, "min: 1.0e9", "min: 2.0e10"), tmp_path / "out")
    assert r.returncode == 1
    assert re.search(r"bad.yaml:\d+: key 'parameters\[0\].min': eta_soft ended at its bound min = 2e\+10: the data want a "
                     r"value beyond it", r.stderr), r.stderr
    fit = yaml.safe_load((tmp_path / "out" / "fit.yaml").read_text())
    assert fit["parameters"]["eta_soft"]["at_bound"] is True
    (tmp_path / "ok").mkdir()
    scene = bad_scene(tmp_path / "ok", "min: 1.0e9", "min: 2.0e10")
    scene.write_text(scene.read_text().replace("output:", "accept: [bound]\noutput:"))
    r = run(scene, tmp_path / "ok" / "out2")
    assert r.returncode == 0 and "warning: eta_soft ended at its bound min = 2e+10 (accepted" in r.stdout, r.stdout


# The other three branches of the bound check (calibrate_report.c, at_bound): a bound is min or max, the parameter's
# scale log or linear. Expected: the synthetic data's truth (eta_soft = 1.3e10, make_synthetic.py) lies beyond the
# named bound, so a fit that reproduces the data ends on that bound and the error names it with its value.
BOUND_CASES = [
    ("log at max", "start: 3.0e9, min: 1.0e9, max: 5.0e9, scale: log", "max", "5e\\+09"),
    ("linear at min", "start: 3.9e10, min: 2.0e10, max: 1.0e12, scale: linear", "min", "2e\\+10"),
    ("linear at max", "start: 3.0e9, min: 1.0e9, max: 5.0e9, scale: linear", "max", "5e\\+09"),
]


@pytest.mark.parametrize("name,bounds,which,value", BOUND_CASES, ids=[c[0] for c in BOUND_CASES])
def test_parameter_at_each_bound(tmp_path, name, bounds, which, value):
    r = run(bad_scene(tmp_path, "start: 3.9e10, min: 1.0e9, max: 1.0e12, scale: log", bounds), tmp_path / "out")
    assert r.returncode == 1, (r.stdout[-2000:], r.stderr)
    assert re.search(rf"bad.yaml:\d+: key 'parameters\[0\].{which}': eta_soft ended at its bound {which} = {value}: the data "
                     r"want a value beyond it", r.stderr), r.stderr
    fit = yaml.safe_load((tmp_path / "out" / "fit.yaml").read_text())
    assert fit["parameters"]["eta_soft"]["at_bound"] is True


def test_failed_reference(tmp_path):
    """A full model that fails: an error naming runs[0].reference, the scene, its exit code and log; the forward
    fit kept in fit.yaml, its quote saying the bias is unknown."""
    ref = tmp_path / "ref.yaml"
    text = (CAL / "forward" / "nano_fast.yaml").read_text().replace("../../../meshes/", f"{MESHES}/")
    ref.write_text(text.replace("until: {load: 250}", "until: {load: 1.0e9}"))  # never reached: the run fails
    r = run(bad_scene(tmp_path, "reference: none", f"reference: {ref}"), tmp_path / "out")
    assert r.returncode == 1
    assert re.search(r"bad.yaml:\d+: key 'runs\[0\].reference': the full-model run of .*ref.yaml failed \(exit code 1; its log: "
                     r".*full0_nano/forward.log\) \(fit.yaml has the forward model's fit; its bias is not known\)", r.stderr), r.stderr
    fit = yaml.safe_load((tmp_path / "out" / "fit.yaml").read_text())
    assert "the full-model run failed" in fit["quote"]["eta_soft"]["from"]


def table_scene(tmp_path, stage0):
    """forward/nano_fast.yaml with its loading stage replaced."""
    text = (CAL / "forward" / "nano_fast.yaml").read_text().replace("../../../meshes/", f"{MESHES}/")
    old = "    duration: 600\n    indenter: {load: {exp: {P0: 22, k: 0.0156}}, until: {load: 250}}"
    assert old in text
    path = tmp_path / "table.yaml"
    path.write_text(text.replace(old, stage0))
    return path


def history(path):
    """The rows as text: the two runs are compared digit for digit."""
    with open(path) as f:
        return list(csv.DictReader(f))


def test_table_load_is_the_ramp(tmp_path):
    """A load table of two rows, (0, 0) and (60 s, 600 uN), drives the indenter as the ramp load: 600 does, to
    rounding (the same steps and Newton iterations; depths within 1e-9 um of the 0.2 um, loads within 1e-8 of the
    600 uN). The bounds are the Newton tolerance's, not the rounding's: two steps of this scene stall
    (docs/contact.md) and are cut back in both runs, the retried steps stop where the error estimate allows, and
    from there the step sizes carry the two loads' rounding on. Measured: 1.4e-10 um and 7.5e-7 uN (1.5e-12 um and
    7.8e-9 uN without the stall test, -indent_stall_window 0). A misread table is off by far more: a wrong
    time_factor or factor changes the load by its whole size. The run against the ramp run is [self]; the load of
    every step against the closed form P = 10 t uN is [ind]."""
    (tmp_path / "load.csv").write_text("t_min,P_mN\n0,0\n1,0.6\n")
    ramp = table_scene(tmp_path, "    duration: 60\n    indenter: {load: 600}")
    ramp = ramp.rename(tmp_path / "ramp.yaml")
    table = table_scene(tmp_path, "    duration: 60\n    indenter: {load: {table: {file: load.csv, time: t_min, value: P_mN, "
                                  "time_factor: 60, factor: 1000}}}")
    for scene, out in ((ramp, "r"), (table, "t")):
        run_driver(scene, tmp_path / out, driver=DRIVER, timeout=600)  # DriverError: it failed
    a, b = history(tmp_path / "r" / "history.csv"), history(tmp_path / "t" / "history.csv")
    assert len(a) == len(b) > 100
    assert [x["newton_its"] for x in a] == [y["newton_its"] for y in b]
    assert max(abs(float(x["depth"]) - float(y["depth"])) for x, y in zip(a, b)) < 1e-9  # 1.4e-10 measured
    assert max(abs(float(x["load"]) - float(y["load"])) for x, y in zip(a, b)) < 1e-8 * 600  # 7.5e-7 uN measured
    # Independent of the ramp run: the table's load at every step of the loading stage (t <= 60 s) is the closed
    # form P = 600 uN t / 60 s (the two rows interpolated linearly), to 1e-8 of 600 uN (measured 1.1e-13 uN).
    loading = [y for y in b if float(y["time"]) <= 60]
    assert len(loading) > 20
    ramp_law = max(abs(float(y["load"]) - 10.0 * float(y["time"])) for y in loading)
    print(f"table load against P = 10 t: {ramp_law:.2e} uN")
    assert ramp_law < 1e-8 * 600


TABLE_BAD = [
    ("ends before the stage", "0,0\n30,300\n",
     r"table.yaml:\d+: key 'stages\[0\].indenter.load.table': the table's times end at 30 s .*before the stage's end "
     r"\(duration 60 s\)"),
    ("negative load", "0,0\n10,-5\n60,600\n",
     r"table.yaml:\d+: key 'stages\[0\].indenter.load.table': the load at t = 10 s \(row 2\) is -5: expected loads >= 0"),
]


@pytest.mark.parametrize("name,rows,message", TABLE_BAD, ids=[b[0] for b in TABLE_BAD])
def test_table_load_bad(tmp_path, name, rows, message):
    (tmp_path / "load.csv").write_text("t,P\n" + rows)
    scene = table_scene(tmp_path, "    duration: 60\n    indenter: {load: {table: {file: load.csv, time: t, value: P}}}")
    r = subprocess.run([DRIVER, "-input", str(scene), "-output_dir", str(tmp_path / "out")], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 2
    assert re.search(message, r.stderr), r.stderr


def test_two_cycles_need_a_stage_column(tmp_path):
    """Without a stage column the stages are found from one loading cycle: a curve that loads twice is an error
    that asks for the column."""
    lines = (CAL / "data" / "nano_synthetic.csv").read_text().splitlines()
    rows = [r.split(",") for r in lines[2:]]
    t_end = float(rows[-1][0])
    again = [[f"{t_end + float(r[0]):.10g}", r[1], r[2]] for r in rows[:15]]  # the loading once more
    data = tmp_path / "twice.csv"
    data.write_text("\n".join(lines[:2] + [",".join(r) for r in rows + again]) + "\n")
    r = run(bad_scene(tmp_path, "drive: scene", "drive: data", data=data), tmp_path / "out")
    assert r.returncode == 2
    assert re.search(r"bad.yaml:\d+: key 'runs\[0\].data': the load rises from 16.\d+ to \d+.?\d* at time \d+.?\d* within the "
                     r"unloading: more than one loading cycle\? Give the data's stages as a column "
                     r"\(runs\[0\].data.columns.stage\)", r.stderr), r.stderr
