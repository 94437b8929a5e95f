"""camclay9.paper_numbers: the numbers of docs/paper.md and the trend checks of tools/reproduce.py --quick,
on synthetic runs whose answers are known."""
import json
from pathlib import Path

import numpy as np
import pytest
from camclay9 import paper_numbers as pn
from camclay9.lomnitz import lomnitz

ROOT = Path(__file__).resolve().parents[2]


def write_triaxial(run, t, eps, soft, hard, t_hold=1.0e6):
    """A history.csv as the FE triaxial scene writes it: stage 0 the hold, stage 1 the creep (compression
    negative)."""
    run.mkdir(parents=True)
    rows = ["time,stage,step,eps_33,evp33_hard_mean,evp33_soft_mean", f"{t_hold},0,1,-0.001,-0.0001,-0.0002"]
    rows += [f"{t_hold + ti},1,{k + 2},{-0.001 - e},{-0.0001 - h},{-0.0002 - s}"
             for k, (ti, e, s, h) in enumerate(zip(t, eps, soft, hard))]
    (run / "history.csv").write_text("\n".join(rows) + "\n")


def test_lomnitz_curve_gives_its_own_parameters_however_sampled(tmp_path):
    t = np.r_[0.0, np.geomspace(0.01, 36000.0, 300)]
    eps = lomnitz(t, 9.97e-5, 385.0)
    write_triaxial(tmp_path / "r", t, eps, eps, 0.01 * eps)
    n = pn.triaxial_numbers(tmp_path / "r", 0)
    for fit in n["fits"].values():
        assert fit["B"] == pytest.approx(9.97e-5, rel=1e-3) and fit["tau"] == pytest.approx(385.0, rel=1e-2)
    assert n["creep"]["385"] == pytest.approx(9.97e-5 * np.log(2.0), rel=1e-4)
    assert n["creep"]["385"] == pytest.approx(n["paper_creep"]["385"], rel=1e-4)
    assert n["soft_over_hard"]["385"] == pytest.approx(100.0)
    assert n["soft_over_hard_10x_until"] == pytest.approx(36000.0)
    assert n["soft_over_hard_min_early"] == pytest.approx(100.0) and n["soft_over_hard_min"] == pytest.approx(100.0)


def test_sampling_changes_the_fit_of_a_non_lomnitz_curve(tmp_path):
    """A curve that is not a Lomnitz law (two log terms): the even-in-t fit weighs the late times and
    reads a larger tau than the even-in-log-t fit (issue 14: 597 s vs 208 s on the model's point curve)."""
    t = np.r_[0.0, np.geomspace(0.01, 36000.0, 400)]
    eps = lomnitz(t, 4e-5, 20.0) + lomnitz(t, 4e-5, 3000.0)
    write_triaxial(tmp_path / "r", t, eps, eps, eps)
    f = pn.triaxial_numbers(tmp_path / "r", 0)["fits"]
    assert f["even_t"]["tau"] > 1.5 * f["even_log_t"]["tau"]


def test_last_time_above_interpolates_the_crossing():
    t = np.array([1.0, 2.0, 3.0, 4.0])
    r = np.array([30.0, 20.0, 5.0, 4.0])
    assert pn.last_time_above(t, r, 10.0) == pytest.approx(2.0 + 10.0 / 15.0)
    assert pn.last_time_above(t, r, 50.0) is None


def trends_input(creep_slow=0.01, creep_fast=0.04, bedding=(0.7, 0.72, 0.74, 0.76, 0.8), ratio=(60.0, 80.0)):
    ind = {f"loading_rate_a{a}": {"depth_end_of_load": d, "creep_depth": c}
           for a, d, c in zip(pn.ALPHAS, (0.21, 0.19, 0.17), (creep_slow, 0.02, creep_fast))}
    ind.update({f"bedding_theta{t}": {"creep_depth": c} for t, c in zip(pn.THETAS_BEDDING, bedding)})
    tri = {th: {"creep": {"385": c, "3600": 2 * c, "36000": 4 * c}, "soft_over_hard": {"385": r},
                "soft_over_hard_min_early": r, "soft_over_hard_10x_until": 2000.0, "duration": 36000.0}
           for th, c, r in ((0, 6e-5, ratio[0]), (90, 4e-5, ratio[1]))}
    return {"indent": ind, "triaxial": tri, "fig13": {}}


