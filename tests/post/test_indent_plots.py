"""Tests of post/indent_plots.py on a synthetic indentation run built here (no driver needed).

The run: stages load (0-10 s), hold (10-2010 s), unload (2010-2030 s); history.csv with known loads and
depths (creep depth 0.375 - 0.25 = 0.125 um exactly); fields.h5 in the driver's layout on a
16-triangle mesh of [-1, 1] x [-1, 0] (top at y = 0, tip at the origin) with analytic fields:
  u = d(t) g(x) (0.1 x, -1),  g = exp(-|x|^2),  d(t) = the depth at the output times (u_y(0, 0) = -d);
  evp = a(t) g(centroid) E0 (engineering shear), stress = s(t) g(centroid) S0;
and /time with the output times 0, 10, 110, 510, 2010, 2030 s. Checks: every subcommand runs and
writes its figures; creep.json holds the known numbers; the printed numbers of figs 11-13, vectors and
profile are the analytic ones; the tensor measures; missing files, columns and datasets are named.
"""
import json
import re
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest
from camclay9.fields import full
from camclay9 import indent_plots as ip

ROOT = Path(__file__).resolve().parents[2]

COLUMNS = ip.HISTORY_COLUMNS
# history rows: (time, stage, name, load, depth)
ROWS = [(0.0, 0, "load", 0.0, 0.0), (5.0, 0, "load", 300.0, 0.125), (10.0, 0, "load", 600.0, 0.25),
        (110.0, 1, "hold", 600.0, 0.3), (510.0, 1, "hold", 600.0, 0.34), (1010.0, 1, "hold", 600.0, 0.36),
        (2010.0, 1, "hold", 600.0, 0.375), (2020.0, 2, "unload", 300.0, 0.3), (2030.0, 2, "unload", 0.0, 0.2)]
T_OUT = np.array([0.0, 10.0, 110.0, 510.0, 2010.0, 2030.0])
D_OUT = np.array([0.0, 0.25, 0.3, 0.34, 0.375, 0.2])          # depth at the output times
A_OUT = np.array([0.0, 0.5, 1.0, 2.0, 3.0, 3.0])              # evp amplitude
S_OUT = np.array([0.0, 100.0, 90.0, 80.0, 70.0, 0.0])         # stress amplitude
E0 = np.array([1e-3, -2e-3, 0.5e-3, 4e-3, 0.0, 0.0])          # engineering shear 12
S0 = np.array([-1.0, -3.0, -1.2, 0.5, 0.0, 0.0])


def write_history(run, rows=ROWS, drop=None):
    names = [c for c in COLUMNS if c != drop]
    lines = [",".join(names)]
    for k, (t, st, name, P, h) in enumerate(rows):
        vals = dict.fromkeys(COLUMNS, "0")
        vals.update(time=repr(t), stage=str(st), stage_name=name, step=str(k), load=repr(P), depth=repr(h))
        lines.append(",".join(vals[c] for c in names))
    (run / "history.csv").write_text("\n".join(lines) + "\n")


def grid_2d():
    xs, ys = np.linspace(-1, 1, 5), np.linspace(-1, 0, 3)
    x = np.array([(a, b) for b in ys for a in xs])
    idx = lambda i, j: j * 5 + i          # noqa: E731
    cells = []
    for j in range(2):
        for i in range(4):
            cells += [(idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)), (idx(i, j), idx(i + 1, j + 1), idx(i, j + 1))]
    return x, np.array(cells)


def grid_3d():
    from scipy.spatial import Delaunay
    g = np.linspace(-1, 1, 3)
    x = np.array([(a, b, c) for c in (-1.0, 0.0) for b in g for a in g])
    return x, Delaunay(x).simplices


def write_fields(run, x, cells, skip=()):
    dim, nt = x.shape[1], T_OUT.size
    g = np.exp(-np.sum(x ** 2, axis=1))
    u = np.zeros((nt, len(x), dim))
    u[:, :, 0] = 0.1 * D_OUT[:, None] * (g * x[:, 0])[None]
    u[:, :, dim - 1] = -D_OUT[:, None] * g[None]
    gc = np.exp(-np.sum(x[cells].mean(axis=1) ** 2, axis=1))
    with h5py.File(run / "fields.h5", "w") as f:          # the driver's layout (camclay9.fields)
        f["/time"] = T_OUT[:, None]
        f["/mesh/coordinates"] = x
        f["/mesh/cells"] = cells.astype(np.int32)
        for k in range(nt):
            f[f"/fields/displacement/{k:06d}"] = np.pad(u[k], ((0, 0), (0, 3 - dim)))
            for name, amp, v in (("evp", A_OUT, E0), ("evp_soft", A_OUT, E0), ("evp_hard", 0 * A_OUT, E0),
                                 ("strain", A_OUT, E0), ("stress", S_OUT, S0)):
                if name not in skip:           # full 3x3 tensors, strains as tensors (camclay9.fields)
                    f[f"/fields/{name}/{k:06d}"] = full(amp[k] * gc[:, None] * v[None, :], strain=name != "stress")
            for name in ("pc_hard", "pc_soft", "phi"):
                f[f"/fields/{name}/{k:06d}"] = np.ones(len(cells))
    return gc


