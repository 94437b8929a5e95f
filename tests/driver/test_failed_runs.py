"""What a run that fails leaves (issue 35 item 4; docs/driver.md, "summary.json" and "What is never lost"):

* an FE and an indentation run that fail after some steps (a stage whose UMAT tolerance cannot be met: the step
  fails for good at the step-size minimum) write summary.json with "completed": false, the stages done with their
  reported outputs, the counters so far (steps: the history's rows but row 0) and "failure" (the stage it failed
  in, its index, the time reached, the message); on 2 ranks the same counters in one file (rank 0 writes it);
* a run that fails at its first step, into the directory of an earlier run, leaves the earlier run's summary.json
  and history byte for byte and its own summary as summary.json.part, beside its other .part files;
* an adaptation whose last level fails leaves OUT's files and the kept level untouched, says in
  OUT/summary.json.part which level failed and lists the levels; a level stopped by -max_steps is not kept;
* a restart from a checkpoint of an older format (a point's, as cbec814^ wrote them) or with a history of the older
  layout is refused with exit 2, saying so and to run the scene again from its start, and writes nothing; a refused
  restart (another scene) leaves summary.json untouched.

$DRIVER is the driver (CTest sets it); driver_elastic is beside it.
"""
import json
import shutil
from pathlib import Path

from camclay9 import driver_path, read_history, run_driver
from test_contact import ELASTIC, ROLLERS, ROOT
from test_stage_runner import MESHES, camclay_cone  # Cam-Clay IX kerogen under a cone, coarse axisymmetric

BIN = driver_path(root=ROOT).parent
# the UMAT's own control at a tolerance no step meets: every step is cut to the minimum, then fails for good
IMPOSSIBLE = "{adaptive: true, first: 1, min: 0.5, error: {measure: worst_point, tol: 1.0e-30}}"


def run(text, out, args=(), exe="driver", ranks=1, timeout=600):
    """The driver on a scene (written beside out): its process, whatever its exit status."""
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    return run_driver(scene, out, args, driver=BIN / exe, ranks=ranks, cwd=out.parent, timeout=timeout, check=False)


def summary(path):
    return json.loads(Path(path).read_text())


def box(creep_steps, hold=True):
    """Cam-Clay IX in a box under its initial stress, held (3 steps), then an axial creep load (instant); without the
    hold, the load ramps up from the start (no zero-time step: the stage's first step is its first)."""
    stages = "  - {name: hold, duration: 100, pressure: {x1: 35, y1: 35, z1: 35}, steps: {count: 3}}\n" if hold else ""
    return f"""scene: fe
mesh: {{geometry: {MESHES}/box.geo, parameters: {{Lx: 1, Ly: 1, Lz: 1, size: 0.5}}}}
material: {{props: woodford, bedding_angle: 0}}
initial: {{stress: [-35, -35, -35, 0, 0, 0], pressure: {{x1: 35, y1: 35, z1: 35}}}}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}, {{group: z0, components: [z]}}]
  pressure: [x1, y1, z1]
stages:
{stages}  - {{name: creep, duration: 400, {"load: instant, " if hold else ""}pressure: {{x1: 35, y1: 35, z1: 75}}, steps: {creep_steps}}}
"""


def check_failure(s, hist, kind, stage, done, time):
    """summary.json of a run that failed in `stage` (index len(done)) at `time`, the stages `done` before it."""
    f = s["failure"]
    print(f"{kind}: failure {f}; counters {s['counters']}")
    assert s["kind"] == kind and s["completed"] is False
    assert f["stage"] == stage and f["stage_index"] == len(done) and f["time"] == time
    assert f"stage '{stage}'" in f["error"] and "step failed for good" in f["error"]
    assert [st["name"] for st in s["stages"]] == ["start", *done]
    assert s["counters"]["steps"] == len(hist) - 1 and s["counters"]["cutbacks"] >= 1 and s["counters"]["umat_calls"] > 0
    assert hist["time"][-1] == time