def test_trends_pass_and_each_fails_when_its_trend_is_reversed():
    assert all(t["ok"] for t in pn.check_trends(trends_input()))
    assert not pn.check_trends(trends_input(creep_slow=0.05))[0]["ok"]            # slow loading creeps more
    assert not pn.check_trends(trends_input(bedding=(0.5, 0.6, 0.7, 0.8, 0.9)))[1]["ok"]  # 1.8 > 1.5
    n = trends_input()
    n["triaxial"][90]["creep"]["36000"] = 1e-3                                    # theta 90 overtakes
    assert not pn.check_trends(n)[2]["ok"]
    assert not pn.check_trends(trends_input(ratio=(60.0, 8.0)))[3]["ok"]          # hard frame not negligible
    n = trends_input()
    del n["triaxial"][90]
    assert not any(t["ok"] for t in pn.check_trends(n)[1:])                        # a missing run fails


def test_stated_errors_of_an_adapted_run(tmp_path):
    """An adapted run's summary.json (docs/adapt.md) gives the table of Figs. 3-5 its stated errors, in place of the
    lower-bound flag: the creep depth's mesh and time-step errors (the hold's), the residual depth's (the unload's
    end), the number of meshes; a run on one mesh states none."""
    import json
    run = tmp_path / "bn"
    run.mkdir()
    stage = lambda name, me, te: {"name": name, "end": {"depth": 1.0}, "change": {"depth": 0.1}, "mesh_error": me, "time_error": te}
    js = {"stages": [stage("start", None, None), stage("load", {"end": {"depth": 0}, "change": {"depth": 0}}, None),
                     stage("hold", {"end": {"depth": 0.002}, "change": {"depth": 0.003}}, {"change": {"depth": 0.0004}}),
                     stage("unload", {"end": {"depth": 0.021}, "change": {"depth": 0.02}}, None)],
          "levels": [{}, {}, {}, {}]}
    (run / "summary.json").write_text(json.dumps(js))
    s = pn.stated_errors(run)
    assert s == {"meshes": 4, "creep_mesh_error": 0.003, "creep_time_error": 0.0004, "residual_mesh_error": 0.021}
    assert pn.stated_text(s, "creep_mesh_error", "creep_time_error") == " (± 0.003 mesh, 4 meshes; ± 0.0004 time steps)"
    assert pn.stated_errors(tmp_path) == {}


def test_fig11_zone_of_a_half_model_is_the_whole_blocks():
    """Fig. 11's zone numbers (camclay9.paper_fields.sector_shares) on a mesh mirror-symmetric about x = 0 and on its
    half x >= 0 (the loading-rate scenes' half model) under a symmetric field: the same shares and the same fill of the
    half-disc (the half holds half of the zone's area, which the fill counts twice)."""
    from types import SimpleNamespace
    from camclay9 import paper_fields as pf

    n = 40                                                  # the half [0, 1] x [-1, 0], two triangles per square
    xs, ys = np.linspace(0, 1, n + 1), np.linspace(-1, 0, n + 1)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    x = np.c_[X.ravel(), Y.ravel()]
    v = lambda i, j: i * (n + 1) + j
    cells = np.array([c for i in range(n) for j in range(n)
                      for c in ((v(i, j), v(i + 1, j), v(i + 1, j + 1)), (v(i, j), v(i + 1, j + 1), v(i, j + 1)))])
    whole_x = np.r_[x, x * [-1, 1]]                         # the mirror image's nodes follow
    whole_cells = np.r_[cells, cells + len(x)]

    def run(x, cells):
        F = SimpleNamespace(x=x, cells=cells, centroids=x[cells].mean(axis=1))
        e1, e2 = (x[cells[:, 1]] - x[cells[:, 0]]), (x[cells[:, 2]] - x[cells[:, 0]])
        H = SimpleNamespace(F=F, A=0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]))
        c = F.centroids
        field = np.exp(-((c[:, 0] / 0.3) ** 2 + ((c[:, 1] + 0.1) / 0.2) ** 2))
        return pf.sector_shares(H, field, 0.25)

    half, whole = run(x, cells), run(whole_x, whole_cells)
    print(f"half model {half}\nwhole block {whole}")
    assert pf.half_model(SimpleNamespace(x=x)) and not pf.half_model(SimpleNamespace(x=whole_x))
    for k in ("surface", "middle", "beneath", "fill", "radius"):
        assert half[k] == pytest.approx(whole[k], rel=1e-9), k


