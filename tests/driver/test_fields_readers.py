"""Field output for every reader (issue 11): meshio's XDMF reader loads fields.xmf of small FE scenes (3D P1
and P2, plane strain, axisymmetric, an axisymmetric indentation; 1 and 2 ranks) as a time series, with

- the output times equal to the history times at which fields were written (the initial state and every
  step here), and the same times in fields.h5's /time;
- the point array displacement (n, 3) and the cell arrays stress, strain (full 3x3 Tensor, 9 components),
  phi (and, with Cam-Clay IX, evp_hard, evp_soft, evp, pc_hard, pc_soft), each with its expected shape;
  P2 meshes as quadratic cells (tetra10, with the displacement at the mid-side nodes);
- the displacement of a uniaxially loaded linear-elastic bar (driver_elastic, E = 1000, nu = 0.25) at
  its far corner equal to the closed form at every output, and the out-of-plane (plane strain) or hoop
  (axisymmetric) component, the 33 entry of the tensor, equal to its closed form;

and fields.xmf readable after each output of a run stopped with -max_steps N (N + 1 outputs), and the
output-file protocol: a run that ends before its first output after the initial state leaves an earlier
run's fields.h5 and fields.xmf untouched (its own files stay as .part, and fields.xmf.part names
fields.h5.part: it shows this run's output, not the earlier run's).

$DRIVER and $DRIVER_ELASTIC are the driver executables (CTest sets them). Exit 77 (CTest: skipped)
without meshio (post/requirements.txt; tools/setup.sh installs it).
"""
import os
import xml.etree.ElementTree as ET
from pathlib import Path

import h5py
import numpy as np
import pytest
from camclay9 import driver_path, read_history, run_driver
from camclay9.fields import voigt

try:
    import meshio
except ImportError:                       # the CTest entry maps exit 77 to "skipped"
    print("meshio is not installed (pip install -r post/requirements.txt): skipped")
    os._exit(77)

ROOT = Path(__file__).resolve().parents[2]
DRIVER = driver_path(root=ROOT)
DRIVER_ELASTIC = driver_path("driver_elastic", root=ROOT)
E, NU, P = 1000.0, 0.25, 6.0
ELASTIC = f"{{umat: elastic, props: [{E}, {NU}], nstatv: 0}}"
LX, LY, LZ = 2.0, 1.0, 1.5
NSTEPS = 3


def run(exe, text, out, ranks=1, args=(), check=True):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    return run_driver(scene, out, args, driver=exe, ranks=ranks, cwd=ROOT, timeout=600, check=check)


def bar_3d(order):
    """Uniaxial compression P along z: rollers on x0, y0, z0, pressure on z1, ramped over NSTEPS steps."""
    return f"""scene: fe
mesh: {{geometry: meshes/box.geo, parameters: {{Lx: {LX}, Ly: {LY}, Lz: {LZ}, size: 0.5}}, order: {order}}}
material: {ELASTIC}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}, {{group: z0, components: [z]}}]
  pressure: [z1]
stages:
  - {{name: load, duration: 1, pressure: {{z1: {P}}}, steps: {{count: {NSTEPS}}}}}
output: {{fields_every: 1}}
"""


def bar_2d(kin):
    """Compression P along y on the top y1 of [0, LX] x [0, LY]: rollers on x0 (the axis in axisymmetry), y0."""
    return f"""scene: fe
mesh: {{geometry: meshes/rectangle.geo, parameters: {{Lx: {LX}, Ly: {LY}, size: 0.25}}, order: 1, kinematics: {kin}}}
material: {ELASTIC}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}]
  pressure: [y1]
stages:
  - {{name: load, duration: 1, pressure: {{y1: {P}}}, steps: {{count: {NSTEPS}}}}}
output: {{fields_every: 1}}
"""


