"""Tests of camclay9.lomnitz and post/point_plots.py.

(a) the Lomnitz fit recovers the paper's theta = 0 values (B = 9.97e-5, tau = 385 s, theory.md §5.4);
(b) point_plots runs on a realistic material-point history made by the independent reference
    integration (python/camclay9/reference.py): Woodford props, theta = 0, both frames at
    -35 MPa, jump to diag(-35, -35, -75) MPa and creep for 36000 s;
(c) a history.csv with a missing column is rejected with the file and the column named.
"""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from camclay9 import reference as ref
from camclay9 import point_plots as pp
from camclay9.lomnitz import lomnitz, lomnitz_fit

ROOT = Path(__file__).resolve().parents[2]

B_PAPER, TAU_PAPER = 9.97e-5, 385.0


# ------------------------------------------------------------------ (a) Lomnitz fit
def test_lomnitz_fit_exact_data():
    t = np.r_[0.0, np.geomspace(1.0, 36000.0, 80)]
    B, tau = lomnitz_fit(t, lomnitz(t, B_PAPER, TAU_PAPER))
    assert abs(B / B_PAPER - 1) < 1e-6 and abs(tau / TAU_PAPER - 1) < 1e-6, (B, tau)


def test_lomnitz_fit_noisy_data():
    t = np.geomspace(1.0, 36000.0, 80)
    rng = np.random.default_rng(2021)
    eps = lomnitz(t, B_PAPER, TAU_PAPER) * (1.0 + 0.01 * rng.standard_normal(t.size))   # 1 % noise
    B, tau = lomnitz_fit(t, eps)
    assert abs(B / B_PAPER - 1) < 0.05 and abs(tau / TAU_PAPER - 1) < 0.05, (B, tau)


def test_lomnitz_fit_rejects_nothing_to_fit():
    with pytest.raises(ValueError):
        lomnitz_fit([0.0, 1.0, 2.0], [0.0, 0.0, 0.0])


# ------------------------------------------------------------------ (b) a realistic run directory
def write_run(run_dir, drop_column=None):
    """history.csv + scene.json of the creep scenario from the reference integration.

    Rows: 0 the initial state (both frames at -35 I, zero strain); 1 the state right after the elastic
    jump (t = 0, segment 0 'load'); then segment 1 'creep' at t = 1 ... 36000 s. Columns the reference
    does not provide (iteration counts, flags) are zero."""
    props = list(ref.WOODFORD) + [0.0, 0.0, 0.0, 1.0]                # tol = 0, normal (0, 0, 1)
    sig0, sig = -35.0 * np.eye(3), np.diag([-35.0, -35.0, -75.0])
    times = np.r_[0.0, np.geomspace(1.0, 36000.0, 50)]
    r = ref.creep_mixture(props, [0, 0, 1], sig0, sig, times)
    n = times.size + 1
    cols = {c: np.zeros(n) for c in pp.HISTORY_COLUMNS}
    cols["time"][1:] = times
    cols["step"] = np.arange(n, dtype=float)
    cols["stage"][2:] = 1
    cols["dt"][1:] = np.diff(cols["time"])
    v0 = np.array([-35.0, -35.0, -35.0, 0.0, 0.0, 0.0])
    phi = props[0]
    series = {"eps": r["strain"], "sig_hard": r["stress_hard"], "sig_soft": r["stress_soft"],
              "sig": phi * r["stress_hard"] + (1 - phi) * r["stress_soft"],
              "evp_hard": r["evp_hard"], "evp_soft": r["evp_soft"], "evp": r["evp"]}
    for name, arr in series.items():
        for k, c in enumerate(pp.VOIGT):
            cols[f"{name}_{c}"][1:] = arr[:, k]
            if name.startswith("sig"):
                cols[f"{name}_{c}"][0] = v0[k]
    cols["pc_hard"][:] = np.r_[props[11], r["pc_hard"]]
    cols["pc_soft"][:] = np.r_[props[17], r["pc_soft"]]
    names = [c for c in pp.HISTORY_COLUMNS if c != drop_column]
    np.savetxt(run_dir / "history.csv", np.column_stack([cols[c] for c in names]), delimiter=",",
               header=",".join(names), comments="", fmt="%.17g")
    scene = {"name": "woodford_theta0_point", "props": props, "normal": [0.0, 0.0, 1.0],
             "units": {"stress": "MPa", "time": "s"},
             "segments": [{"name": "load", "t_start": 0.0, "t_end": 0.0, "creep": False, "axis": 2},
                          {"name": "creep", "t_start": 0.0, "t_end": 36000.0, "creep": True, "axis": 2}]}
    (run_dir / "scene.json").write_text(json.dumps(scene, indent=1))
    return r


def test_point_plots_on_reference_run(tmp_path):
    run, out = tmp_path / "run", tmp_path / "plots"
    run.mkdir()
    r = write_run(run)
    res = subprocess.run([sys.executable, str(ROOT / "post" / "point_plots.py"), str(run), "--out", str(out)],
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    for png in ("stress_path.png", "stress_strain.png", "creep_creep.png"):
        f = out / png
        assert f.is_file() and f.stat().st_size > 1000, png
        assert f.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n", png

    line = [s for s in res.stdout.splitlines() if s.startswith("creep creep:")]
    assert len(line) == 1, res.stdout
    print(line[0])
    B_out = float(line[0].split("B = ")[1].split(",")[0])
    tau_out = float(line[0].split("tau = ")[1].split()[0])
    fit = json.loads((out / "creep_fit.json").read_text())["creep"]
    assert fit["B"] > 0 and fit["tau"] > 0 and B_out > 0 and tau_out > 0
    assert abs(B_out / fit["B"] - 1) < 1e-3 and abs(tau_out / fit["tau"] - 1) < 1e-3

    # the creep curve is measured from the state after the elastic jump, and the fit follows it
    creep = -(r["strain"][:, 2] - r["strain"][0, 2])
    model = lomnitz(r["time"], fit["B"], fit["tau"])
    assert np.max(np.abs(model - creep)) < 0.1 * creep[-1]


# ------------------------------------------------------------------ (c) malformed input
def test_missing_column_is_named(tmp_path):
    write_run(tmp_path, drop_column="sig_hard_33")
    with pytest.raises(ValueError) as err:
        pp.read_history(tmp_path / "history.csv")
    msg = str(err.value)
    assert "history.csv" in msg and "sig_hard_33" in msg, msg

    res = subprocess.run([sys.executable, str(ROOT / "post" / "point_plots.py"), str(tmp_path)],
                         capture_output=True, text=True, timeout=600)
    assert res.returncode != 0
    assert "history.csv" in res.stderr and "sig_hard_33" in res.stderr, res.stderr