def test_fig15_flow_of_a_half_model_is_the_whole_blocks():
    """Fig. 15's flow axis (camclay9.paper_fields.flow_axis) of a half model (bedding at theta = 0 and 90) is that of
    its field with the mirror image (paper_fields.mirrored): on nodes symmetric about x = 0 with a symmetric field (u_x
    odd, u_y even) the same as the whole block's, axis on the axis of the load; the half's own would tilt (+x)."""
    from camclay9 import paper_fields as pf

    g = np.linspace(-1, 1, 41)
    X, Y = np.meshgrid(g, -np.linspace(0.01, 1, 30), indexing="ij")
    whole = np.c_[X.ravel(), Y.ravel()]
    field = lambda x: np.c_[x[:, 0] * np.exp(-4 * (x ** 2).sum(1)), -(1 + x[:, 0] ** 2) * np.exp(-3 * (x ** 2).sum(1))]
    half = whole[whole[:, 0] >= -1e-12]
    xm, um = pf.mirrored(half, field(half))
    a, b, c = pf.flow_axis(whole, field(whole), 0.4, 0), pf.flow_axis(xm, um, 0.4, 0), pf.flow_axis(half, field(half), 0.4, 0)
    print(f"whole block beta {a['beta']:.3g}, anisotropy {a['anisotropy']:.6g}; half mirrored {b['beta']:.3g}, "
          f"{b['anisotropy']:.6g}; the half alone {c['beta']:.3g}")
    assert len(xm) == len(whole) and abs(a["beta"]) < 1e-9 and abs(b["beta"]) < 1e-9 and c["beta"] > 1
    assert b["anisotropy"] == pytest.approx(a["anisotropy"], rel=1e-9)
    assert b["mean_angle"] == pytest.approx(a["mean_angle"], abs=1e-9)


@pytest.mark.parametrize("alpha", ["0.1", "1", "10"])
def test_whole_block_of_a_shipped_half_model(alpha):
    """camclay9.indent2d_study.whole_block turns each shipped loading-rate half model back into the whole block the 2D
    study's ladders ran on: x from -W/2, both sides fixed in x, no mirror plane, no copies; the rest unchanged."""
    from camclay9.indent2d_study import whole_block

    half = (ROOT / "input" / f"loading_rate_a{alpha}.yaml").read_text()
    whole = whole_block(half)
    assert "half: 1," in half and "copies: 2" in half and "mirror:" in half
    assert "half: 0," in whole and "copies" not in whole.split("indenter:")[-1].split("\n")[0] and "\n  mirror:" not in whole
    assert "    - {group: left, components: [x]}\n    - {group: right, components: [x]}\n" in whole
    assert whole_block(whole) == whole
    strip = lambda t: [l for l in t.splitlines() if not l.startswith("#")]
    assert len(strip(half)) - len(strip(whole)) == 1          # the mirror key and its entry against the left side's entry


