"""The section "3D indentation: mesh convergence and the cheapest model" of docs/performance.md, from the results of
bench/indent_convergence_bench.py: per scene (kerogen, BN, BP) a table per ladder, the converged 3D answer with
its uncertainty, and every rung against it, the shipped mesh marked; then the reading written by hand in
bench/indent_convergence_conclusions.md."""
import time
from pathlib import Path

from camclay9.convergence import richardson
from indent_ladders import MODELS, OUT3, ladder, ladders

ROOT = Path(__file__).resolve().parents[1]
CONCLUSIONS = ROOT / "bench" / "indent_convergence_conclusions.md"  # the section's reading, written by hand
TITLE = "## 3D indentation: mesh convergence and the cheapest model"
NOISY = {"sector2"}  # ladders whose finest rungs scatter without a trend (the reading says why)
# Per scene: its units (P, creep, h_res: name and factor from µN, µm), the mesh it ships (model, h_tip) and the
# one it shipped before (kerogen: the sector re-picked in issue 25, item 5, from h_tip 0.1 with h_far 8 h_tip to 0.12
# with h_far 4 h_tip), and how its converged answer is made (reference() below).
GROUPS = {
    "kerogen": dict(title="Kerogen, nanoindentation to 200 nm (nanoindent_kerogen*.yaml; φ = 0)",
                    units=(("µN", 1), ("nm", 1e3), ("nm", 1e3)), shipped=("sector2", 0.12), before=("sector2f8", 0.1),
                    ref=("two", "sector2", "sector1")),
    "BN": dict(title="BN, microindentation to 5 µm (microindent_BN*.yaml; φ = 0.5, bedding normal e_z)",
               units=(("mN", 1e-3), ("nm", 1e3), ("µm", 1)), shipped=("bn2", 2.5), before=("bn2", 2.5),
               ref=("limit", "bn2")),
    "BP": dict(title="BP, microindentation to 5 µm (microindent_BP.yaml; φ = 0.5, bedding normal e_x)",
               units=(("mN", 1e-3), ("nm", 1e3), ("µm", 1)), shipped=("bp2", 2.5), before=("bp2", 2.5),
               ref=("limit", "bp2")),
}




def bracket(hs, xs):
    """The limits that the last two rungs give if the order is 1 and if it is 2 (a band for erratic ladders)."""
    if len(xs) < 2:
        return None
    r = hs[-2] / hs[-1]
    lims = [xs[-1] + (xs[-1] - xs[-2]) / (r ** p - 1) for p in (1, 2)]
    return min(lims), max(lims)


def limits(res, model, tol=None):
    rows = ladder(res, model, tol)
    hs = [r["h_tip"] for r in rows]
    return {k: richardson(hs, [r["o"][k] for r in rows]) for k in OUT3}


def fmt(group, k, v):
    name, f = GROUPS[group]["units"][OUT3.index(k)]
    return f"{v * f:.2f}" if v * f < 1000 else f"{v * f:.1f}"


def estimate_mean(res, model, n=3):
    """A ladder without a trend left: its finest n rungs' mean, ± half their range (relative)."""
    rows = ladder(res, model)[-n:]
    if len(rows) < n:
        return None
    xs = {k: [r["o"][k] for r in rows] for k in OUT3}
    return {k: (sum(v) / n, (max(v) - min(v)) / 2 / abs(sum(v) / n)) for k, v in xs.items()}


def estimate_limit(res, model):
    """A converging ladder: its Richardson limit (last three rungs, order 0.5-4), ± its distance to the finest rung;
    else the middle of the band the last two rungs give for orders 1 to 2, ± the band's half-width or the middle's
    distance to the finest rung, whichever is larger (relative)."""
    rows = ladder(res, model)
    if len(rows) < 2:
        return None
    lim, out = limits(res, model), {}
    for k in OUT3:
        hs, xs = [r["h_tip"] for r in rows], [r["o"][k] for r in rows]
        b = bracket(hs, xs)
        x = lim[k][1] if lim[k][1] is not None else (b[0] + b[1]) / 2
        w = abs(x - xs[-1]) if lim[k][1] is not None else max((b[1] - b[0]) / 2, abs(x - xs[-1]))
        out[k] = (x, w / abs(x))
    return out