def exact(kind, t):
    """Displacement of the far corner (Lx, Ly[, Lz]) at load fraction t, and the 33 slot of stress and strain."""
    p = P * t
    if kind == "3d":
        return np.array([NU * p * LX / E, NU * p * LY / E, -p * LZ / E]), -p, -p / E       # 33: the load axis
    if kind == "plane_strain":      # eps_zz = 0: sigma_zz = -nu p (out of plane)
        return np.array([NU * (1 + NU) * p * LX / E, -(1 - NU**2) * p * LY / E, 0.0]), -NU * p, 0.0
    return np.array([NU * p * LX / E, -p * LY / E, 0.0]), 0.0, NU * p / E   # axisymmetric: hoop u_r / r


def read_series(xmf):
    """meshio's reading of fields.xmf: points, cells, [(t, point_data, cell_data)]."""
    with meshio.xdmf.TimeSeriesReader(xmf) as r:
        pts, cells = r.read_points_cells()
        return pts, cells, [r.read_data(k) for k in range(r.num_steps)]


INDICATOR = ("error_indicator", "error_indicator_max")   # docs/adapt.md


def check_series(out, dim, cell_type, names, hist_times):
    pts, cells, frames = read_series(out / "fields.xmf")
    assert pts.shape[1] == dim and len(cells) == 1 and cells[0].type == cell_type
    nv, nc = pts.shape[0], cells[0].data.shape[0]
    assert cells[0].data.min() == 0 and cells[0].data.max() == nv - 1
    times = [t for t, _, _ in frames]
    assert np.array_equal(times, hist_times), (times, hist_times)
    with h5py.File(out / "fields.h5") as f:
        assert np.array_equal(f["/time"][:, 0], hist_times)
    for _, pd, cd in frames:
        assert set(pd) == {"displacement"} and pd["displacement"].shape == (nv, 3)
        assert set(cd) == set(names), (set(cd), names)
        for name, (arr,) in cd.items():
            assert arr.shape == ((nc, 9) if name in ("stress", "strain", "evp", "evp_hard", "evp_soft") else (nc,)), name
    attr = {a.get("Name"): a.get("AttributeType") for a in ET.parse(out / "fields.xmf").iter("Attribute")}
    assert attr["displacement"] == "Vector" and attr["stress"] == attr["strain"] == "Tensor"
    return pts, frames


@pytest.mark.parametrize("kind,order,ranks", [("3d", 1, 1), ("3d", 1, 2), ("3d", 2, 1),
                                              ("plane_strain", 1, 1), ("axisymmetric", 1, 2)])
def test_uniaxial_bar(tmp_path, kind, order, ranks):
    dim = 3 if kind == "3d" else 2
    out = tmp_path / f"{kind}{order}_{ranks}"
    run(DRIVER_ELASTIC, bar_3d(order) if kind == "3d" else bar_2d(kind), out, ranks)
    hist = read_history(out)
    assert hist.size == NSTEPS + 1              # the initial state and one row per step; fields: the same
    cell_type = {(3, 1): "tetra", (3, 2): "tetra10", (2, 1): "triangle", (2, 2): "triangle6"}[dim, order]
    pts, frames = check_series(out, dim, cell_type, {"stress", "strain", "phi", *INDICATOR}, hist["time"])
    corner = int(np.argmin(np.sum((pts - np.array([LX, LY, LZ][:dim])) ** 2, axis=1)))
    assert np.allclose(pts[corner], [LX, LY, LZ][:dim], atol=1e-12)
    for t, pd, cd in frames:
        u, s33, e33 = exact(kind, t)
        err = np.max(np.abs(pd["displacement"][corner] - u)) / (P * LZ / E)
        print(f"{kind} P{order} {ranks} rank(s) t = {t:.4g}: corner u {pd['displacement'][corner]}, exact {u}, error {err:.1e}")
        assert err < 1e-9
        stress, strain = voigt(cd["stress"][0]), voigt(cd["strain"][0], strain=True)
        assert np.allclose(stress[:, 2], s33, atol=1e-9 * P) and np.allclose(strain[:, 2], e33, atol=1e-9 * P / E)
        if dim == 2:
            assert not np.any(stress[:, 4:]) and not np.any(pd["displacement"][:, 2])
        if order == 2:                # every node, mid-side ones included, carries the linear field exactly
            x = pts
            uex = np.array([NU * t * P * x[:, 0] / E, NU * t * P * x[:, 1] / E, -t * P * x[:, 2] / E]).T
            assert np.max(np.abs(pd["displacement"] - uex)) < 1e-9 * P * LZ / E


