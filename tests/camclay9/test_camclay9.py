"""The package camclay9 (python/, issue 35): its readers on small files of the driver's one history layout (and an
old point history, written before it), a
summary.json and a log; its launcher on stand-in drivers (a failure, a timeout, a missing executable) and on the
driver itself (a point scene, under a second). The package is imported as installed by tools/setup.sh, and the
installed copy must be python/camclay9 as it is now: a stale or missing install fails here, never passes."""
import filecmp
import signal
import stat
import sys
from pathlib import Path

import numpy as np
import pytest

try:
    import camclay9
except ImportError as err:  # an error, never a skip: the package is part of the project
    raise ImportError(f"{err}: tools/setup.sh installs it (pip install python/)") from None
from camclay9.history import LEAD
from camclay9 import (DriverError, driver_command, driver_path, history_layout, mesh_line, read_history,
                      read_summary, reported, run_driver, run_measured, stage, summary_line)

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"


def test_installed_package_is_this_checkout():
    got = Path(camclay9.__file__).resolve().parent
    src = ROOT / "python" / "camclay9"
    stale = [f.name for f in sorted(src.glob("*.py")) if not (got / f.name).is_file()
             or not filecmp.cmp(f, got / f.name, shallow=False)]
    assert not stale, f"{got}: {stale} differ from {src}: run tools/setup.sh (it reinstalls the package)"


# ------------------------------------------------------------------ history.csv
@pytest.mark.parametrize("name, kind, first", [("fe", "fe", "pressure_top"), ("indentation", "indentation", "load"),
                                               ("point", "point", "eps_11")])
def test_history_layouts(name, kind, first):
    h = read_history(DATA / f"history_{name}.csv")
    assert history_layout(h) == kind
    assert first in h.dtype.names and h.dtype["time"] == np.float64 and h.dtype["step"] == np.int64
    assert h["step"].tolist() == list(range(h.size))


def test_history_values_by_name():
    fe = read_history(DATA / "history_fe.csv")
    assert fe.size == 3 and fe["stage"].tolist() == [0, 0, 1] and fe["sig_33"][-1] == -75.0
    creep = fe[fe["stage"] == 1]
    assert creep["time"][0] == 3610.0 and creep["pressure_top"][0] == 40.0
    ind = read_history(DATA / "history_indentation.csv", need=("load", "depth"))
    assert ind["stage_name"].tolist() == ["load", "load", "load"] and ind["active_nodes"].dtype == np.int64
    assert ind["depth"][1] == pytest.approx(0.011484643681630201, rel=0, abs=0)
    assert (ind[ind["stage_name"] == "load"]["load"] > -1).all()
    pt = read_history(DATA / "history_point.csv")
    assert pt["stage"].tolist() == [0, 0] and pt["flags"].dtype == np.int64 and pt["sig_33"][0] == -35.0
    assert pt["stage_name"].tolist() == ["load", "load"] and fe["stage_name"].tolist() == ["load", "load", "creep"]


def test_history_one_layout_and_an_old_point_history():
    """Every kind's history begins with the same columns; an old point history's segment reads as its stage."""
    for name in ("fe", "indentation", "point"):
        head = (DATA / f"history_{name}.csv").read_text().splitlines()[0].split(",")
        assert tuple(head[:len(LEAD)]) == LEAD, name
    old = read_history(DATA / "history_point_old.csv")
    new = read_history(DATA / "history_point.csv")
    assert history_layout(old) == "point" and "segment" not in old.dtype.names and "stage_name" not in old.dtype.names
    for name in old.dtype.names:
        assert old[name].tolist() == new[name].tolist(), name


def test_history_run_directory_and_one_row(tmp_path):
    lines = (DATA / "history_point.csv").read_text().splitlines()
    (tmp_path / "history.csv").write_text("\n".join(lines[:2]) + "\n")
    h = read_history(tmp_path)  # a run directory: its history.csv
    assert h.shape == (1,) and h["time"][0] == 0.0


def test_history_errors_name_file_line_column_value(tmp_path):
    lines = (DATA / "history_fe.csv").read_text().splitlines()
    bad = tmp_path / "history.csv"
    bad.write_text("\n".join([lines[0], lines[1], lines[2].replace("10,0,load,1,", "10,0,load,x,", 1)]) + "\n")
    with pytest.raises(ValueError, match=r"history\.csv:3: column 'step' has 'x': expected an integer"):
        read_history(bad)
    bad.write_text("\n".join([lines[0], lines[1] + ",7"]) + "\n")
    with pytest.raises(ValueError, match=r"history\.csv:2: \d+ values, expected \d+"):
        read_history(bad)
    with pytest.raises(ValueError, match=r"history_fe\.csv: column\(s\) 'depth' missing from the header line"):
        read_history(DATA / "history_fe.csv", need=("time", "depth"))
    bad.write_text("time,b,c\n1,2,3\n")  # columns by name: any layout reads
    assert read_history(bad)["c"].tolist() == [3.0]
    with pytest.raises(ValueError, match="not a history.csv layout"):
        history_layout(read_history(bad))
    with pytest.raises(FileNotFoundError, match="nothing/history.csv: no such file"):
        read_history(tmp_path / "nothing")