def test_fe_failure_after_steps(tmp_path):
    out = tmp_path / "box"
    proc = run(box("{count: 4}"), out)
    assert proc.returncode == 0 and summary(out / "summary.json")["failure"] is None
    proc = run(box(IMPOSSIBLE), out)
    assert proc.returncode == 1, proc.stderr
    s = summary(out / "summary.json")      # the run's files replaced the earlier run's: so does its summary
    check_failure(s, read_history(out), "fe", "creep", ["hold"], 100)
    assert s["mesh"]["error_indicator"] is None and not (out / "summary.json.part").exists()
    assert s["stages"][1]["end"]["strain_axial"] < 0            # the hold's reported outputs, as a completed run's
    two = tmp_path / "box2"
    assert run(box(IMPOSSIBLE), two, ranks=2).returncode == 1
    s2 = summary(two / "summary.json")
    print(f"2 ranks: {s2['counters']}")
    assert s2["failure"]["stage"] == "creep" and s2["counters"] == s["counters"]


def test_first_step_failure_keeps_earlier_summary(tmp_path):
    out = tmp_path / "box"
    assert run(box("{count: 4}"), out).returncode == 0
    before = {n: (out / n).read_bytes() for n in ("summary.json", "history.csv")}
    proc = run(box(IMPOSSIBLE, hold=False), out)
    assert proc.returncode == 1 and "this run's files end in .part" in proc.stderr
    assert {n: (out / n).read_bytes() for n in before} == before
    s = summary(out / "summary.json.part")
    print(f"unpromoted: {s['failure']}")
    shutil.copy(out / "history.csv.part", tmp_path / "part.csv")
    check_failure(s, read_history(tmp_path / "part.csv"), "fe", "creep", [], 0)


def test_indentation_failure_after_steps(tmp_path):
    out = tmp_path / "cone"
    proc = run(camclay_cone("  - {name: load, duration: 10, indenter: {load: 150}, steps: {count: 4}}\n"
                    f"  - {{name: hold, duration: 100, indenter: {{load: hold}}, steps: {IMPOSSIBLE}}}"), out)
    assert proc.returncode == 1, proc.stderr
    s = summary(out / "summary.json")
    check_failure(s, read_history(out), "indentation", "hold", ["load"], 10)
    assert abs(s["stages"][1]["end"]["load"] - 150) < 1e-6 and s["stages"][1]["end"]["depth"] > 0


def hertz(out, args):
    """An elastic block under a sphere, two stages, with one adapted level."""
    return run(f"""scene: fe
mesh:
  geometry: {MESHES}/indent_block2d.geo
  parameters: {{W: 8, H: 4, half: 1, h_tip: 0.04, h_far: 1, r_fine: 0.3, r_contact: 0.4}}
  kinematics: axisymmetric
material: {ELASTIC}
boundary:
  fixed: {ROLLERS}
indenter: {{shape: sphere, radius: 1, contact: contact, gap: vertical}}
stages:
  - {{name: push, duration: 1, indenter: {{depth: 0.01}}, steps: {{count: 2}}}}
  - {{name: more, duration: 1, indenter: {{depth: 0.02}}, steps: {{count: 2}}}}
""", out, ["-adapt_levels", "1", *args], exe="driver_elastic")


def test_adaptation_failed_level(tmp_path):
    out = tmp_path / "ad"
    assert hertz(out, []).returncode == 0
    first = summary(out / "summary.json")
    kept = ["summary.json", "history.csv", "mesh.msh", "adapt/level0/level.txt", "adapt/level0/sizes.pos"]
    before = {n: (out / n).read_bytes() for n in kept}
    # level 0 is kept; level 1 runs with one Newton iteration a step (an option its key does not see) and fails
    proc = hertz(out, ["-indent_max_it", "1"])
    assert proc.returncode == 1 and "level 0 kept" in proc.stdout, proc.stdout + proc.stderr
    assert {n: (out / n).read_bytes() for n in kept} == before
    assert not (out / "adapt/level1/level.txt").exists()            # the failed level is never reused
    s = summary(out / "summary.json.part")
    print(f"adaptation: {s['failure']}; levels {[lv['dir'] for lv in s['levels']]}")
    assert s["completed"] is False and s["failure"]["level"] == 1 and s["failure"]["stage"] == "push"
    assert [Path(lv["dir"]).name for lv in s["levels"]] == ["level0", "level1"] and s["levels"][0] == first["levels"][0] | {"kept": True}
    assert [lv["kept"] for lv in first["levels"]] == [False, False] and [lv["kept"] for lv in s["levels"]] == [True, False]
    # the next run keeps level 0 and reruns level 1: the first run's answer
    proc = hertz(out, [])
    assert proc.returncode == 0 and "level 0 kept" in proc.stdout
    again = summary(out / "summary.json")
    assert again["stages"] == first["stages"] and not (out / "summary.json.part").exists()
    assert [lv["kept"] for lv in again["levels"]] == [True, False]    # summary.json says which levels this run reused
    # a level stopped by -max_steps is not kept for a later run
    stop = tmp_path / "stop"
    assert hertz(stop, ["-max_steps", "2"]).returncode == 0
    assert not (stop / "adapt/level0/level.txt").exists() and (stop / "adapt/level0/history.csv").exists()


