"""Meshes made for the answer (docs/adapt.md): the Zienkiewicz-Zhu indicator, adaptation by rerun, the mesh error
a run states in summary.json, the restart's mesh check and the bad inputs of mesh.adapt.

Expected numbers and where they come from:
- the indicator's rate under uniform refinement: for an elastic problem whose displacement is in H^(1+s) the energy
  error of order-k elements falls as h^min(k, s) (Strang & Fix; Ciarlet), and a recovery indicator is equivalent to it
  (Zienkiewicz & Zhu 1987; Ainsworth & Oden 2000, ch. 4). Hertz's contact pressure p = p0 sqrt(1 - r^2/a^2) has an
  infinite gradient at the contact's edge, so the displacement is in H^(5/2 - eps) there: P1 falls as h^1 and P2 as
  h^(3/2).
- the stated time-step error of a held stage's change against Richardson's estimate from two tolerances (backward
  Euler under the output measure is first order in tol).
The stated mesh error's effectivity is measured by bench/adapt_bench.py (docs/performance.md, "Adapted meshes"), not
asserted here: it lies outside [0.5, 2] on several measured cases (docs/adapt.md, "The error estimate").
"""
import math
import re
from pathlib import Path

import numpy as np
import pytest
from camclay9 import driver_path, read_summary, run_driver

from test_contact import ELASTIC, ROLLERS, ROOT, run

BIN = driver_path(root=ROOT).parent
SPHERE = "{shape: sphere, radius: 1, contact: contact, gap: vertical}"


def hertz_scene(order, h_tip, h_far, adapt="", W=8, H=4):
    """An elastic block under a rigid sphere (R = 1) pushed to h = 0.01 (contact radius 0.1), axisymmetric."""
    return f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_block2d.geo
  parameters: {{W: {W}, H: {H}, half: 1, h_tip: {h_tip}, h_far: {h_far}, r_fine: 0.3, r_contact: 0.4}}
  kinematics: axisymmetric
  order: {order}{adapt}
material: {ELASTIC}
boundary:
  fixed: {ROLLERS}
indenter: {SPHERE}
stages:
  - {{name: push, duration: 1, indenter: {{depth: 0.01}}, steps: {{count: 2}}}}