@pytest.fixture(scope="module")
def run2d(tmp_path_factory):
    run = tmp_path_factory.mktemp("indent2d")
    write_history(run)
    x, cells = grid_2d()
    gc = write_fields(run, x, cells)
    return run, x, cells, gc


def test_ph_creep_json(run2d, capsys):
    run = run2d[0]
    assert ip.main([str(run)]) == 0                          # ph is the default subcommand
    for png in ("ph.png", "creep.png"):
        assert (run / png).stat().st_size > 0
    got = json.loads((run / "creep.json").read_text())
    assert got["max_load"] == 600.0
    assert got["depth_end_of_load"] == 0.25
    assert got["depth_end_of_hold"] == 0.375
    assert got["creep_depth"] == 0.125                       # the synthetic hold depth increase, exactly
    assert got["residual_depth"] == 0.2
    assert (got["hold_start_time"], got["hold_end_time"]) == (10.0, 2010.0)
    out = capsys.readouterr().out
    assert "P-h stage 1 (hold): 5 points" in out and "creep depth 0.125 um" in out


def test_ph_without_hold_stage(tmp_path, capsys):
    write_history(tmp_path, rows=[r[:2] + ("load",) + r[3:] for r in ROWS])
    assert ip.main(["ph", str(tmp_path), "--out", str(tmp_path / "o")]) == 0
    got = json.loads((tmp_path / "o" / "creep.json").read_text())
    assert got["creep_depth"] is None and got["max_load"] == 600.0 and got["residual_depth"] == 0.2
    assert "no stage named 'hold'" in capsys.readouterr().out


