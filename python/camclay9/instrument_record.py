"""The exact instrument record of issue 37 (bench/calibrate_coverage.py, tests/calibrate/test_measured_curves.py): a
nanoindentation record (10 rows a second: depth_nm, load_mN, time_s, segment) of the paper's protocol with a hold for
thermal drift (input/calibrate/protocols/paper_drift_hold.yaml), its loads and times from make_synthetic.py, its depths
those of the very forward scene the fit runs (input/calibrate/forward/nano_fast.yaml, through the scene
-calibrate_dry_run writes for the record) at the truth: the model is exact. Paths are those of the repository `root`
(default: camclay9.repo_root())."""
import subprocess
import sys

import numpy as np
import yaml
from camclay9 import driver_path, read_history, run_driver
from camclay9.launch import repo_root


def calibrate_inputs(root=None):
    """input/calibrate of the repository."""
    return repo_root(root) / "input" / "calibrate"


def forward_scene(root=None):
    """The forward scene the fits run: input/calibrate/forward/nano_fast.yaml."""
    return calibrate_inputs(root) / "forward" / "nano_fast.yaml"


def read_csv(path):
    """The numeric columns of a record CSV ('#' lines skipped; history.csv: camclay9.read_history)."""
    with open(path) as f:
        lines = [line.strip().split(",") for line in f if not line.startswith("#")]
    keep = [k for k, v in enumerate(lines[1]) if v.lstrip("-").replace(".", "", 1).replace("e", "", 1).replace("-", "")
            .replace("+", "").isdigit() or v in ("nan", "inf")]
    return [lines[0][k] for k in keep], np.array([[float(r[k]) for k in keep] for r in lines[1:]])


def write_record(path, head, a):
    with open(path, "w") as f:
        f.write(",".join(head) + "\n")
        for row in a:
            f.write(f"{row[0]:.10g},{row[1]:.10g},{row[2]:.10g},{int(row[3])}\n")


def scene_text(data, name, start, drift=None, extra="", units="units: {time: s, load: mN, depth: nm}", root=None):
    """A user's calibrate scene for an instrument record: every column's unit declared."""
    return f"""scene: calibrate
name: {name}
parameters:
  - {{name: eta_soft, start: {start:.6g}, min: 1.0e9, max: 1.0e12, scale: log}}
runs:
  - name: nano
    scene: {forward_scene(root)}
    reference: none
{f'    drift: {drift}' + chr(10) if drift else ''}    data:
      file: {data}
      columns: {{time: time_s, load: load_mN, depth: depth_nm, stage: segment}}
      {units}
weighting: noise
{extra}"""


SHIPPED_DRIFT_HOLD = 60   # s, the drift hold of protocols/paper_drift_hold.yaml as shipped


def protocol(hold, work, root=None):
    """The record's protocol: protocols/paper_drift_hold.yaml, its drift hold lasting `hold` seconds."""
    shipped = calibrate_inputs(root) / "protocols" / "paper_drift_hold.yaml"
    if hold == SHIPPED_DRIFT_HOLD:
        return shipped
    d = yaml.safe_load(shipped.read_text())
    next(st for st in d["stages"] if st["name"] == "drift")["duration"] = hold
    out = work / f"protocol_drift_{hold:g}.yaml"
    out.write_text(yaml.safe_dump(d, sort_keys=False))
    return out


def exact_record(truth, work, log, hold=SHIPPED_DRIFT_HOLD, root=None):
    """The record's loads and times from the protocol run at the truth; its depths those of the scene the fit runs
    (driven by those loads) at the truth, interpolated at the record's times: the model is exact."""
    rec = work / "protocol_run.csv"
    root = repo_root(root)
    subprocess.run([sys.executable, str(calibrate_inputs(root) / "make_synthetic.py"), "--driver",
                    str(driver_path(root=root)), "--scene", str(forward_scene(root)), "--set",
                    f"eta_soft={truth:.10g}", "--protocol", str(protocol(hold, work, root)), "--instrument", "10", "--out",
                    str(rec)],
                   check=True, capture_output=True, timeout=900)
    head, a = read_csv(rec)  # from the first row under load: the paper's loading starts at 22 uN (docs/calibrate.md, Limits)
    a = a[np.argmax(a[:, head.index("load_mN")] > 0):]
    write_record(rec, head, a)
    dry = work / "dry.yaml"
    dry.write_text(scene_text(rec, "dry", truth, units="factors: {time: 1, load: 1000, depth: 0.001}", root=root).replace(
        "weighting: noise\n", ""))  # the scene as any version of calibrate reads it: its forward scene is what is wanted
    run_driver(dry, work / "dry", ["-calibrate_dry_run"], root=root, timeout=900)
    out = work / "truth"
    run_driver(work / "dry" / "protocol" / "nano" / "scene.yaml", out,
               ["-material_set", f"eta_soft={truth:.17g}", "-progress_every", "1000000"], root=root, timeout=900)
    h = read_history(out, need=("time", "depth"))
    head, a = read_csv(rec)
    t = a[:, head.index("time_s")] - a[0, head.index("time_s")]  # the forward run's time 0 is the record's first row
    a[:, head.index("depth_nm")] = 1e3 * np.interp(t, h["time"], h["depth"])
    return head, a