"""


def summary(out):
    return read_summary(out)


def test_indicator_rate_hertz(tmp_path):
    """The indicator's norm on a uniform ladder (the whole mesh halved two or three times): rate 1 on P1 and 3/2 on
    P2 (module docstring), each within 0.25 of the least-squares slope. Measured, with the contact surface's term: 1.06
    (P1, h 0.04 to 0.01) and 1.35 (P2, h 0.08 to 0.01; the contact's edge falls between nodes differently on each
    mesh); without it 0.98 and 1.32. An indicator that recovered P2's stress from the cell means (first order) gives
    about 1."""
    rates = {}
    for order in (1, 2):
        h = np.array([0.04, 0.02, 0.01]) if order == 1 else np.array([0.08, 0.04, 0.02, 0.01])
        eta = []
        for k, hk in enumerate(h):
            out = tmp_path / f"p{order}_{k}"
            run(hertz_scene(order, hk, 8 * hk), out, exe="driver_elastic")
            eta.append(summary(out)["mesh"]["error_indicator"])
        rates[order] = np.polyfit(np.log(h), np.log(eta), 1)[0]
        print(f"P{order}: h {h}, indicator {eta}, rate {rates[order]:.3f}")
    assert abs(rates[1] - 1.0) < 0.25 and abs(rates[2] - 1.5) < 0.25, rates


# Hertz's load at depth 0.01 on the block of hertz_scene, converged: P2 on adapted levels 4, 5 and 6 (24 946, 48 472 and
# 94 582 unknowns) give 1.4986953, 1.4986874 and 1.4986841 (the 2026-11-28 session; the closed form, 1.465, is 2.3 %
# lower: the block is finite). Its uncertainty, about 1e-5 relative, is below the smallest error asserted against it.
HERTZ_LOAD = 1.498683


def test_mesh_error_effectivity_hertz(tmp_path):
    """The stated mesh error of the load (docs/adapt.md, "The error estimate") against its true error, on P1 levels 1 to
    4 of Hertz's contact from a coarse start (1.0 to 0.14 % off): the effectivity (stated over true) within [0.5, 2].
    Measured: 0.50, 0.63, 1.06, 1.03; level 1, whose estimate rests on two levels only, sits at the band's edge (0.5001)
    since the indicator got the contact surface's term (without it: 0.86, 0.96, 0.94, 0.90). The estimate that assumed
    the rate of uniform refinement stated 5.5, 22, 3.3 and 2.9 times the true error here."""
    out = tmp_path / "p1"
    run(hertz_scene(1, 0.05, 1.0, adapt="\n  adapt: {levels: 4, growth: 2}"), out, exe="driver_elastic")
    eff = []
    for level in range(1, 5):
        st = read_summary(out / "adapt" / f"level{level}")["stages"][-1]
        load, err = st["end"]["load"], st["mesh_error"]["end"]["load"]
        eff.append(err / abs(load - HERTZ_LOAD))
        print(f"level {level}: load {load:.7f}, true error {load - HERTZ_LOAD:+.3e}, stated {err:.3e}, effectivity {eff[-1]:.2f}")
    assert all(0.5 <= e <= 2 for e in eff), eff


@pytest.mark.parametrize("order,kin", [(1, "plane_strain"), (2, "plane_strain"), (2, "axisymmetric")])
def test_contact_term_vanishes_on_a_uniform_state(tmp_path, order, kin):
    """The contact surface's term of the indicator (contact_estimate.h) is the residual of the traction, sigma_h n_F
    against the multipliers' lambda n. A flat punch over the whole top of a laterally confined block gives a uniform
    uniaxial strain (test_contact_2d.py), so the stress is exact, the pressure equals -sigma_yy at every node and the
    indicator, recovery and contact term alike, is zero to round-off: stated relative to sigma_yy sqrt(V), below
    1e-7. A term with the traction's sign reversed, or a normal pointing into the cell, gives about 2 sigma_yy
    sqrt(h_F A) per facet, a relative 0.89 here (measured); an indicator without the term would pass, so the term's sign is what
    this asserts (its value where the state is not uniform: the Hertz rate test above and docs/adapt.md)."""
    W, H, depth = 2.0, 1.0, 0.002
    out = tmp_path / f"punch_p{order}_{kin}"
    run(f"""scene: fe
mesh: {{geometry: meshes/rectangle.geo, parameters: {{X0: {0 if kin == "axisymmetric" else -W / 2}, Lx: {W}, Ly: {H}, size: 0.2}},
        kinematics: {kin}, order: {order}}}
material: {ELASTIC}
boundary:
  fixed: [{{group: y0, components: [x, y]}}, {{group: x0, components: [x]}}, {{group: x1, components: [x]}}]
indenter: {{shape: flat_punch, radius: 5, tip: [0, {H}], contact: y1}}
stages:
  - {{name: push, duration: 1, indenter: {{depth: {depth}}}, steps: {{count: 2}}}}