def test_compare(run2d, tmp_path, capsys):
    other = tmp_path / "other"
    other.mkdir()
    write_history(other, rows=[(t, s, n, P, 2 * h) for t, s, n, P, h in ROWS])
    assert ip.main(["compare", str(run2d[0]), str(other), "--labels", "a", "b", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "compare_ph.png").exists() and (tmp_path / "compare_creep.png").exists()
    out = capsys.readouterr().out
    assert "creep a: 5 points over 2000 s" in out and "creep depth 0.125 um" in out
    assert "creep b: 5 points over 2000 s" in out and "creep depth 0.25 um" in out
    with pytest.raises(SystemExit, match="2 runs but 1 labels"):
        ip.main(["compare", str(run2d[0]), str(other), "--labels", "a"])


def test_fields(run2d, tmp_path, capsys):
    run, x, cells, gc = run2d
    assert ip.main(["fields", str(run), "--out", str(tmp_path), "--window", "0.6"]) == 0
    for k in (9, 10, 11, 12, 13):
        assert (tmp_path / f"fig{k}.png").stat().st_size > 0
    out = capsys.readouterr().out
    for th in (100, 500, 2000):                                # outputs at exactly these hold times
        assert f"hold time {th} s (asked {th} s)" in out
    # fig13 by default: the mean over |x| < a/4, -a/2 < y < 0, a = 2.5 x the depth at the end of loading (0.25 um):
    # its |sigma| change over the hold = (s(2010) - s(10)) |S0| x the area mean of g over the region
    box = (-0.625 / 4, 0.625 / 4, -0.625 / 2, 0.0)
    with ip.Fields(run) as F:
        w = ip.clipped_areas(F, box)
    m = re.search(r"fig13 mean over \|x\| < (\S+), (\S+) < y < 0 .* change (\S+) MPa", out)
    assert (float(m.group(1)), float(m.group(2))) == pytest.approx(box[1:3], rel=5e-3)
    expect = (S_OUT[4] - S_OUT[1]) * np.sum(gc * w) / np.sum(w) * ip.tensor_norm(S0, False)
    assert float(m.group(3)) == pytest.approx(expect, rel=1e-5)
    # --probe: the one cell beneath the tip, its |sigma| change over the hold = (s(2010) - s(10)) g_c |S0|
    assert ip.main(["fields", str(run), "--out", str(tmp_path), "--probe", "0", "-0.000001"]) == 0
    out = capsys.readouterr().out
    with ip.Fields(run) as F:
        c, _ = ip.probe_cell(F, None)
    assert 12 in cells[c] and x[cells[c]].mean(axis=0)[1] < 0          # a cell at the tip (vertex 12 = origin)
    assert np.argmin(np.hypot(*(x[cells].mean(axis=1) - [0, -1e-6]).T)) == c
    m = re.search(r"fig13 cell (\d+) .* change (\S+) MPa", out)
    assert int(m.group(1)) == c
    expect = (S_OUT[4] - S_OUT[1]) * gc[c] * ip.tensor_norm(S0, False)
    assert float(m.group(2)) == pytest.approx(expect, rel=1e-5)
    # the deformed-mesh variant runs too
    assert ip.main(["fields", str(run), "--out", str(tmp_path / "d"), "--deformed", "--scale", "2",
                    "--hold-times", "2000"]) == 0


def test_vectors_and_profile_2d(run2d, tmp_path, capsys):
    run = run2d[0]
    assert ip.main(["vectors", str(run), "--out", str(tmp_path), "--window", "0.8"]) == 0
    out = capsys.readouterr().out
    m = re.search(r"max \|du\| (\S+) um at \((\S+), (\S+)\) um", out)
    assert float(m.group(1)) == pytest.approx(0.375 - 0.25, rel=1e-5)       # at the tip, the creep depth
    assert (float(m.group(2)), float(m.group(3))) == (0.0, 0.0)
    assert ip.main(["profile", str(run), "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    m = re.search(r"(\d+) vertices on y = 0, vertical displacement min (\S+) um at \((\S+)\)", out)
    assert int(m.group(1)) == 5 and float(m.group(2)) == pytest.approx(-0.2, rel=1e-5) and float(m.group(3)) == 0
    assert (tmp_path / "vectors.png").exists() and (tmp_path / "profile.png").exists()


def test_profile_3d(tmp_path, capsys):
    x, cells = grid_3d()
    write_fields(tmp_path, x, cells)
    assert ip.main(["profile", str(tmp_path), "--time", "2010"]) == 0
    out = capsys.readouterr().out
    m = re.search(r"at t = (\S+) s .*: (\d+) vertices on z = 0, vertical displacement min (\S+) um", out)
    assert float(m.group(1)) == 2010 and int(m.group(2)) == 9 and float(m.group(3)) == pytest.approx(-0.375, rel=1e-5)
    assert (tmp_path / "profile.png").exists()
    write_history(tmp_path)
    with pytest.raises(SystemExit, match=r"fields\.h5: fields needs a 2D run"):
        ip.main(["fields", str(tmp_path)])


def test_tensor_measures():
    v = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0])
    assert ip.tensor_norm(v, False) == pytest.approx(np.sqrt(14 + 2 * (16 + 25 + 36)))
    assert ip.tensor_norm(v, True) == pytest.approx(np.sqrt(14 + 2 * (4 + 6.25 + 9)))
    assert ip.trace(v) == 6.0
    assert ip.dev_norm(v, True) == pytest.approx(np.sqrt(1 + 0 + 1 + 2 * (4 + 6.25 + 9)))
    assert ip.dev_norm(np.array([2.0, 2.0, 2.0, 0, 0, 0]), False) == pytest.approx(0.0)


def test_cli_default_is_ph(run2d, tmp_path):
    proc = subprocess.run([sys.executable, str(ROOT / "post" / "indent_plots.py"), str(run2d[0]), "--out", str(tmp_path)],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert (tmp_path / "ph.png").exists() and json.loads((tmp_path / "creep.json").read_text())["creep_depth"] == 0.125


def test_missing_inputs_are_named(tmp_path):
    with pytest.raises(SystemExit, match=r"history\.csv: no such file"):
        ip.main(["ph", str(tmp_path)])
    write_history(tmp_path, drop="depth")
    with pytest.raises(SystemExit, match=r"history\.csv: column\(s\) 'depth' missing"):
        ip.main(["ph", str(tmp_path)])
    write_history(tmp_path)
    with pytest.raises(SystemExit, match=r"fields\.h5: no such file"):
        ip.main(["fields", str(tmp_path)])
    x, cells = grid_2d()
    write_fields(tmp_path, x, cells, skip=("evp",))
    with pytest.raises(SystemExit, match=r"fields\.h5: dataset '/fields/evp' is missing"):
        ip.main(["fields", str(tmp_path)])
    with h5py.File(tmp_path / "fields.h5", "a") as f:
        del f["/time"]
    with pytest.raises(SystemExit, match=r"fields\.h5: dataset '/time' is missing"):
        ip.main(["profile", str(tmp_path)])
    write_history(tmp_path, rows=[r[:2] + ("load",) + r[3:] for r in ROWS])
    write_fields(tmp_path, x, cells)
    with pytest.raises(SystemExit, match=r"history\.csv: no stage named 'hold' \(stage names: load\)"):
        ip.main(["vectors", str(tmp_path)])


def test_colour_limits_are_robust():
    """One singular cell (1e6) among values spread over [0, 1]: the default limits are the 1-99 %
    percentiles of the cells, [0.01, 0.99] to 1e-12 for this evenly spaced set; --clip 0 is min..max."""
    v = np.append(np.linspace(0.0, 1.0, 1001), 1e6)
    mask = np.ones(v.size, bool)
    lo, hi, cmap = ip.color_limits(v, mask, False)
    assert cmap == "viridis" and np.allclose([lo, hi], np.percentile(v, [1, 99]), rtol=1e-12)
    assert 0.009 < lo < 0.011 and 0.98 < hi < 1.0
    assert ip.color_limits(v, mask, False, clip=0)[:2] == (0.0, 1e6)
    m = ip.color_limits(np.append(np.linspace(-1.0, 1.0, 1001), -1e6), mask, True)[1]   # signed: symmetric
    assert 0.97 < m < 1.0
    assert "1–99 % percentiles" in ip.clip_label(1.0)