# ------------------------------------------------------------------ summary.json
def test_summary():
    s = read_summary(DATA)
    assert s["kind"] == "indentation" and s["counters"]["steps"] == 40
    assert stage(s, "hold")["change"]["depth"] == 0.0082
    assert reported(s, "hold", "depth", "change") == 0.0082 and reported(s, "load", "load") == 1000
    assert s.path == str(DATA / "summary.json") and "path" not in s  # the file's keys only
    with pytest.raises(KeyError, match="summary.json: no stage 'unload' \\(stages: start, load, hold\\)"):
        stage(s, "unload")
    with pytest.raises(KeyError, match="reports no 'force'"):
        reported(s, "hold", "force")


def test_summary_errors(tmp_path):
    (tmp_path / "summary.json").write_text('{"scene": "x", "kind": "fe"}')
    with pytest.raises(ValueError, match=r"summary\.json: no key 'completed', 'counters', 'cost', 'mesh', 'stages'"):
        read_summary(tmp_path)
    (tmp_path / "summary.json").write_text('{"scene": ')
    with pytest.raises(ValueError, match="not JSON"):
        read_summary(tmp_path)
    # a run that failed before its first step was done: summary.json.part, read when named
    part = tmp_path / "summary.json.part"
    part.write_text((DATA / "summary.json").read_text())
    assert read_summary(part).path == str(part)
    with pytest.raises(FileNotFoundError, match="summary.json.part"):
        read_summary(tmp_path / "none")


# ------------------------------------------------------------------ the log
INDENT = ("indentation your_indent_axi: 3 steps, 24 Newton iterations (predictor on), 0 cutbacks (0 by the error "
          "measure), 0 active-set cycles, 591808 UMAT calls, assembly 0.93 s, linear solves 4.08 s (direct, 287 Krylov "
          "iterations, 8 factorisations), wall 5.12 s -> ind/adapt/level2/history.csv")
POINT = ("point scene oedometer: 180 steps, 0 cutbacks, worst control residual 8.54e-13 (relative), 0.0041 s -> "
         "pt/history.csv")


def test_summary_line_three_kinds():
    fe = summary_line((DATA / "driver.log").read_text())
    assert fe == dict(kind="fe scene", scene="triaxial", steps=57, newton_iterations=171, cutbacks=2,
                      cutbacks_by_error=1, umat_calls=1201536, assembly_s=3.21, wall_s=20.05,
                      output_dir="results/triaxial", failed=False)
    ind = summary_line("noise\n" + INDENT + "\nadapt: level 2\n")
    assert (ind["kind"], ind["steps"], ind["newton_iterations"], ind["predictor"], ind["active_set_cycles"]) == \
        ("indentation", 3, 24, "on", 0)
    assert (ind["linear_solves_s"], ind["linear_solver"], ind["krylov_iterations"], ind["factorisations"]) == \
        (4.08, "direct", 287, 8)
    assert ind["wall_s"] == 5.12 and ind["output_dir"] == "ind/adapt/level2"
    pt = summary_line(POINT)
    assert (pt["kind"], pt["steps"], pt["cutbacks"], pt["worst_control_residual"], pt["wall_s"], pt["failed"]) == \
        ("point scene", 180, 0, 8.54e-13, 0.0041, False)
    assert "newton_iterations" not in pt
    assert summary_line(POINT.replace(" s ->", " s, FAILED ->"))["failed"] is True
    two = INDENT.replace("3 steps", "2 steps") + "\n" + INDENT  # levels of an adapted run: the last is the answer
    assert summary_line(two)["steps"] == 3 and summary_line(two, index=0)["steps"] == 2


def test_summary_line_missing_and_mesh_line():
    with pytest.raises(ValueError, match="no summary line"):
        summary_line("driver: scene.yaml:3: key 'x': not a key\n")
    m = mesh_line((DATA / "driver.log").read_text())
    assert m == dict(scene="triaxial", cells=6132, order=2, quadrature_points=4, unknowns=28731)
    with pytest.raises(ValueError, match="no mesh line"):
        mesh_line(POINT)