def test_run_times_say_which_adapted_levels_were_reused(tmp_path):
    """tools/reproduce.py reads the levels a run reused from its summary.json (levels[].kept), and the run-time sentence
    of docs/paper.md and docs/performance.md says so: those times are not from scratch."""
    import importlib.util
    from camclay9 import paper_doc
    spec = importlib.util.spec_from_file_location("reproduce", ROOT / "tools" / "reproduce.py")
    rp = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(rp)
    run = tmp_path / "bp"   # a run's summary.json as the driver writes it (its levels' other keys left out)
    run.mkdir()
    (run / "summary.json").write_text(json.dumps({"levels": [{"cells": 923, "kept": True}, {"cells": 3264, "kept": True},
                                                             {"cells": 6201, "kept": False}]}))
    assert rp.kept_levels(run) == [0, 1]
    assert rp.kept_levels(tmp_path / "none") == []
    meta = {"walls": {"bp": 240.0, "bn": 120.0}, "cpus": {"bp": 239.0, "bn": 119.0}, "wall_runs": 250.0, "wall_total": 255.0,
            "date": "2026-12-01"}
    assert "Not from scratch" not in paper_doc.performance_section(meta)
    text = paper_doc.performance_section({**meta, "kept": {"bp": rp.kept_levels(run)}})
    assert "bp reused its adapted levels 0, 1 from an earlier run" in text and "bn reused" not in text
    # a rerun of one scene (--only) keeps the other scenes' kept levels, and its own from this run
    prev = {"walls": {"bp": 240.0, "bn": 120.0}, "cpus": {"bp": 239.0, "bn": 119.0}, "wall_runs": 250.0,
            "kept": {"bp": [0, 1], "bn": [0]}}
    runs = rp.record_runs(prev, {"bn": 180.0}, {"bn": 179.0}, {}, 181.0, ["bn"], "2026-12-01", only=True)
    assert runs["kept"] == {"bp": [0, 1]} and runs["walls"] == {"bp": 240.0, "bn": 180.0} and runs["wall_runs"] == 250.0
    assert rp.record_runs(prev, {"bn": 180.0}, {"bn": 179.0}, {}, 181.0, [], "2026-12-01", only=False)["kept"] == {}


def test_bedding_variants_adapt_at_1um_and_keep_one_mesh_at_3um(tmp_path):
    """tools/reproduce.py's bedding scenes: at 1 µm the shipped scene as it is (a first mesh and one rerun on an adapted
    mesh), at 3 µm one mesh of the sizes measured for it (h_tip 0.125 µm, h_far 3.75 µm, the fine zone's reach scaled by
    1/3), no rerun; the quick run's coarse variant never adapts."""
    import importlib.util
    import yaml
    spec = importlib.util.spec_from_file_location("reproduce", ROOT / "tools" / "reproduce.py")
    rp = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(rp)
    one = yaml.safe_load(rp.variant_scene("bedding_theta45", tmp_path / "a.yaml", quick=False).read_text())
    shipped = yaml.safe_load((ROOT / "input" / "bedding_theta45.yaml").read_text())
    assert one["mesh"]["adapt"] == shipped["mesh"]["adapt"] and one["mesh"]["adapt"]["levels"] >= 1
    three = yaml.safe_load(rp.variant_scene("bedding_theta45_t3", tmp_path / "b.yaml", quick=False).read_text())
    p = three["mesh"]["parameters"]
    assert "adapt" not in three["mesh"] and (p["h_tip"], p["h_far"]) == (0.125, 3.75)
    assert abs(p["r_fine"] - shipped["mesh"]["parameters"]["r_fine"] / 3) < 1e-12 and three["mesh"]["thickness"] == 3
    assert "adapt" not in yaml.safe_load(rp.variant_scene("bedding_theta45", tmp_path / "c.yaml", quick=True).read_text())["mesh"]


def test_area_percentile():
    """camclay9.paper_fields.area_percentile: the value below which q % of the area lies; two cells of values 1 and 2
    and areas 3 and 1 put 75 % of the area at 1, so the 50th and 75th percentiles are 1 and the 80th is 2 (by count,
    numpy's median would be 1.5)."""
    from camclay9 import paper_fields as pf
    v, a = np.array([2.0, 1.0]), np.array([1.0, 3.0])
    assert (pf.area_percentile(v, a, 50), pf.area_percentile(v, a, 75), pf.area_percentile(v, a, 80)) == (1.0, 1.0, 2.0)


