"""The 3D indentation mesh study (bench/indent_convergence_bench.py runs it): each ladder is a scene of input/ on a
family of meshes indexed by h_tip; its store holds one result per rung. From the store this module writes the section
"3D indentation: mesh convergence and the cheapest model" of docs/performance.md (per scene a table per ladder, the
converged answer with its uncertainty, every rung against it, the shipped mesh marked, then the reading written by
hand in bench/indent_convergence_conclusions.md), and gives the numbers that README.md, docs/paper.md and that reading
quote (numbers(): camclay9.doc_quotes, camclay9.paper_doc).

The store, docs/results/indent_convergence.json: {"provenance": {"command", "date", "note"}, "rungs": {key: rung}},
the key "model[@tol]:h_tip" (key()), a rung {"model", "h_tip", "tol", "o": {output: value in µN and µm}, "unknowns",
"cpu", "rss_mb", "steps", "newton", "umat_calls", "factorisations", "solver", "date", "rev"} or {"failed": why, ...}.
docs/results/indent3d.json keeps the few figures no run of this study makes (its provenance says where they come
from); BN's and BP's adapted levels come from docs/results/adapt_bench.json (bench/adapt_bench.py)."""
import math
import re

from . import repo_root, results_store
from . import convergence

STORE = "indent_convergence"
KEPT = "indent3d"    # the carried-over figures
TITLE = "## 3D indentation: mesh convergence and the cheapest model"
R2 = math.sqrt(2)
OUT3 = ("load at end of loading", "creep depth", "residual depth")  # the three outputs a mesh is judged on
SHORT = {"load at end of loading": "P", "depth at end of loading": "h_max", "creep depth": "creep",
         "residual depth": "h_res"}


def model(label, name, order, far, r_fine, hs, group, nested=None):
    """A ladder: its scene (input/NAME.yaml), element order, h_far / h_tip, r_fine (None: as shipped), h_tip's;
    nested: the h_tip of one mesh whose tetrahedra are split into eight once per halving of h_tip (so every rung's
    mesh holds the one before it), instead of a new mesh per rung."""
    return dict(label=label, scene=name, order=order, far=far, r_fine=r_fine, hs=hs, group=group, nested=nested)


K, B = "nanoindent_kerogen_sector", "microindent_BN_sector"
MODELS = {
    "sector2": model("60° sector, P2", K, 2, 4, 0.9, [0.2, 0.1414, 0.12, 0.1, 0.07071, 0.05, 0.03536], "kerogen"),
    "sector1": model("60° sector, P1", K, 1, 8, 0.9, [0.1, 0.07071, 0.05, 0.03536, 0.025, 0.01768], "kerogen"),
    "sector2f8": model("60° sector, P2, h_far 8 h_tip", K, 2, 8, 0.9, [0.1414, 0.12, 0.1, 0.07071], "kerogen"),
    "sector2n": model("60° sector, P2, nested (the h_tip 0.2 mesh split)", K, 2, 4, 0.9, [0.2, 0.1, 0.05], "kerogen", 0.2),
    "sector1n": model("60° sector, P1, nested (the h_tip 0.2 mesh split)", K, 1, 4, 0.9, [0.1, 0.05, 0.025], "kerogen",
                      0.2),
    "half2": model("half model (cube), P2", "nanoindent_kerogen", 2, 4, 0.9, [0.12], "kerogen"),
    "old1": model("60° sector, P1, r_fine 0.4 (the scenes before)", K, 1, 8, 0.4, [0.1, 0.07071, 0.05], "kerogen"),
    "axi1": model("axisymmetric cone, P1", "nanoindent_kerogen_axi", 1, 7.5, None,
                  [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01, 0.01 / R2, 0.005], "kerogen"),
    "axi2": model("axisymmetric cone, P2", "nanoindent_kerogen_axi", 2, 7.5, None,
                  [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01], "kerogen"),
    "bn2": model("BN, 60° sector, P2", B, 2, 8, None, [5, 3.536, 2.5, 1.768, 1.25, 0.8839], "BN"),
    "bn1": model("BN, 60° sector, P1", B, 1, 8, None, [2.5, 1.768, 1.25, 0.8839, 0.625], "BN"),
    "bnaxi2": model("BN, axisymmetric cone, P2", "microindent_BN_axi", 2, 7.5, None,
                    [0.5, 0.5 / R2, 0.25, 0.25 / R2, 0.125], "BN"),
    "bnaxi1": model("BN, axisymmetric cone, P1", "microindent_BN_axi", 1, 7.5, None,
                    [0.5, 0.5 / R2, 0.25, 0.25 / R2, 0.125, 0.125 / R2], "BN"),
    "bp2": model("BP, half model (cube), P2", "microindent_BP", 2, 8, None, [5, 3.536, 2.5, 1.768, 1.25], "BP"),
}