""", out)
    E, nu = 1000.0, 0.3
    syy = E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) * depth / H
    vol = W * H * (math.pi * W if kin == "axisymmetric" else 1)   # int 2 pi r dA = pi W^2 H (r from 0 to W)
    eta = summary(out)["mesh"]["error_indicator"]
    print(f"P{order} {kin}: indicator {eta:.3e}, relative {eta / (syy * math.sqrt(vol)):.3e}")
    assert eta / (syy * math.sqrt(vol)) < 1e-7


def test_adapt_two_ranks(tmp_path):
    """Adaptation on 2 ranks (the indicator's recovery across ranks, the size field gathered on rank 0): the same
    meshes and the same answer as on 1 rank, P2 Hertz with two levels (measured: 313, 909, 1711 cells on both; the
    loads equal to 10 digits)."""
    text = hertz_scene(2, 0.05, 1.0, adapt="\n  adapt: {levels: 2, growth: 2}")
    s = {}
    for n in (1, 2):
        out = tmp_path / f"np{n}"
        run(text, out, exe="driver_elastic", np_=n)
        s[n] = summary(out)
    cells = {n: [lv["cells"] for lv in s[n]["levels"]] for n in s}
    load = {n: s[n]["stages"][-1]["end"]["load"] for n in s}
    print(f"cells {cells}, loads {load}")
    assert cells[1] == cells[2] and len(cells[1]) == 3 and abs(load[2] / load[1] - 1) < 1e-9


def drive(scene_text, out, args=(), exe="driver_elastic"):
    """Run a scene without asserting success: (exit status, stdout + stderr)."""
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(scene_text)
    proc = run_driver(scene, out, args, driver=BIN / exe, timeout=300, check=False)
    return proc.returncode, proc.stdout + proc.stderr


BAD = [
    ("\n  adapt: {levels: 0}", (), ["mesh.adapt.levels", "0"]),
    ("\n  adapt: {levels: 9}", (), ["mesh.adapt.levels", "9"]),
    ("\n  adapt: {growth: 1}", (), ["mesh.adapt.growth", "1.2 to 8", "got 1"]),
    ("\n  adapt: {tol: 0}", (), ["mesh.adapt.tol", "got 0"]),
    ("\n  adapt: {level: 2}", (), ["mesh.adapt", "level"]),
    ("\n  adapt: 3", (), ["mesh.adapt"]),
    ("", ("-adapt_growth", "0.5"), ["-adapt_growth", "0.5", "1.2 to 8"]),
    ("", ("-adapt_levels", "1", "-restart"), ["-restart", "-adapt_levels", "without -restart"]),
    ("", ("-adapt_levels", "9"), ["-adapt_levels", "9"]),
]


@pytest.mark.parametrize("adapt,args,words", BAD)
def test_bad_adapt_input(tmp_path, adapt, args, words):
    """Each bad mesh.adapt key or option: exit status 2, a message naming the key or option and the value, and an
    earlier run's files untouched."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "history.csv").write_text("earlier run\n")
    code, text = drive(hertz_scene(1, 0.05, 0.4, adapt=adapt), out, args)
    print(text.strip().splitlines()[-1])
    assert code == 2 and all(w in text for w in words), text
    assert (out / "history.csv").read_text() == "earlier run\n" and not (out / "adapt").exists()


def test_adapt_needs_geometry(tmp_path):
    """mesh.adapt (or -adapt_levels) on a scene given as a .msh without its geometry: refused, naming the key."""
    first = tmp_path / "first"
    run(hertz_scene(1, 0.05, 0.4), first, exe="driver_elastic")
    text = hertz_scene(1, 0.05, 0.4).replace(f"  geometry: {ROOT}/meshes/indent_block2d.geo\n", f"  file: {first}/mesh.msh\n")
    text = re.sub(r"  parameters: \{[^}]*\}\n", "", text)
    for adapt, args, key in [("\n  adapt: {levels: 1}", (), "mesh.adapt"), ("", ("-adapt_levels", "1"), "-adapt_levels")]:
        code, out = drive(text.replace("  order: 1", "  order: 1" + adapt), tmp_path / "msh", args)
        assert code == 2 and key in out and "mesh.geometry" in out, out


def test_adapt_relative_paths(tmp_path):
    """The README's command form, `driver -input input/<scene>.yaml` from the folder above, with the scene's
    geometry relative to the scene (../meshes/...): the adapted level's .geo includes the scene's .geo, and gmsh
    resolves an Include against the including file's folder, so the path must not be the working directory's.
    Before the fix level 1 stopped with gmsh's "Unable to open file '.../adapt/level1/input/../meshes/...'"."""
    (tmp_path / "input").mkdir()
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "block.geo").write_text((ROOT / "meshes" / "indent_block2d.geo").read_text())
    text = hertz_scene(1, 0.05, 0.4, adapt="\n  adapt: {levels: 1}").replace(f"{ROOT}/meshes/indent_block2d.geo", "../meshes/block.geo")
    (tmp_path / "input" / "hertz.yaml").write_text(text)
    proc = run_driver("input/hertz.yaml", "out", (), driver=BIN / "driver_elastic", cwd=tmp_path, timeout=300, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert len(summary(tmp_path / "out")["levels"]) == 2


def test_restart_refuses_another_mesh(tmp_path):
    """A checkpoint carries its mesh's hash: the same scene file restarted after its .geo changed (so the same scene
    hash, another mesh) is refused with the checkpoint's own message, exit status 2, and the earlier history and mesh
    are untouched. Before the hash the run read another mesh's state ("cannot be read into this run's mesh", or an
    HDF5 error)."""
    geo = tmp_path / "block.geo"
    geo.write_text((ROOT / "meshes" / "indent_block2d.geo").read_text())
    text = hertz_scene(1, 0.05, 0.4).replace(f"{ROOT}/meshes/indent_block2d.geo", str(geo))
    out = tmp_path / "out"
    code, log = drive(text, out, ("-checkpoint_every", "1", "-max_steps", "1"))
    assert code == 0, log
    history, mesh = (out / "history.csv").read_bytes(), (out / "mesh.msh").read_bytes()
    code, log = drive(text, out, ("-restart",))   # the same mesh: the restart goes on
    assert code == 0 and "restart" in log.lower(), log
    code, log = drive(text, out, ("-checkpoint_every", "1", "-max_steps", "1"))
    geo.write_text(geo.read_text().replace("Mesh.MeshSizeMax = h_far;", "Mesh.MeshSizeMax = 0.9 * h_far;"))
    history, mesh = (out / "history.csv").read_bytes(), (out / "mesh.msh").read_bytes()
    code, log = drive(text, out, ("-restart",))
    print(log.strip().splitlines()[-1])
    assert code == 2 and "another mesh" in log, log
    assert (out / "history.csv").read_bytes() == history and (out / "mesh.msh").read_bytes() == mesh


def names_and_counts(msh):
    """The physical groups of a gmsh 4.1 file: name -> (dimension, number of elements of the entities tagged with it)."""
    text = Path(msh).read_text()
    names = {}
    block = text.split("$PhysicalNames\n")[1].split("$EndPhysicalNames")[0].splitlines()[1:]
    for line in block:
        d, tag, name = line.split(maxsplit=2)
        names[(int(d), int(tag))] = name.strip('"')
    ents = text.split("$Entities\n")[1].split("$EndEntities")[0].splitlines()
    tagged = {}   # (dim, entity tag) -> physical tags
    n = list(map(int, ents[0].split()))
    row = 1
    for dim in range(4):
        for _ in range(n[dim]):
            f = ents[row].split()
            row += 1
            k = 4 if dim == 0 else 7
            tagged[(dim, int(f[0]))] = [int(t) for t in f[k + 1:k + 1 + int(f[k])]]
    els = text.split("$Elements\n")[1].split("$EndElements")[0].splitlines()
    out, i = {}, 1
    while i < len(els):
        dim, tag, _, m = map(int, els[i].split())
        for p in tagged.get((dim, tag), []):
            key = names[(dim, p)]
            out[key] = (dim, out.get(key, (dim, 0))[1] + m)
        i += 1 + m
    return out


def test_adapt_keeps_groups_and_planes(tmp_path):
    """One adapted level of the 60-degree sector (3D, P2, elastic, under a Berkovich): the adapted mesh has every
    physical group of the first, of the same dimension and not empty, and more cells where the indicator asked for them
    (more contact-surface faces); the driver's own group checks pass on it (every node of mirror_a, mirror_b and side1
    in its plane, docs/driver.md "Groups against their keys"), and it reports the same quantities."""
    text = f"""scene: fe
mesh:
  geometry: {ROOT}/meshes/indent_sector.geo
  parameters: {{L: 2, span: 60, h_tip: 0.3, h_far: 0.8, r_fine: 0.9, r_contact: 0.95}}
  order: 2
  adapt: {{levels: 1, growth: 2}}
material: {ELASTIC}
boundary:
  fixed: [{{group: bottom, components: [x, y, z]}}]
  mirror:
    - {{group: mirror_a, normal: [0.5, -0.8660254037844386, 0]}}
    - {{group: mirror_b, normal: [1, 0, 0]}}
    - {{group: side1, normal: [0.5, 0.8660254037844386, 0]}}
indenter: {{shape: berkovich, half_angle: 65.27, contact: contact, copies: 6}}
stages:
  - {{name: push, duration: 1, indenter: {{depth: 0.1}}, steps: {{count: 2}}}}
"""
    out = tmp_path / "sector"
    run(text, out, exe="driver_elastic")
    g0 = names_and_counts(out / "adapt" / "level0" / "mesh.msh")
    g1 = names_and_counts(out / "adapt" / "level1" / "mesh.msh")
    print("level 0:", g0, "\nlevel 1:", g1)
    assert set(g0) == set(g1) and all(g1[k][0] == g0[k][0] and g1[k][1] > 0 for k in g0)
    assert g1["contact"][1] > g0["contact"][1]
    s = summary(out)
    assert s["mesh_error"] is not None and len(s["levels"]) == 2 and s["levels"][1]["cells"] > 1.3 * s["levels"][0]["cells"]
    assert (out / "mesh.msh").read_bytes() == (out / "adapt" / "level1" / "mesh.msh").read_bytes()
    # -adapt_growth 4 asks for twice the cells of growth 2 from the same level 0: the meshes differ by about 2 (gmsh
    # makes more cells than asked on both, by about the same ratio)
    run(text, tmp_path / "sector4", exe="driver_elastic", args=["-adapt_growth", "4"])
    ratio = summary(tmp_path / "sector4")["levels"][1]["cells"] / s["levels"][1]["cells"]
    print(f"level 1 cells, growth 4 over growth 2: {ratio:.2f}")
    assert 1.4 < ratio < 2.8


def test_fields_every_does_not_shape_the_mesh(tmp_path):
    """The adapted mesh serves the times the run reports at (its start, the stages' output times and ends), not the
    times a user asks fields at: Hertz pushed in 4 steps, once with fields at the start and the end only and once at
    every step (output.fields_every 1), gives the same size field byte for byte and the same level-1 mesh and load.
    Before the indicator's history kept report times only, each field output entered it: the contact's edge at the
    intermediate steps (radius 0.05 to 0.087 of the final 0.1) raised the indicator inside the final contact, and the
    level-1 meshes differed."""
    base = hertz_scene(1, 0.05, 1.0, adapt="\n  adapt: {levels: 1, growth: 2}").replace("steps: {count: 2}", "steps: {count: 4}")
    runs = {}
    for every in (0, 1):
        out = tmp_path / f"every{every}"
        run(base + f"output: {{fields_every: {every}}}\n", out, exe="driver_elastic")
        runs[every] = out
    written = [len(re.findall(r"<Grid Name=\"output ", (runs[e] / "fields.xmf").read_text())) for e in (0, 1)]
    sizes = [(runs[e] / "adapt" / "level0" / "sizes.pos").read_bytes() for e in (0, 1)]
    s = [summary(runs[e]) for e in (0, 1)]
    cells = [[lv["cells"] for lv in x["levels"]] for x in s]
    print(f"field outputs {written}, cells {cells}, loads {[x['stages'][-1]['end']['load'] for x in s]}")
    assert written[1] > written[0]
    assert sizes[0] == sizes[1] and cells[0] == cells[1]
    assert s[0]["stages"][-1]["end"]["load"] == s[1]["stages"][-1]["end"]["load"]


def test_restart_checks_the_checkpoint_first(tmp_path):
    """A damaged checkpoint (its rank-0 file cut short) or none at all: the checkpoint's own message (exit status 1),
    found before the earlier fields.h5 is opened, so the earlier history, fields and mesh are untouched; with the
    earlier fields.h5 gone as well, still the checkpoint's message (before: "Error in HDF5 call H5Fopen()", the
    fields being opened for appending first)."""
    text = hertz_scene(1, 0.05, 0.4)
    out = tmp_path / "out"
    code, log = drive(text, out, ("-checkpoint_every", "1", "-max_steps", "1"))
    assert code == 0, log
    files = {n: (out / n).read_bytes() for n in ("history.csv", "fields.h5", "fields.xmf", "mesh.msh")}
    ckpt = out / "checkpoint.1.rank0.bin"
    ckpt.write_bytes(ckpt.read_bytes()[:40])
    code, log = drive(text, out, ("-restart",))
    print(log.strip().splitlines()[-1])
    assert code == 1 and "missing or incomplete" in log and "checkpoint.1.rank0.bin" in log, log
    (out / "checkpoint.latest").unlink()
    code, log = drive(text, out, ("-restart",))
    assert code == 1 and "checkpoint.latest is missing" in log, log
    assert all((out / n).read_bytes() == b for n, b in files.items())
    (out / "fields.h5").unlink()
    code, log = drive(text, out, ("-restart",))
    assert code == 1 and "checkpoint.latest is missing" in log and "HDF5" not in log, log


def test_your_own_scene_template(tmp_path):
    """input/your_indent_axi.yaml (README, "Your own indentation scene") runs as a user would run it, here with one
    rerun (-adapt_levels 1): summary.json gives the creep depth (the hold's depth change) and the residual depth with
    their mesh errors, and the log a line per stage and one on how the estimate was made (from two levels: unchecked).
    Expected: the creep depth within 2 % of the P2 reference of
    docs/performance.md ("Adapted meshes", the sphere: 8.196 nm), the residual depth within 1 % (40.44 nm) [reg: this
    code's P2 run], each stated error positive."""
    out = tmp_path / "yours"
    proc = run_driver(ROOT / "input" / "your_indent_axi.yaml", out, ["-adapt_levels", "1"], driver=BIN / "driver",
                      timeout=600)  # DriverError: it failed
    assert "reported, stage 'hold'" in proc.stdout and "mesh error" in proc.stdout
    # one rerun: the estimate rests on one change, and the log and the summary say that nothing checks it yet
    assert "mesh error: the last change over the fall of the squared error indicator, from two levels: nothing checks it yet" in proc.stdout
    assert "from two levels" in summary(out)["mesh_error"]["how"]
    st = summary(out)["stages"]
    creep, h_res = 1000 * st[2]["change"]["depth"], 1000 * st[3]["end"]["depth"]
    e_creep, e_res = 1000 * st[2]["mesh_error"]["change"]["depth"], 1000 * st[3]["mesh_error"]["end"]["depth"]
    print(f"creep depth {creep:.4f} nm (mesh error {e_creep:.3g}), residual depth {h_res:.3f} nm (mesh error {e_res:.3g})")
    assert abs(creep / 8.196 - 1) < 0.02 and abs(h_res / 40.44 - 1) < 0.01 and e_creep > 0 and e_res > 0


def test_time_error_effectivity(tmp_path):
    """The time-step error stated for a held stage's change (docs/adapt.md, "The time-step error"): the kerogen twin
    (input/nanoindent_kerogen_axi.yaml) at the output measure's tol 0.03 and 0.015 on the load and the hold. Backward
    Euler with this control is first order in tol (docs/performance.md, "Time-step error control": the errors halve
    with tol), so the creep depth's true error at tol 0.03 is 2 (h(0.03) - h(0.015)) (Richardson), independent of the
    estimate; expected: estimate / true error in [0.5, 2] (measured 0.79; 0.80 against the extrapolation of tol 0.005
    and 0.0025). Stages whose load changes state none (null): their departures hold the response's curvature."""
    text = (ROOT / "input" / "nanoindent_kerogen_axi.yaml").read_text().replace("../meshes/", f"{ROOT}/meshes/")
    creep, est = {}, {}
    for tol in (0.03, 0.015):
        out = tmp_path / f"tol{tol}"
        scene = text.replace("tol: 1.5e-2", f"tol: {tol}")
        assert scene.count(f"tol: {tol}") == 2
        code, log = drive(scene, out, exe="driver")
        assert code == 0 and "time-step error" in log, log[-2000:]
        st = summary(out)["stages"]
        assert [s["name"] for s in st] == ["start", "load", "hold", "unload"]
        assert st[1]["time_error"] is None and st[3]["time_error"] is None and st[2]["time_error"]["change"]["load"] == 0
        creep[tol], est[tol] = st[2]["change"]["depth"], st[2]["time_error"]["change"]["depth"]
    true = 2 * (creep[0.03] - creep[0.015])
    print(f"creep depth {creep}, stated time-step error {est[0.03]:.4g}, Richardson {true:.4g}, effectivity {est[0.03] / abs(true):.3f}")
    assert 0.5 <= est[0.03] / abs(true) <= 2