def reference(res, group):
    """The converged answer of a scene and its relative uncertainty per output, and a sentence saying how: 'limit'
    (one ladder's limit), or 'two': the middle of a P2 ladder's finest rungs (mean) and a P1 ladder's limit, ± the
    larger of half their distance and either's own uncertainty."""
    kind, *models = GROUPS[group]["ref"]
    if kind == "limit":
        e = estimate_limit(res, models[0])
        how = f"the {MODELS[models[0]]['label']} ladder's limit (Richardson where its order is 0.5–4, else the p = 1 … 2 band)"
        return ({k: v[0] for k, v in e.items()}, {k: v[1] for k, v in e.items()}, how) if e else (None, None, None)
    a, b = estimate_mean(res, models[0]), estimate_limit(res, models[1])
    if not a or not b:
        return None, None, None
    ref = {k: (a[k][0] + b[k][0]) / 2 for k in OUT3}
    hw = {k: max(abs(a[k][0] - b[k][0]) / 2 / abs(ref[k]), a[k][1], b[k][1]) for k in OUT3}
    how = (f"the middle of the {MODELS[models[0]]['label']} ladder's finest three rungs (their mean) and the "
           f"{MODELS[models[1]]['label']} ladder's limit")
    return ref, hw, how


def ladder_table(res, group, model, tol):
    """One ladder: a row per rung (in brackets the error against its own limit), then its limits."""
    (pu, _), (cu, _), (hu, _) = GROUPS[group]["units"]
    rows, lim = ladder(res, model, tol), limits(res, model, tol)
    label = MODELS[model]["label"] + (f", time steps at tol {tol:g}" if tol else "")
    lines = [f"**{label}**", "", f"| h_tip [µm] | unknowns | P [{pu}] | creep [{cu}] | h_res [{hu}] | steps | UMAT calls "
             "| CPU [s] | memory [MB] |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [fmt(group, k, r["o"][k]) + (f" ({r['o'][k] / lim[k][1] - 1:+.1%})" if lim[k][1] and model not in NOISY
                                             else "") for k in OUT3]
        lines.append(f"| {r['h_tip']:.4g} | {r['unknowns']} | {' | '.join(cells)} | {r['steps']} | "
                     f"{r.get('umat_calls', 0) / 1e6:.1f} M | {r['cpu']:.0f} | {r.get('rss_mb', 0):.0f} |")
    if len(rows) >= 3 and model in NOISY:  # no trend left: the scatter of the finest rungs, not an extrapolation
        e = estimate_mean(res, model)
        cells = [f"{fmt(group, k, e[k][0])} ± {e[k][1]:.1%}" for k in OUT3]
        lines.append(f"| finest three: mean ± half-range | | {' | '.join(cells)} | | | | |")
    elif len(rows) >= 3:
        lim_cells = [f"{fmt(group, k, lim[k][1])} (p = {lim[k][0]:.2f})" if lim[k][1] else
                     f"erratic (p = {lim[k][0]:.2f})" if lim[k][0] else "not monotone" for k in OUT3]
        band = [bracket([r["h_tip"] for r in rows], [r["o"][k] for r in rows]) for k in OUT3]
        lines += [f"| Richardson limit | | {' | '.join(lim_cells)} | | | | |",
                  f"| limit if p = 1 … 2 (last two rungs) | | "
                  + " | ".join(f"{fmt(group, k, b[0])} – {fmt(group, k, b[1])}" for k, b in zip(OUT3, band)) + " | | | | |"]
    return lines + [""]