def test_fig11_zone_does_not_follow_the_mesh():
    """Fig. 11's zone numbers (paper_fields.sector_shares) of one smooth field on a uniform mesh and on a mesh whose
    cells crowd near the tip (as an adapted one's do): by area (the percentiles since 2026-12-02) within 0.01 of each
    other; by cell count, as before, the crowded cells raise the zone's threshold and the numbers move by more than 0.04."""
    from types import SimpleNamespace
    from camclay9 import paper_fields as pf

    def mesh(n, grade):
        s = np.linspace(0, 1, n + 1) ** grade              # grade > 1: the cells crowd near x = 0 and y = 0
        X, Y = np.meshgrid(s, -s, indexing="ij")
        x = np.c_[X.ravel(), Y.ravel()]
        v = lambda i, j: i * (n + 1) + j
        cells = np.array([c for i in range(n) for j in range(n)
                          for c in ((v(i, j), v(i + 1, j), v(i + 1, j + 1)), (v(i, j), v(i + 1, j + 1), v(i, j + 1)))])
        F = SimpleNamespace(x=x, cells=cells, centroids=x[cells].mean(axis=1))
        e1, e2 = (x[cells[:, 1]] - x[cells[:, 0]]), (x[cells[:, 2]] - x[cells[:, 0]])
        return SimpleNamespace(F=F, A=0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]))

    def zone(H, percentile):
        c = H.F.centroids
        r = np.hypot(c[:, 0], c[:, 1])
        field = np.exp(-((c[:, 0] / 0.3) ** 2 + ((c[:, 1] + 0.1) / 0.2) ** 2)) + 0.5 * np.exp(-(r / 0.02) ** 2)
        return pf.sector_shares(H, field, 0.25, percentile=percentile)

    uniform, graded = mesh(120, 1.0), mesh(120, 2.5)
    by_area = [zone(uniform, pf.area_percentile), zone(graded, pf.area_percentile)]
    by_count = [zone(uniform, pf.count_percentile), zone(graded, pf.count_percentile)]
    keys = ("surface", "middle", "beneath", "fill")
    d_area = max(abs(by_area[0][k] - by_area[1][k]) for k in keys)
    d_count = max(abs(by_count[0][k] - by_count[1][k]) for k in keys)
    print(f"by area {by_area}\nby count {by_count}\nlargest difference: by area {d_area:.3f}, by count {d_count:.3f}")
    assert d_area < 0.01 and d_count > 0.04


def test_fig15_flow_axis_does_not_follow_the_mesh():
    """Fig. 15's flow axis (paper_fields.flow_axis) of one displacement field on a uniform mesh and on one whose vertices
    crowd near the tip: with the vertices weighed by their areas (paper_fields.nodal_areas, since 2026-12-02) within
    0.2 deg of each other; weighed by their count, as before, more than 1 deg apart."""
    from types import SimpleNamespace
    from camclay9 import paper_fields as pf

    def mesh(n, grade):
        s = np.linspace(0, 1, n + 1) ** grade
        X, Y = np.meshgrid(np.r_[-s[:0:-1], s], -s, indexing="ij")
        x = np.c_[X.ravel(), Y.ravel()]
        m = 2 * n + 1
        v = lambda i, j: i * (n + 1) + j
        cells = np.array([c for i in range(m - 1) for j in range(n)
                          for c in ((v(i, j), v(i + 1, j), v(i + 1, j + 1)), (v(i, j), v(i + 1, j + 1), v(i, j + 1)))])
        F = SimpleNamespace(x=x, cells=cells)
        e1, e2 = (x[cells[:, 1]] - x[cells[:, 0]]), (x[cells[:, 2]] - x[cells[:, 0]])
        return x, pf.nodal_areas(F, 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]))

    # a flow tilted near the tip and straight down away from it: the vertices' density decides the axis by count
    du = lambda x: np.c_[0.6 * np.exp(-(np.hypot(*x.T) / 0.05) ** 2), -np.ones(len(x))]
    (xu, wu), (xg, wg) = mesh(60, 1.0), mesh(60, 2.5)
    by_area = [pf.flow_axis(xu, du(xu), 0.5, 0, wu)["beta"], pf.flow_axis(xg, du(xg), 0.5, 0, wg)["beta"]]
    by_count = [pf.flow_axis(xu, du(xu), 0.5, 0)["beta"], pf.flow_axis(xg, du(xg), 0.5, 0)["beta"]]
    print(f"beta by area {by_area}, by count {by_count}")
    assert abs(by_area[0] - by_area[1]) < 0.2 and abs(by_count[0] - by_count[1]) > 1
