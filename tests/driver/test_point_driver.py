"""The material-point driver (issue #3): every shipped scene runs and is plotted; mixed control holds
its prescribed components; creep converges at first order to an independent Radau integration; a
recorded UMAT call replays bit for bit; DDSDDE agrees with finite differences along a path; bad input
names the file, the line and the key.

$DRIVER is the driver executable (CTest sets it); scenes are read from input/point/.
"""
import json
import re
import sys
from pathlib import Path

import numpy as np
import pytest
from camclay9 import point_plots, read_history, run_driver, summary_line
from camclay9 import reference as ref

ROOT = Path(__file__).resolve().parents[2]

# Every shipped point scene; the full extremes sweep is a benchmark (bench/run_extremes_sweep.sh).
SCENES = sorted(p for p in (ROOT / "input" / "point").glob("*.yaml") if "scene: sweep" not in p.read_text())


def run(scene, outdir, *options, check=True):
    """The driver ($DRIVER or build/bin/driver) on a scene; check: DriverError when it fails."""
    return run_driver(scene, outdir, options, root=ROOT, cwd=ROOT, timeout=600, check=check)


def history(outdir):
    return read_history(outdir)


@pytest.mark.parametrize("scene", SCENES, ids=[s.stem for s in SCENES])
def test_scene_runs_and_plots(scene, tmp_path):
    proc = run(scene, tmp_path)
    worst = summary_line(proc.stdout)["worst_control_residual"]
    assert worst <= 1e-10, proc.stdout                      # mixed control holds to 1e-10 (relative)
    point_plots.main([str(tmp_path)])
    for png in ("stress_path.png", "stress_strain.png"):
        assert (tmp_path / png).stat().st_size > 1000


def test_mixed_control_holds_prescribed_components(tmp_path):
    run(ROOT / "input/point/triaxial_creep_theta0.yaml", tmp_path / "creep")
    h = history(tmp_path / "creep")
    creep = h["stage"] == 1
    for comp, target in (("sig_11", -35.0), ("sig_22", -35.0), ("sig_33", -75.0), ("sig_12", 0.0)):
        assert np.max(np.abs(h[comp][creep] - target)) <= 1e-10 * 75, comp
    run(ROOT / "input/point/constant_volume_shear.yaml", tmp_path / "cv")
    h = history(tmp_path / "cv")
    volume = h["eps_11"] + h["eps_22"] + h["eps_33"]
    assert np.max(np.abs(volume - volume[0])) <= 1e-12
    assert np.max(np.abs(h["eps_11"] - h["eps_22"])) <= 1e-12
    assert abs(h["eps_33"][-1] + 0.03) <= 1e-12


HOLD = 1.0e6
CREEP = 3600.0


def creep_scene(path, n_hold, n_creep):
    """The theta = 0 triaxial creep point with fixed geometric steps: n_hold over the 1e6-s hold,
    n_creep over 3600 s of creep. Doubling n with the square root of the ratio halves every step."""
    r_hold = 1e5 ** (1.0 / n_hold)       # the first hold step is ~1e-5 of the hold: ~1e-3 s at n = 50
    r_creep = 1e4 ** (1.0 / n_creep)
    path.write_text(f"""
scene: point
name: convergence
material: {{props: woodford, bedding_angle: 0}}
initial: {{stress: [-35, -35, -35, 0, 0, 0]}}
segments:
  - {{name: hold, duration: {HOLD}, steps: {{count: {n_hold}, spacing: geometric, ratio: {r_hold!r}}},
     control: {{11: {{stress: -35}}, 22: {{stress: -35}}, 33: {{stress: -35}}, others: {{stress: 0}}}}}}
  - {{name: creep, duration: {CREEP}, load: instant, creep: true,
     steps: {{count: {n_creep}, spacing: geometric, ratio: {r_creep!r}}},
     control: {{11: {{stress: -35}}, 22: {{stress: -35}}, 33: {{stress: -75}}, others: {{stress: 0}}}}}}
""")


def driver_creep(outdir):
    h = history(outdir)
    rows = np.where(h["stage"] == 1)[0]
    return h["eps_33"][rows[-1]] - h["eps_33"][rows[0]]     # from the instant jump to the end


def reference_creep(hold):
    n = [0.0, 0.0, 1.0]
    sig0 = -35.0 * np.eye(3)
    held = ref.creep_mixture(ref.WOODFORD, n, sig0, sig0, [hold], rtol=1e-10)
    sol = ref.creep_mixture(ref.WOODFORD, n, sig0, np.diag([-35.0, -35.0, -75.0]), [CREEP], rtol=1e-10,
                            evp0_hard=held["evp_hard"][-1], evp0_soft=held["evp_soft"][-1])
    return sol["strain"][-1][2] - sol["strain0"][2]