def key(model, h, tol=None):
    return f"{model}{'@' + format(tol, 'g') if tol else ''}:{h:.6g}"


def ladder(res, model, tol=None):
    """The finished rungs of a ladder, coarsest first."""
    return sorted((r for r in res.values() if r["model"] == model and r.get("tol") == tol and "failed" not in r),
                  key=lambda r: -r["h_tip"])


def ladders(res, group=None):
    """(model, tol) of every ladder in res (of one group), in MODELS' order, the shipped tolerance first."""
    found = {(r["model"], r.get("tol")) for r in res.values()
             if "failed" not in r and r["model"] in MODELS and group in (None, MODELS[r["model"]]["group"])}
    return sorted(found, key=lambda mt: (list(MODELS).index(mt[0]), mt[1] is not None, mt[1] or 0))


# Per scene: its units (P, creep, h_res: name and factor from µN, µm), the mesh it ships (model, h_tip) and the
# one it shipped before (kerogen: the sector re-picked in issue 25, item 5, from h_tip 0.1 with h_far 8 h_tip to 0.12
# with h_far 4 h_tip), and how its converged answer is made (reference() below).
GROUPS = {
    "kerogen": dict(title="Kerogen, nanoindentation to 200 nm (nanoindent_kerogen*.yaml; φ = 0)",
                    units=(("µN", 1, 2), ("nm", 1e3, 2), ("nm", 1e3, 2)), shipped=("sector2", 0.12), before=("sector2f8", 0.1),
                    ref="sector2"),
    "BN": dict(title="BN, microindentation to 5 µm (microindent_BN*.yaml; φ = 0.5, bedding normal e_z)",
               units=(("mN", 1e-3, 1), ("nm", 1e3, 1), ("µm", 1, 3)), shipped=("bn2", 2.5), before=("bn2", 2.5),
               ref="bn2"),
    "BP": dict(title="BP, microindentation to 5 µm (microindent_BP.yaml; φ = 0.5, bedding normal e_x)",
               units=(("mN", 1e-3, 1), ("nm", 1e3, 1), ("µm", 1, 3)), shipped=("bp2", 2.5), before=("bp2", 2.5),
               ref="bp2"),
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
    name, f, d = GROUPS[group]["units"][OUT3.index(k)]
    return f"{v * f:.{d}f}"


LOOSE = 0.02  # an output whose finest rung moved by more than this (relative) is not converged on the ladder
TREND = 0.005  # ... nor one still rising or falling at an unresolved order by more than this
DRIVER = re.compile(r"^driver: \S+: ")  # a failed rung's message without the driver's name and the scene's path


def equal_ratios(hs):
    """Whether the last three rungs' h_tip's are in one ratio (a rung that failed leaves a ladder with unequal ones)."""
    return len(hs) < 3 or abs(hs[-3] * hs[-1] / hs[-2] ** 2 - 1) <= 0.01


def richardson(hs, xs):
    """camclay9.convergence.richardson on the last three rungs where their ratios are equal (equal_ratios), on which
    alone it applies: (order, limit) or (None, None)."""
    return convergence.richardson(hs, xs) if equal_ratios(hs) else (None, None)


def converged(res, model):
    """The converged answer of a ladder, per output: (value, relative uncertainty, rule, settled), from its last three
    rungs.
    Where they converge at an order of 0.5 to 4 (richardson): the middle of the finest rung and the Richardson limit,
    ± half their distance. Where they converge faster than that, or are not monotone (the meshes' noise is as large as
    what is left of the trend): the finest rung, ± its change from the rung before. Else (monotone, but slower than
    order 0.5, not contracting, or on unequal ratios, by more than TREND): the finest rung, ± its last change, 'not
    converged' (settled False); so too wherever that change exceeds LOOSE. None with fewer than two rungs."""
    rows = ladder(res, model)
    if len(rows) < 2:
        return None
    out = {}
    for k in OUT3:
        hs, xs = [r["h_tip"] for r in rows], [r["o"][k] for r in rows]
        p, lim = richardson(hs, xs)
        if lim is not None:
            x = (xs[-1] + lim) / 2
            out[k] = (x, abs(lim - xs[-1]) / 2 / abs(x), f"the middle of the finest rung and the Richardson limit (p = {p:.2f})",
                      True)
            continue
        w = abs(xs[-1] - xs[-2]) / abs(xs[-1])
        trend = (len(xs) >= 3 and (xs[-3] - xs[-2]) * (xs[-2] - xs[-1]) > 0 and not (p is not None and p > 4)
                 and w > TREND)
        settled = not trend and w <= LOOSE
        out[k] = (xs[-1], w, "the finest rung, ± its change from the rung before"
                  + ("" if settled else ": **not converged**" + (" (still rising or falling)" if trend else "")), settled)
    return out


def reference(res, group):
    """The converged answer of a scene (its ladder named in GROUPS, converged() above): values and relative
    uncertainties per output, a sentence saying how each was made, and the outputs not converged."""
    model = GROUPS[group]["ref"]
    e = converged(res, model)
    if not e:
        return None, None, None, None
    rows = ladder(res, model)
    how = (f"the {MODELS[model]['label']} ladder to h_tip {rows[-1]['h_tip']:.4g} µm; "
           + "; ".join(f"{SHORT[k]}: {e[k][2]}" for k in OUT3))
    return {k: v[0] for k, v in e.items()}, {k: v[1] for k, v in e.items()}, how, [k for k in OUT3 if not e[k][3]]


def cpu(r):
    """A rung's CPU seconds, marked when the contact solve was the field split (the kept factorisation otherwise)."""
    return f"{r['cpu']:.0f}" + (" (split)" if r.get("solver") == "fieldsplit" else "")


def ladder_table(res, group, model, tol):
    """One ladder: a row per rung (in brackets the error against its own limit), then its limits."""
    (pu, _, _), (cu, _, _), (hu, _, _) = GROUPS[group]["units"]
    rows, lim = ladder(res, model, tol), limits(res, model, tol)
    label = MODELS[model]["label"] + (f", time steps at tol {tol:g}" if tol else "")
    lines = [f"**{label}**", "", f"| h_tip [µm] | unknowns | P [{pu}] | creep [{cu}] | h_res [{hu}] | steps | UMAT calls "
             "| CPU [s] | memory [MB] |", "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [fmt(group, k, r["o"][k]) + (f" ({r['o'][k] / lim[k][1] - 1:+.1%})" if lim[k][1] else "") for k in OUT3]
        lines.append(f"| {r['h_tip']:.4g} | {r['unknowns']} | {' | '.join(cells)} | {r['steps']} | "
                     f"{r.get('umat_calls', 0) / 1e6:.1f} M | {cpu(r)} | {r.get('rss_mb', 0):.0f} |")
    if len(rows) >= 3:
        lim_cells = ["the last three rungs' ratios differ" if not equal_ratios([r["h_tip"] for r in rows]) else
                     f"{fmt(group, k, lim[k][1])} (p = {lim[k][0]:.2f})" if lim[k][1] else
                     f"erratic (p = {lim[k][0]:.2f})" if lim[k][0] else "not monotone" for k in OUT3]
        band = [bracket([r["h_tip"] for r in rows], [r["o"][k] for r in rows]) for k in OUT3]
        lines += [f"| Richardson limit | | {' | '.join(lim_cells)} | | | | |",
                  "| limit if p = 1 … 2 (last two rungs) | | "
                  + " | ".join(f"{fmt(group, k, b[0])} – {fmt(group, k, b[1])}" for k, b in zip(OUT3, band)) + " | | | | |"]
    return lines + [""]


def within(errors):
    """'1 %' or '2 %' when every error is at most that, else ''."""
    worst = max(map(abs, errors))
    return "1 %" if worst <= 0.01 else "2 %" if worst <= 0.02 else ""


def against_table(res, group, ref, hw, how, loose):
    """Every rung of the scene against its converged answer, sorted by CPU time; the shipped mesh marked; no rung
    marked within 1 or 2 % where an output (loose) is not converged."""
    g = GROUPS[group]
    lines = [f"**Every rung against the converged answer** ({how}: P = {fmt(group, OUT3[0], ref[OUT3[0]])} "
             f"{g['units'][0][0]} ± {hw[OUT3[0]]:.1%}, creep = {fmt(group, OUT3[1], ref[OUT3[1]])} {g['units'][1][0]} ± "
             f"{hw[OUT3[1]]:.1%}, h_res = {fmt(group, OUT3[2], ref[OUT3[2]])} {g['units'][2][0]} ± {hw[OUT3[2]]:.1%}), "
             "sorted by CPU time; within: the largest of the three errors is at most 1 % or 2 %"
             + ("" if not loose else f" (no mark here: {', '.join(SHORT[k] for k in loose)} not converged)"), "",
             "| model | h_tip | unknowns | CPU [s] | UMAT calls | P | creep | h_res | within |",
             "|---|---|---|---|---|---|---|---|---|"]
    rows = [r for r in res.values() if "failed" not in r and MODELS.get(r["model"], {}).get("group") == group]
    for r in sorted(rows, key=lambda r: r["cpu"]):
        e = [r["o"][k] / ref[k] - 1 for k in OUT3]
        label = MODELS[r["model"]]["label"] + (f", tol {r['tol']:g}" if r.get("tol") else "")
        at = (r["model"], round(r["h_tip"], 6))
        if r.get("tol") is None and at == g["shipped"]:
            label = f"**{label}: the shipped scene**"
        elif r.get("tol") is None and at == g["before"]:
            label = f"{label}: shipped before"
        lines.append(f"| {label} | {r['h_tip']:.4g} | {r['unknowns']} | {cpu(r)} | {r.get('umat_calls', 0) / 1e6:.1f} M | "
                     + " | ".join(f"{x:+.1%}" for x in e) + f" | {'' if loose else within(e)} |")
    return lines + [""]


def intro(pv):
    return [TITLE, "",
            f"Command: `{pv.get('command', '')}` ({pv.get('date', '')}; {pv.get('note', '')}).",
            "`bench/indent_convergence_bench.py` (issue 12, items 3-4; issue 25, item 5): the 3D indentation scenes as shipped",
            "(Cam-Clay IX; exponential load to the target depth, hold 60 s, unload in 20 s; the shipped time-step settings,",
            "output measure tol 1.5e-2) on ladders of h_tip at ratio about √2. 3D: h_tip within r_fine of the tip (0.9 µm,",
            "the whole contact at 200 nm: the Berkovich's corners reach 0.87 µm; × 25 for BN and BP), h_far = 4 or 8 h_tip",
            "as the ladder says (P1: 8 h_tip); 'r_fine 0.4' is the family of the scenes before (the contact's rim in the",
            "graded zone). Axisymmetric: r_fine as shipped (0.4 µm; BN's 10 µm), h_far 7.5 h_tip. Fields off, one rank,",
            "one run per rung, under nice -n 10. P: the indenter's whole load at the end of loading; creep: depth gained",
            "over the hold; h_res: residual depth. In brackets: the error against the Richardson limit of the ladder's own",
            "last three rungs. CPU: user + system of the driver (gmsh's meshing included) [s]; '(split)': the contact solve",
            "was the field split (`-indent_solver auto` above 50 000 unknowns, its threshold when those rungs ran), else",
            "the kept factorisation (the rungs record which); memory: the driver's peak resident set [MB]. On a shared",
            "machine (2 cores, other jobs running) the wall time is not comparable, the CPU time roughly. The results",
            "are kept in `docs/results/indent_convergence.json` (the bench's --results), each rung with its date and",
            "commit.", ""]


def section(store, root=None):
    """The section from the store; the reading from bench/indent_convergence_conclusions.md of the repository root."""
    res = store.get("rungs", {})
    lines = intro(store.get("provenance", {}))
    for group, g in GROUPS.items():
        if not ladders(res, group):
            continue
        lines += [f"### {g['title']}", ""]
        for model, tol in ladders(res, group):
            lines += ladder_table(res, group, model, tol)
        ref, hw, how, loose = reference(res, group)
        if ref:
            lines += against_table(res, group, ref, hw, how, loose)
    failed = sorted((r for r in res.values() if "failed" in r), key=lambda r: (r["model"], -r["h_tip"]))
    if failed:
        lines += ["Rungs that did not run: " + "; ".join(f"{MODELS[r['model']]['label']} at h_tip {r['h_tip']:.4g} "
                                                        f"({DRIVER.sub('', r['failed'])})" for r in failed) + ".", ""]
    conclusions = repo_root(root) / "bench" / "indent_convergence_conclusions.md"
    if conclusions.exists():   # the reading, written by hand from the tables
        lines += [conclusions.read_text().rstrip(), ""]
    return "\n".join(lines) + "\n"


NAMES = dict(zip(OUT3, ("P", "creep", "h_res")))
KEPT_KEYS = {"kerogen": ("berkovich_cone_elastic", "shipped_cost"), "BN": ("cost",), "BP": ("cost",)}  # in KEPT


def scaled(group, k, v):
    """An output in the store's units (µm, µN) in the units the documents print for the scene."""
    return v * GROUPS[group]["units"][OUT3.index(k)][1]


def rungs(res, group):
    """Every finished rung of a scene at the shipped time-step tolerance, keyed 'model_h_tip'."""
    out = {}
    for r in res.values():
        if "failed" in r or r.get("tol") or MODELS.get(r["model"], {}).get("group") != group:
            continue
        out[f"{r['model']}_{r['h_tip']:.4g}"] = {
            **{NAMES[k]: scaled(group, k, r["o"][k]) for k in OUT3}, "unknowns": r["unknowns"], "cpu": r["cpu"], "steps": r["steps"], "umat_calls_M": r.get("umat_calls", 0) / 1e6,
            "rss_mb": r.get("rss_mb")}
    return dict(sorted(out.items()))


def lists(res, group, model, shipped=None):
    """A ladder as lists, coarsest first, with its Richardson limits (None where the rungs do not converge)."""
    rows = ladder(res, model)
    d = {"h_tip": [r["h_tip"] for r in rows], "unknowns": [r["unknowns"] for r in rows],
         "cpu": [r["cpu"] for r in rows], "steps": [r["steps"] for r in rows]}
    for k in OUT3:
        xs = [scaled(group, k, r["o"][k]) for r in rows]
        p, lim = richardson(d["h_tip"], xs)
        d[NAMES[k]], d[NAMES[k] + "_limit"], d[NAMES[k] + "_order"] = xs, lim, p
    if shipped in d["h_tip"]:  # the shipped scene's rung, by name
        i = d["h_tip"].index(shipped)
        d.update(shipped=shipped, ship={q: d[q][i] for q in ("P", "creep", "h_res", "unknowns", "cpu")})
    return d


def adapted(adapt, case):
    """The last two adapted levels of bench/adapt_bench.py's case (its q in nm and µN; to mN, nm, µm)."""
    levels = adapt.get("cases", {}).get(case, {}).get("levels", [])[-2:]
    f = {"P": 1e-3, "creep": 1, "h_res": 1e-3}
    return {**{q: [lv["q"][q] * f[q] for lv in levels] for q in f}, "unknowns": [lv["unknowns"] for lv in levels]}


def summary(store, adapt, kept):
    """The numbers the documents quote: the kerogen reference and rungs, BN's and BP's ladders, BN's twin, their
    adapted levels; with the carried-over figures of kept (docs/results/indent3d.json)."""
    res = store.get("rungs", {})
    out = {g: {k: kept.get(g, {}).get(k) for k in KEPT_KEYS[g] if k in kept.get(g, {})} for g in KEPT_KEYS}
    ref, hw, how, _ = reference(res, "kerogen")
    if ref:
        out["kerogen"]["reference"] = {**{NAMES[k]: scaled("kerogen", k, ref[k]) for k in OUT3},
                                       "hw": {NAMES[k]: hw[k] for k in OUT3}, "how": how}
    out["kerogen"].update(rungs=rungs(res, "kerogen"), p2=lists(res, "kerogen", "sector2", 0.12),
                          p1=lists(res, "kerogen", "sector1"))
    out["BN"].update(p2=lists(res, "BN", "bn2", 2.5), p1=lists(res, "BN", "bn1"), adapted=adapted(adapt, "bn"))
    twin = converged(res, "bnaxi2")
    if twin:
        h = twin["residual depth"][0]
        out["BN"]["twin_h_res"] = h
        out["BN"]["twin_from_h_tip"] = next(r["h_tip"] for r in ladder(res, "bnaxi2")
                                            if abs(r["o"]["residual depth"] / h - 1) < 1e-3)
        out["BN"]["twin"] = lists(res, "BN", "bnaxi2")
    out["BP"].update(p2=lists(res, "BP", "bp2", 2.5), adapted=adapted(adapt, "bp"))
    return out


def numbers(store_dir=None):
    """summary() of the stores in docs/results (or store_dir); {} without the study's store."""
    store = results_store.load(STORE, store_dir)
    return summary(store, results_store.load("adapt_bench", store_dir), results_store.load(KEPT, store_dir)) if store else {}