def test_indentation_scene_two_ranks(tmp_path):
    """An axisymmetric cone indentation on Cam-Clay IX (coarse, 2 ranks): every cell field, the times."""
    out = tmp_path / "indent"
    run(DRIVER, """scene: fe
mesh:
  geometry: meshes/indent_block2d.geo
  parameters: {W: 2, H: 1, half: 1, h_tip: 0.1, h_far: 0.3, r_fine: 0.3, r_contact: 0.8}
  kinematics: axisymmetric
material: {props: woodford, set: {phi: 0.5, tol: 1.0e-4}}
boundary:
  fixed: [{group: bottom, components: [x, y]}, {group: left, components: [x]}, {group: right, components: [x]}]
indenter: {shape: cone, half_angle: 70.3, contact: contact}
stages:
  - {name: push, duration: 1, indenter: {depth: 0.02}, steps: {count: 2}}
output: {fields_every: 1}
""", out, ranks=2)
    hist = read_history(out)
    _, frames = check_series(out, 2, "triangle", {"stress", "strain", "evp_hard", "evp_soft", "evp", "pc_hard",
                                                  "pc_soft", "phi", *INDICATOR}, hist["time"])
    assert np.all(frames[-1][2]["phi"][0] == 0.5)
    uy = frames[-1][1]["displacement"][:, 1]
    assert abs(uy.min() + 0.02) < 1e-9          # the tip vertex follows the indenter to the depth 0.02


def test_xmf_valid_after_each_output(tmp_path):
    """-max_steps N: the run stops after N steps, and fields.xmf (promoted after the first step) holds the
    N + 1 outputs 0, ..., N / NSTEPS."""
    for n in (1, 2):
        out = tmp_path / f"stop{n}"
        assert f"stopped after {n} steps" in run(DRIVER_ELASTIC, bar_3d(1), out, args=["-max_steps", str(n)]).stdout
        _, _, frames = read_series(out / "fields.xmf")
        assert np.allclose([t for t, _, _ in frames], np.arange(n + 1) / NSTEPS, rtol=1e-14)
        assert not (out / "fields.h5.part").exists() and not (out / "fields.xmf.part").exists()


def test_unpromoted_run_keeps_earlier_results(tmp_path):
    """A run into the directory of an earlier one that ends before its first step (here stopped by
    -max_steps 0 after writing the initial state) leaves its files as
    fields.h5.part / fields.xmf.part (a valid index of its one output) and the earlier fields.h5 and
    fields.xmf byte for byte."""
    out = tmp_path / "keep"
    run(DRIVER_ELASTIC, bar_3d(1), out)
    before = {n: (out / n).read_bytes() for n in ("fields.h5", "fields.xmf")}
    proc = run(DRIVER_ELASTIC, bar_3d(1).replace("fields_every: 1", "fields_every: 0"), out, args=["-max_steps", "0"])
    assert "stopped after 0 steps" in proc.stdout
    assert {n: (out / n).read_bytes() for n in before} == before
    assert len(read_series(out / "fields.xmf")[2]) == NSTEPS + 1
    part = ET.parse(out / "fields.xmf.part")
    assert [t.get("Value") for t in part.iter("Time")] == ["0"]
    assert all(d.text.startswith("fields.h5.part:") for d in part.iter("DataItem"))   # this run's data, not the earlier run's
    assert len(read_series(out / "fields.xmf.part")[2]) == 1
    with h5py.File(out / "fields.h5.part") as f:
        assert f["/time"][:, 0].tolist() == [0.0] and list(f["/fields/displacement"]) == ["000000"]