def against_table(res, group, ref, hw, how):
    """Every rung of the scene against its converged answer, sorted by CPU time; the shipped mesh marked."""
    g = GROUPS[group]
    lines = [f"**Every rung against the converged answer** ({how}: P = {fmt(group, OUT3[0], ref[OUT3[0]])} "
             f"{g['units'][0][0]} ± {hw[OUT3[0]]:.1%}, creep = {fmt(group, OUT3[1], ref[OUT3[1]])} {g['units'][1][0]} ± "
             f"{hw[OUT3[1]]:.1%}, h_res = {fmt(group, OUT3[2], ref[OUT3[2]])} {g['units'][2][0]} ± {hw[OUT3[2]]:.1%}), "
             "sorted by CPU time; ✓: all three within 2 %", "",
             "| model | h_tip | unknowns | CPU [s] | P | creep | h_res | ≤ 2 % |", "|---|---|---|---|---|---|---|---|"]
    rows = [r for r in res.values() if "failed" not in r and MODELS.get(r["model"], {}).get("group") == group]
    for r in sorted(rows, key=lambda r: r["cpu"]):
        e = [r["o"][k] / ref[k] - 1 for k in OUT3]
        label = MODELS[r["model"]]["label"] + (f", tol {r['tol']:g}" if r.get("tol") else "")
        at = (r["model"], round(r["h_tip"], 6))
        if r.get("tol") is None and at == g["shipped"]:
            label = f"**{label}: the shipped scene**"
        elif r.get("tol") is None and at == g["before"]:
            label = f"{label}: shipped before"
        lines.append(f"| {label} | {r['h_tip']:.4g} | {r['unknowns']} | {r['cpu']:.0f} | "
                     + " | ".join(f"{x:+.1%}" for x in e) + f" | {'✓' if max(map(abs, e)) <= 0.02 else ''} |")
    return lines + [""]


def intro(command, note):
    return [TITLE, "",
            f"Command: `{command}` ({time.strftime('%Y-%m-%d', time.gmtime())}; {note}).",
            "`bench/indent_convergence_bench.py` (issue 12, items 3-4; issue 25, item 5): the 3D indentation scenes as shipped",
            "(Cam-Clay IX; exponential load to the target depth, hold 60 s, unload in 20 s; the shipped time-step settings,",
            "output measure tol 1.5e-2) on ladders of h_tip at ratio about √2. 3D: h_tip within r_fine of the tip (0.9 µm,",
            "the whole contact at 200 nm: the Berkovich's corners reach 0.87 µm; × 25 for BN and BP), h_far = 4 or 8 h_tip",
            "as the ladder says (P1: 8 h_tip); 'r_fine 0.4' is the family of the scenes before (the contact's rim in the",
            "graded zone). Axisymmetric: r_fine 0.4, h_far 7.5 h_tip. Fields off, one rank, one run per rung, under",
            "nice -n 10. P: the indenter's whole load at the end of loading; creep: depth gained over the hold; h_res:",
            "residual depth. In brackets: the error against the Richardson limit of the ladder's own last three rungs.",
            "CPU: user + system of the driver (gmsh's meshing included) [s]; memory: its peak resident set [MB]; a shared,",
            "loaded machine (2 cores, other users' jobs running): the wall time is not comparable, the CPU time roughly.",
            "The results are kept in `docs/results/indent_convergence.json` (the bench's --results).", ""]


def section(res, command, note):
    lines = intro(command, note)
    for group, g in GROUPS.items():
        if not ladders(res, group):
            continue
        lines += [f"### {g['title']}", ""]
        for model, tol in ladders(res, group):
            lines += ladder_table(res, group, model, tol)
        ref, hw, how = reference(res, group)
        if ref:
            lines += against_table(res, group, ref, hw, how)
    failed = sorted((r for r in res.values() if "failed" in r), key=lambda r: (r["model"], -r["h_tip"]))
    if failed:
        lines += ["Rungs that did not run: " + "; ".join(f"{MODELS[r['model']]['label']} at h_tip {r['h_tip']:.4g} "
                                                        f"({r['failed']})" for r in failed) + ".", ""]
    if CONCLUSIONS.exists():
        lines += [CONCLUSIONS.read_text()]
    return "\n".join(lines) + "\n"