def test_creep_converges_at_first_order_to_radau(tmp_path):
    exact = reference_creep(HOLD)
    errors = []
    for n in (50, 100, 200, 400):
        scene = tmp_path / f"conv{n}.yaml"
        creep_scene(scene, n, n)
        run(scene, tmp_path / f"out{n}")
        errors.append(abs(driver_creep(tmp_path / f"out{n}") - exact) / abs(exact))
    orders = [np.log2(errors[k] / errors[k + 1]) for k in range(len(errors) - 1)]
    print(f"Radau creep strain after {HOLD:g} s hold, {CREEP:g} s creep: {exact:.10e}")
    print("relative errors:", ", ".join(f"{e:.3e}" for e in errors), " observed orders:",
          ", ".join(f"{p:.3f}" for p in orders))
    assert all(0.85 < p < 1.15 for p in orders), orders
    assert errors[-1] < 5e-3


def test_error_of_the_shipped_scene(tmp_path):
    """The shipped scene (adaptive steps, tol = 2e-7): its creep strain at 1 h and 10 h against the
    reference with the same hold. Prints the error; asserts it is below 1 %."""
    out = tmp_path / "shipped"
    run(ROOT / "input/point/triaxial_creep_theta0.yaml", out)
    meta = json.loads((out / "scene.json").read_text())
    hold = meta["segments"][0]["t_end"]
    h = history(out)
    rows = np.where(h["stage"] == 1)[0]
    t = h["time"][rows] - h["time"][rows[0]]
    eps = h["eps_33"][rows] - h["eps_33"][rows[0]]
    n = [0.0, 0.0, 1.0]
    sig0 = -35.0 * np.eye(3)
    held = ref.creep_mixture(ref.WOODFORD, n, sig0, sig0, [hold], rtol=1e-10)
    sol = ref.creep_mixture(ref.WOODFORD, n, sig0, np.diag([-35.0, -35.0, -75.0]), [3600.0, 36000.0],
                            rtol=1e-10, evp0_hard=held["evp_hard"][-1], evp0_soft=held["evp_soft"][-1])
    for k, when in enumerate((3600.0, 36000.0)):
        exact = sol["strain"][k][2] - sol["strain0"][2]
        got = np.interp(when, t, eps)
        err = abs(got - exact) / abs(exact)
        print(f"default settings: creep at {when:g} s = {got:.6e}, reference {exact:.6e}, relative error {err:.2e}")
        assert err < 1e-2


def test_replay_is_bit_for_bit(tmp_path):
    run(ROOT / "input/point/triaxial_creep_theta0.yaml", tmp_path, "-write_replay_at_step", "120")
    proc = run(tmp_path / "replay_step_120.yaml", tmp_path / "replayed")
    assert "identical to the recorded call, bit for bit" in proc.stdout
    # A changed recorded result is caught.
    text = (tmp_path / "replay_step_120.yaml").read_text()
    text = re.sub(r"(expected:\n  pnewdt: )([0-9.eE+-]+)", lambda m: m.group(1) + "0.5", text)
    (tmp_path / "tampered.yaml").write_text(text)
    proc = run(tmp_path / "tampered.yaml", tmp_path / "t", check=False)
    assert proc.returncode != 0 and "differs from the recorded call" in proc.stderr


def test_tangent_check_along_a_path(tmp_path):
    proc = run(ROOT / "input/point/triaxial_drained_medium.yaml", tmp_path, "-check_tangent")
    worst = float(re.search(r"central differences\| / \|DDSDDE\| = ([0-9.eE+-]+)", proc.stdout).group(1))
    print(proc.stdout.strip())
    assert worst < 1e-6


@pytest.mark.parametrize("snippet, expected", [
    ("segments:\n  - {duration: 1, control: {others: {stress: 0}}, stepz: {count: 1}}\n",
     r":\d+: unknown key 'segments\[0\]\.stepz'"),
    ("segments:\n  - {duration: x, control: {others: {stress: 0}}}\n",
     r":\d+: key 'segments\[0\]\.duration': expected a finite number, got 'x'"),
    # a number followed by text (a unit) is not the number (issue 38: no case had trailing text)
    ("segments:\n  - {duration: 10s, control: {others: {stress: 0}}}\n",
     r":\d+: key 'segments\[0\]\.duration': expected a finite number, got '10s'"),
    ("segments:\n  - {duration: 1, control: {11: {stress: 0}}}\n",
     r":\d+: key 'segments\[0\]\.control': component 22 is not controlled"),
    ("segments: []\n", r":\d+: key 'segments': expected at least one segment"),
])
def test_bad_input_names_file_line_and_key(tmp_path, snippet, expected):
    scene = tmp_path / "bad.yaml"
    scene.write_text("scene: point\nmaterial: {props: woodford}\n" + snippet)
    proc = run(scene, tmp_path / "o", check=False)
    assert proc.returncode == 2
    assert str(scene) in proc.stderr and re.search(expected, proc.stderr), proc.stderr


def test_bad_props_name_the_slot(tmp_path):
    scene = tmp_path / "badprops.yaml"
    scene.write_text("scene: point\nmaterial: {props: woodford, set: {lambda_p_soft: -1}}\n"
                     "segments:\n  - {duration: 1, control: {others: {stress: 0}}}\n")
    proc = run(scene, tmp_path / "o", check=False)
    assert proc.returncode == 2 and "PROPS(17)" in proc.stderr and "badprops.yaml:2" in proc.stderr