# ------------------------------------------------------------------ the launcher
def fake_driver(tmp_path, body):
    exe = tmp_path / "bin" / "driver"
    exe.parent.mkdir(exist_ok=True)
    exe.write_text("#!/bin/sh\n" + body + "\n")
    exe.chmod(exe.stat().st_mode | stat.S_IXUSR)
    return exe


def test_driver_path(tmp_path, monkeypatch):
    exe = fake_driver(tmp_path, "exit 0")
    (tmp_path / "bin" / "driver_elastic").write_bytes(exe.read_bytes())
    (tmp_path / "bin" / "driver_elastic").chmod(0o755)
    monkeypatch.setenv("DRIVER", str(exe))
    monkeypatch.delenv("DRIVER_ELASTIC", raising=False)
    assert driver_path() == exe and driver_path("driver_elastic") == tmp_path / "bin" / "driver_elastic"
    monkeypatch.setenv("DRIVER", str(tmp_path / "none"))
    with pytest.raises(FileNotFoundError, match=r"none \(\$DRIVER\): no such executable"):
        driver_path()
    monkeypatch.delenv("DRIVER")
    with pytest.raises(FileNotFoundError, match="not inside the repository"):
        driver_path(root=tmp_path)
    assert driver_command("s.yaml", "o", ["-x", 1], driver=exe, ranks=2, prefix=["nice"]) == \
        ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", "2", "nice", str(exe), "-input", "s.yaml",
         "-output_dir", "o", "-x", "1"]


def test_repo_root_of_a_script_then_of_the_current_directory(tmp_path):
    """A script of a repository finds its own repository wherever it is started (the files the shared modules read,
    docs/results and docs/performance.md among them, are that repository's); python -c, which is no script, finds
    the current directory's; neither inside a repository: FileNotFoundError naming the current directory."""
    import subprocess
    mine, other, outside = tmp_path / "mine", tmp_path / "other", tmp_path / "outside"
    for repo in (mine, other):
        (repo / "driver" / "src").mkdir(parents=True)
        (repo / "CMakeLists.txt").write_text("")
    outside.mkdir()
    (mine / "tools").mkdir()
    script = mine / "tools" / "where.py"
    script.write_text("import camclay9\nprint(camclay9.repo_root())\n")
    for cwd in (other, outside):
        r = subprocess.run([sys.executable, str(script)], cwd=cwd, capture_output=True, text=True, timeout=60)
        assert r.stdout.strip() == str(mine.resolve()), r.stderr
    code = "import camclay9; print(camclay9.repo_root())"
    r = subprocess.run([sys.executable, "-c", code], cwd=other / "driver", capture_output=True, text=True, timeout=60)
    assert r.stdout.strip() == str(other.resolve()), r.stderr
    r = subprocess.run([sys.executable, "-c", code], cwd=outside, capture_output=True, text=True, timeout=60)
    assert r.returncode == 1 and f"{outside.resolve()}: not inside the repository" in r.stderr, r.stderr


def test_run_driver_output_failure_timeout(tmp_path):
    exe = fake_driver(tmp_path, 'echo "$@"; echo "point scene s: 1 steps, 0 cutbacks, worst control residual 0 '
                                '(relative), 0.1 s -> $4/history.csv"')
    p = run_driver("s.yaml", tmp_path / "o", ["-max_steps", 3], driver=exe, timeout=60)
    assert p.stdout.splitlines()[0] == f"-input s.yaml -output_dir {tmp_path / 'o'} -max_steps 3"
    assert summary_line(p.stdout)["output_dir"] == str(tmp_path / "o") and p.wall >= 0 and p.cpu >= 0
    bad = fake_driver(tmp_path, 'echo "line 1" >&2; echo "driver: s.yaml:2: key x: bad" >&2; exit 2')
    with pytest.raises(DriverError, match=r"driver -input s\.yaml: exit code 2; the end of its stderr:\nline 1\n"
                                          r"driver: s\.yaml:2: key x: bad") as err:
        run_driver("s.yaml", driver=bad, timeout=60)
    assert err.value.returncode == 2 and "key x" in err.value.stderr
    assert run_driver("s.yaml", driver=bad, timeout=60, check=False).returncode == 2
    slow = fake_driver(tmp_path, "echo started >&2; exec sleep 30")
    with pytest.raises(DriverError, match=r"timed out after 0\.5 s") as err:
        run_driver("s.yaml", driver=slow, timeout=0.5)
    assert err.value.returncode is None
    with pytest.raises(ValueError, match="timeout"):
        run_driver("s.yaml", driver=slow, timeout=None)


