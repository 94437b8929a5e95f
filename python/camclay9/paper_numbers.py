"""The numbers of docs/paper.md, read from the runs of tools/reproduce.py, and the paper's stated trends.

collect(DIR) reads DIR/<scene>/history.csv (and fields.h5 of the loading-rate runs) and returns a dict
(also written to DIR/numbers.json); check_trends(numbers) checks the four trends the paper states and
that the quick mode asserts. Conventions: creep strain = axial strain since the deviator was applied,
compression positive; indentation creep depth = h - h(start of hold); Lomnitz law B log(1 + t/tau) (eq. 28)
read with the natural logarithm (camclay9.lomnitz; "paper_creep") and with log10 ("paper_creep_log10": the
same curve / ln 10): the paper does not say which.
"""
import json
from pathlib import Path

import numpy as np
from camclay9 import read_history
from camclay9.lomnitz import lomnitz, lomnitz_fit
from camclay9.paper_fields import A_BED, BENEATH, REGION_KEYS, flow_direction, loading_rate_numbers

ALPHAS = ("0.1", "1", "10")
THETAS_BEDDING = (0, 30, 45, 60, 90)
THETAS_TRIAXIAL = (0, 90)
PAPER_LOMNITZ = {0: (9.97e-5, 385.0), 90: (6.74e-5, 364.0)}   # Yin et al. 2021 §5, eq. 28 and Fig. 17
CREEP_TIMES = (385.0, 3600.0, 36000.0)                          # s after the deviator
RATIO_TIMES = (100.0, 385.0, 1000.0, 3600.0, 36000.0)
SOFT_OVER_HARD = 10.0                                           # §5, Fig. 18: "more than 10 times larger"
EARLY = 385.0          # "early creep" in the checks: the paper's tau (385 s, 364 s), Fig. 17
N_FIT = 400            # samples of the resampled Lomnitz fits


# ------------------------------------------------------------------ triaxial
def triaxial_series(run):
    """(t, eps, soft, hard) of the creep stage: time since the deviator, axial creep strain and the mean
    axial viscoplastic strain of each frame since the deviator (compression positive)."""
    h = read_history(run, need=("time", "stage", "eps_33", "evp33_soft_mean", "evp33_hard_mean"))
    rows = np.flatnonzero(h["stage"] == h["stage"].max())
    t = h["time"][rows] - h["time"][rows[0]]

    def since(col):
        return -(h[col][rows] - h[col][rows[0]])
    return t, since("eps_33"), since("evp33_soft_mean"), since("evp33_hard_mean")


def resampled_fits(t, eps):
    """Lomnitz fits of one curve sampled three ways: evenly in t, evenly in log t (from 1 s), and at the
    driver's steps (adaptive, close to even in log t)."""
    tl = np.linspace(0.0, t[-1], N_FIT)
    tg = np.geomspace(1.0, t[-1], N_FIT)
    return {"even_t": lomnitz_fit(tl, np.interp(tl, t, eps)),
            "even_log_t": lomnitz_fit(tg, np.interp(tg, t, eps)),
            "steps": lomnitz_fit(t, eps)}


def last_time_above(t, ratio, level):
    """The last time at which ratio >= level, interpolated linearly between samples; None if never."""
    above = np.flatnonzero(ratio >= level)
    if above.size == 0:
        return None
    k = above[-1]
    if k == ratio.size - 1:
        return float(t[-1])
    r0, r1 = ratio[k], ratio[k + 1]
    return float(t[k] + (t[k + 1] - t[k]) * (r0 - level) / (r0 - r1))