POINT = """scene: point
material: {props: woodford, bedding_angle: 0}
initial: {stress: [-35, -35, -35, 0, 0, 0]}
segments:
  - {name: hold, duration: 100, steps: {count: 4}, control: {11: {stress: -35}, 22: {stress: -35}, 33: {stress: -35}, others: {stress: 0}}}
  - {name: creep, duration: 100, load: instant, steps: {count: 4},
     control: {11: {stress: -35}, 22: {stress: -35}, 33: {stress: -75}, others: {stress: 0}}}
"""


def test_restart_from_older_layout(tmp_path):
    out = tmp_path / "pt"
    assert run(POINT, out, ["-checkpoint_every", "3", "-max_steps", "3"]).returncode == 0
    files = {f.name: f.read_bytes() for f in out.iterdir()}
    step = (out / "checkpoint.latest").read_text().split()[0]
    ckpt = out / f"checkpoint.{step}.rank0.bin"
    fmt = int.from_bytes(files[ckpt.name][4:8], "little")

    def refused(what):
        proc = run(POINT, out, ["-restart"])
        print(f"{what}: {proc.stderr.strip()}")
        assert proc.returncode == 2 and "run the scene again from its start, without -restart" in proc.stderr
        assert {f.name: f.read_bytes() for f in out.iterdir() if f.name != ckpt.name and f.name != "history.csv"} == \
            {n: b for n, b in files.items() if n != ckpt.name and n != "history.csv"}
        return proc.stderr

    # a checkpoint of the format before this one (the state of a point of cbec814^, its history's old columns)
    ckpt.write_bytes(files[ckpt.name][:4] + (fmt - 1).to_bytes(4, "little") + files[ckpt.name][8:])
    assert f"checkpoint format {fmt - 1}; this driver reads format {fmt}): a checkpoint of an older layout" in refused("format")
    assert (out / "history.csv").read_bytes() == files["history.csv"]
    # a history of the older layout (a point's time,step,segment,...) beside a checkpoint of this format
    ckpt.write_bytes(files[ckpt.name])
    lines = files["history.csv"].decode().split("\n")
    old = "time,step,segment,dt,newton_its,local_its,cutbacks," + lines[0].split(",", 8)[8]
    (out / "history.csv").write_text("\n".join([old, *lines[1:]]))
    assert "column 2 is 'step', this driver writes 'stage'" in refused("history")
    assert (out / "history.csv").read_text().split("\n")[0] == old
    # another scene: refused before the run, summary.json untouched (refused() compares it)
    (out / "history.csv").write_bytes(files["history.csv"])
    proc = run(POINT.replace("duration: 100, load", "duration: 200, load"), out, ["-restart"])
    assert proc.returncode == 2 and "differs from the one the checkpoint" in proc.stderr
    assert (out / "summary.json").read_bytes() == files["summary.json"]
    # the same files as written: the restart continues, and completes
    proc = run(POINT, out, ["-restart"])
    assert proc.returncode == 0, proc.stderr
    assert summary(out / "summary.json")["completed"] is True and len(read_history(out)) == 10


def test_restart_beside_older_fe_history_on_two_ranks(tmp_path):
    """An FE history without stage_name (the layout before it) on 2 ranks: rank 0 reads the history, and every rank
    stops with its message (no rank waits in the run)."""
    out = tmp_path / "box"
    assert run(box("{count: 4}"), out, ["-checkpoint_every", "2", "-max_steps", "2"], ranks=2).returncode == 0
    lines = (out / "history.csv").read_text().split("\n")
    old = [",".join(c for k, c in enumerate(line.split(",")) if k != 2) for line in lines]   # no stage_name
    (out / "history.csv").write_text("\n".join(old))
    before = {f.name: f.read_bytes() for f in out.iterdir()}
    proc = run(box("{count: 4}"), out, ["-restart"], ranks=2, timeout=120)   # a rank left waiting: the timeout fails it
    print(proc.stderr.strip())
    assert proc.returncode == 2 and "column 3 is 'step', this driver writes 'stage_name'" in proc.stderr
    assert {f.name: f.read_bytes() for f in out.iterdir()} == before