def test_run_measured_memory_exit_code_timeout(tmp_path):
    """run_measured measures the one process it runs: a child that holds 200 MB (written, so resident) peaks above
    200 MB and under 200 MB plus an interpreter; its exit code and output are kept; a timeout kills it."""
    hold = "import sys; b = bytearray(200 * 2**20); b[::4096] = b'x' * len(b[::4096]); print('held'); sys.exit(3)"
    rc, cpu, mem, wall = run_measured([sys.executable, "-c", hold], tmp_path / "log", timeout=60)
    assert rc == 3 and (tmp_path / "log").read_text() == "held\n"
    assert 200 < mem < 200 + 100 and cpu > 0 and wall >= cpu * 0.5
    with pytest.raises(DriverError, match=r"timed out after 0\.5 s"):
        run_measured(["sleep", "30"], tmp_path / "log2", timeout=0.5)


def test_run_measured_budget_counts_the_stopped_tree(tmp_path):
    """A budget stops the run (exit code -SIGTERM) and still measures it: the CPU and peak memory of a grandchild that
    holds 150 MB and spins (the shell between stands for mpiexec, which does not pass its ranks' usage on when it is
    stopped), read before the stop."""
    spin = ("import time; b = bytearray(150 * 2**20); b[::4096] = b'x' * len(b[::4096]); print('held', flush=True)\n"
            "while True: pass")
    cmd = ["sh", "-c", f'"{sys.executable}" -c "{spin}"; true']
    rc, cpu, mem, wall = run_measured(cmd, tmp_path / "log", timeout=60, budget=2.0)
    assert rc == -signal.SIGTERM and 2.0 <= wall < 30
    assert 150 < mem < 150 + 100 and cpu > 0.3, (cpu, mem)
    assert (tmp_path / "log").read_text().startswith("held")
    with pytest.raises(ValueError, match="budget"):
        run_measured(["true"], tmp_path / "log3", budget=0)


def test_run_driver_on_a_point_scene(tmp_path):
    """The driver itself: its summary line and history agree (one row per step and the start)."""
    exe = driver_path(root=ROOT)  # $DRIVER (CTest gives it) or build/bin/driver; FileNotFoundError: not built
    p = run_driver(ROOT / "input" / "point" / "oedometer.yaml", tmp_path / "o", driver=exe, timeout=300)
    s = summary_line(p.stdout)
    h = read_history(tmp_path / "o")
    assert s["kind"] == "point scene" and s["scene"] == "oedometer" and history_layout(h) == "point"
    assert tuple(h.dtype.names[:len(LEAD)]) == LEAD  # the driver's history begins with the shared columns
    assert h.size == s["steps"] + 1 and h["step"][-1] == s["steps"]
    summ = read_summary(tmp_path / "o")  # a point run's summary.json: its stages, counters and the point's own
    assert summ["kind"] == "point" and summ["completed"] and summ["counters"]["steps"] == s["steps"]
    assert summ["counters"]["umat_calls"] >= 1 + s["steps"] and "final_stress" in summ["point"]
    last = h[-1]
    assert [st["name"] for st in summ["stages"]][1:] == list(dict.fromkeys(h["stage_name"][1:]))
    assert reported(summ, last["stage_name"], "strain_volumetric") == pytest.approx(
        last["eps_11"] + last["eps_22"] + last["eps_33"], rel=1e-9, abs=1e-15)


def test_adapt_effectivity_only_against_a_converged_answer():
    """camclay9.adapt_study.effectivity, which the section's tables and the reading's count both use: the stated error
    over the true one (here 0.5 stated against 1.0 true: 0.5), and no effectivity within the reference's own
    uncertainty (a true error below 0.2 %), without a stated error, or against another mesh's answer
    ("converged": false, as the adapt bench's cases on the uniform ladder's fixed steps)."""
    from camclay9.adapt_quotes import effectivities
    from camclay9.adapt_study import effectivity
    ref = {"P": 100.0}
    assert effectivity(ref, "P", 101.0, 0.5) == pytest.approx(0.5)
    assert effectivity(ref, "P", 100.1, 0.5) is None
    assert effectivity(ref, "P", 101.0, float("nan")) is None and effectivity(ref, "creep", 101.0, 0.5) is None
    assert effectivity(dict(ref, converged=False), "P", 101.0, 0.5) is None
    level = {"level": 1, "q": {"P": 101.0, "h_max": 101.0}, "e": {"P": 2.0, "h_max": 2.0}}
    cases = {"a": {"reference": {"P": 100.0, "h_max": 100.0}, "levels": [level]},
             "b": {"reference": {"P": 100.0, "converged": False}, "levels": [level]}}
    assert effectivities(cases) == [("a", 1, "P", pytest.approx(2.0))]