def triaxial_numbers(run, theta):
    t, eps, soft, hard = triaxial_series(run)
    B, tau = PAPER_LOMNITZ[theta]
    pos = t > 0
    ratio = soft[pos] / np.maximum(hard[pos], 1e-300)
    return {
        "duration": float(t[-1]),
        "creep": {f"{x:g}": float(np.interp(x, t, eps)) for x in CREEP_TIMES},
        "paper_creep": {f"{x:g}": float(lomnitz(x, B, tau)) for x in CREEP_TIMES},
        "paper_creep_log10": {f"{x:g}": float(lomnitz(x, B, tau) / np.log(10.0)) for x in CREEP_TIMES},
        "fits": {k: {"B": v[0], "tau": v[1]} for k, v in resampled_fits(t, eps).items()},
        "soft_over_hard": {f"{x:g}": float(np.interp(x, t[pos], ratio)) for x in RATIO_TIMES if x <= t[-1] * (1 + 1e-6)},
        "soft_over_hard_10x_until": last_time_above(t[pos], ratio, SOFT_OVER_HARD),
        # the smallest ratio over the hold's first EARLY s and over the whole hold (Fig. 18's claim covers all of it)
        "soft_over_hard_min_early": float(min(np.min(ratio[t[pos] <= EARLY]), np.interp(EARLY, t[pos], ratio))),
        "soft_over_hard_min": float(np.min(ratio)),
    }


# ------------------------------------------------------------------ indentation
def indent_numbers(run):
    from camclay9.indent_plots import History, creep_summary
    h = History(run)
    s = creep_summary(h)
    s["max_depth"] = float(np.max(h["depth"]))
    s.update(stated_errors(Path(run)))
    return s


def stated_errors(run):
    """The mesh and time-step errors the run states (its summary.json, docs/adapt.md) for the creep depth (the hold's
    depth change) and the residual depth (the unload's end depth), with the number of meshes: {} without them."""
    path = run / "summary.json"
    if not path.is_file():
        return {}
    js = json.loads(path.read_text(encoding="utf-8"))
    st = {x["name"]: x for x in js.get("stages", [])}
    out = {"meshes": len(js.get("levels", [])) or 1}
    hold, unload = st.get("hold", {}), st.get("unload", {})
    if hold.get("mesh_error"):
        out["creep_mesh_error"] = hold["mesh_error"]["change"]["depth"]
    if hold.get("time_error"):
        out["creep_time_error"] = hold["time_error"]["change"]["depth"]
    if unload.get("mesh_error"):
        out["residual_mesh_error"] = unload["mesh_error"]["end"]["depth"]
    return out


def stated_text(s, mesh_key, time_key=None):
    """' (± e mesh, n meshes; ± t time steps)' of the errors a run stated (stated_errors), or ''."""
    parts = [f"± {s[mesh_key]:.2g} mesh, {s['meshes']} meshes" if mesh_key in s else "",
             f"± {s[time_key]:.2g} time steps" if time_key and time_key in s else ""]
    parts = [p for p in parts if p]
    return f" ({'; '.join(parts)})" if parts else ""


# ------------------------------------------------------------------ all
def collect(out):
    """All numbers of the runs in `out` (missing runs are left out); writes out/numbers.json."""
    out = Path(out)
    n = {"indent": {}, "fig13": {}, "triaxial": {}}
    for d in sorted(p for p in out.iterdir() if (p / "history.csv").is_file()):
        if d.name.startswith("triaxial_theta"):
            theta = int(d.name.removeprefix("triaxial_theta"))
            n["triaxial"][theta] = triaxial_numbers(d, theta)
            continue
        n["indent"][d.name] = indent_numbers(d)
        if d.name.startswith("loading_rate_a"):
            f = loading_rate_numbers(d)
            if f is not None:
                s = f["fig13"]["dsig"]
                n["fig13"][d.name.removeprefix("loading_rate_a")] = {
                    "region": list(BENEATH), "change_end": float(s[-1]), "change_min": float(min(s)),
                    "change_max": float(max(s[1:] if len(s) > 1 else s)), "hold": float(f["fig13"]["t"][-1]), "outputs": len(s)}
                n["fig13"][d.name.removeprefix("loading_rate_a")].update(
                    t=f["fig13"]["t"], dsig=[float(x) for x in s])
                n["indent"][d.name].update(evp_start=f["evp_start"], fig10b=f["fig10b"], fig10b_total=f["fig10b_total"],
                                           fig11=f["fig11"], fig11_sens=f["fig11_sens"], checker=f["checker"],
                                           regions={k: f[k] for k in REGION_KEYS})
        if d.name.startswith("bedding_theta") and d.name.removeprefix("bedding_theta").isdigit():
            n["indent"][d.name]["flow"] = flow_direction(d, A_BED, int(d.name.removeprefix("bedding_theta")))
    (out / "numbers.json").write_text(json.dumps(n, indent=1, default=float) + "\n", encoding="utf-8")
    return n


def _trend(name, ok, detail):
    return {"name": name, "ok": bool(ok), "detail": detail}


def check_trends(n):
    """The four trends of the paper the model reproduces (issue 14), each with its measured margin. A
    missing run fails its trend."""
    out = []
    ind, tri = n["indent"], n["triaxial"]
    lr = [ind.get(f"loading_rate_a{a}") for a in ALPHAS]
    if all(lr):
        d = [r["depth_end_of_load"] for r in lr]
        c = [r["creep_depth"] for r in lr]
        ok = d[0] > d[1] > d[2] and c[0] < c[1] < c[2]
        out.append(_trend("faster loading: shallower at the end of loading, more creep in the hold (§4.1, Figs. 7, 8)", ok,
                          "alpha 0.1/1/10: depth at end of load " + " > ".join(f"{x:.4g}" for x in d) + " um, creep "
                          + " < ".join(f"{x:.4g}" for x in c) + f" um; margins: depth ratios {d[0] / d[1]:.3f}, "
                          f"{d[1] / d[2]:.3f}, creep ratios {c[1] / c[0]:.3f}, {c[2] / c[1]:.3f} (must be > 1)"))
    else:
        out.append(_trend("faster loading (§4.1)", False, "loading-rate runs missing"))
    bed = [ind.get(f"bedding_theta{t}") for t in THETAS_BEDDING]
    if all(bed) and 0 in tri and 90 in tri:
        c = np.array([r["creep_depth"] for r in bed])
        spread = c.max() / c.min()
        tx = tri[0]["creep"]["36000"] / tri[90]["creep"]["36000"]
        out.append(_trend("anisotropy weak in indentation creep, strong in triaxial creep (§4.2, Fig. 14; §5)",
                          spread < tx, f"indentation creep depth max/min over theta 0-90 = {spread:.3f} "
                          f"({', '.join(f'{x:.4g}' for x in c)} um) < triaxial theta0/theta90 creep at 10 h = {tx:.3f}"))
    else:
        out.append(_trend("anisotropy weak in indentation (§4.2)", False, "bedding or triaxial runs missing"))
    if 0 in tri and 90 in tri:
        r = {k: tri[0]["creep"][k] / tri[90]["creep"][k] for k in tri[0]["creep"]}
        out.append(_trend("theta = 0 creeps more than theta = 90 (§5, Fig. 17)", all(v > 1 for v in r.values()),
                          "theta0/theta90 creep ratio " + ", ".join(f"{v:.3f} at {k} s" for k, v in r.items())
                          + f" (paper's fits: {lomnitz(385, *PAPER_LOMNITZ[0]) / lomnitz(385, *PAPER_LOMNITZ[90]):.3f} "
                          "at 385 s; must be > 1)"))
        e = {th: tri[th]["soft_over_hard_min_early"] for th in THETAS_TRIAXIAL}
        until = {th: tri[th].get("soft_over_hard_10x_until") for th in THETAS_TRIAXIAL}
        out.append(_trend("the soft frame dominates the first 385 s of creep (§5, Fig. 18, which claims it for the whole "
                          "10 h: docs/paper.md gives that verdict)", all(v > SOFT_OVER_HARD for v in e.values()),
                          "soft/hard mean axial creep, smallest over the hold's first 385 s: "
                          + ", ".join(f"theta {th}: {v:.1f}" for th, v in e.items()) + f" (must be > {SOFT_OVER_HARD:g}); "
                          "above 10 until " + ", ".join(f"{u:.0f} s" if u else "never" for u in until.values())
                          + f" of the {tri[0]['duration']:.0f} s hold"))
    else:
        out.append(_trend("triaxial trends (§5)", False, "triaxial runs missing"))
    return out
