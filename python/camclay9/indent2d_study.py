"""The mesh and element study of the paper's 2D indentation scenes (issue 26; bench/indent2d_convergence_bench.py runs
it): its scenes and ladders, each scene's converged answer from the rungs (Richardson limit or mean of the finest
three), and the section "## 2D indentation: mesh and element study" of docs/performance.md written from the results
store (docs/results/indent2d_convergence.json), which tools/doc_numbers.py checks.
"""
import math
import time
from pathlib import Path

import yaml

from camclay9.convergence import richardson
from camclay9.launch import repo_root

TITLE = "## 2D indentation: mesh and element study"
R2 = math.sqrt(2)
# The shipped loading-rate scenes, and bedding at theta = 0 and 90, are half models (x >= 0, the mirror plane x = 0,
# indenter.copies 2); the study's ladders ran on the whole block, and keep to it: these replacements turn the one into
# the other.
HALF_TO_WHOLE = (("half: 1,", "half: 0,"),
                 ("    - {group: right, components: [x]}\n  mirror:\n    - {group: left, normal: [1, 0]}   # x = 0, the indenter's axis\n",
                  "    - {group: left, components: [x]}\n    - {group: right, components: [x]}\n"),
                 ("contact: contact, copies: 2}", "contact: contact}"))


def half_model_scene(text):
    """Whether a plane-strain indentation scene's text is the half model (indent_block2d.geo's half: 1)."""
    return HALF_TO_WHOLE[0][0] in text


def whole_block(text):
    """A shipped plane-strain half model's scene text as the whole block it is half of (unchanged if it is not one)."""
    if not half_model_scene(text):
        return text
    for old, new in HALF_TO_WHOLE:
        assert text.count(old) == 1, f"the half model's scene has no single {old!r}"
        text = text.replace(old, new)
    return text


# scene key: (scene file, length scale (the bedding block is the loading-rate block x 25), region under the tip,
# a change of the scene's text or None). "lrphi": the loading-rate scene with the hard frame (phi 0.5, as the
# bedding scenes), whose elastic shear stiffness keeps the mixture from the incompressibility of the soft frame's flow
SCENES = {"lr": ("loading_rate_a1", 1.0, (-0.125, 0.125, -0.25, 0.0), None),
          "lrphi": ("loading_rate_a1", 1.0, (-0.125, 0.125, -0.25, 0.0), ("set: {phi: 0}", "set: {phi: 0.5}")),
          "bed": ("bedding_theta45", 25.0, (-1.35, 1.35, -2.7, 0.0), None),
          "lr01": ("loading_rate_a0.1", 1.0, (-0.125, 0.125, -0.25, 0.0), None),
          "lr10": ("loading_rate_a10", 1.0, (-0.125, 0.125, -0.25, 0.0), None)}
KEYS = ("h_max", "creep", "h_res", "sig_load", "sig_hold", "dsig")
LIMIT = {"h_max": 0.01, "creep": 0.01, "h_res": 0.01, "sig_hold": 0.05}   # the shipped model's budget
REPORTED = ("h_max", "creep", "sig_hold")   # what the shipped 2D scenes report (they have no unload: no h_res)
LABEL = {"h_max": "h_max [nm]", "creep": "creep [nm]", "h_res": "h_res [nm]", "sig_load": "σ̄ load [MPa]",
         "sig_hold": "σ̄ hold [MPa]", "dsig": "Δσ̄ [MPa]"}
# ladder: (label, scene, order, what varies, the fixed value, the ladder in loading-rate units (x scale for bed))
H_LR = [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01, 0.01 / R2, 0.005]
LADDERS = {
    "lr2": ("loading rate, P2, r_fine 0.6", "lr", 2, "h_tip", 0.6, H_LR[:6]),
    "lr1": ("loading rate, P1, r_fine 0.6", "lr", 1, "h_tip", 0.6, H_LR[2:]),
    "lr2r": ("loading rate, P2, h_tip 0.02", "lr", 2, "r_fine", 0.02, [0.4, 0.6, 0.9]),
    "lr1r": ("loading rate, P1, h_tip 0.02", "lr", 1, "r_fine", 0.02, [0.4, 0.6, 0.9]),
    "lr1old": ("loading rate, P1, r_fine 0.4 (as shipped)", "lr", 1, "h_tip", 0.4, [0.02, 0.01, 0.005]),
    "lr2f": ("loading rate, P2, r_fine 0.9", "lr", 2, "h_tip", 0.9, [0.04, 0.04 / R2, 0.02, 0.02 / R2, 0.01, 0.01 / R2]),
    "lr2n": ("loading rate, P2, r_fine 0.9, other meshes near h_tip 0.02 (mesh noise)", "lr", 2, "h_tip", 0.9, [0.0206, 0.0194]),
    "lr2t": ("loading rate, P2, h_tip 0.02, r_fine 0.9, time-step tol", "lr", 2, "tol", (0.02, 0.9), [5e-3]),
    "lrphi1": ("loading rate with the hard frame (φ = 0.5), P1, r_fine 0.6", "lrphi", 1, "h_tip", 0.6, [0.02]),
    "lrphi2": ("loading rate with the hard frame (φ = 0.5), P2, r_fine 0.6", "lrphi", 2, "h_tip", 0.6, [0.04]),
    "bed2": ("bedding 45°, P2, r_fine 10", "bed", 2, "h_tip", 0.4, H_LR[:6]),
    "bed1": ("bedding 45°, P1, r_fine 10", "bed", 1, "h_tip", 0.4, H_LR[:6]),
    "bed2r": ("bedding 45°, P2, h_tip 0.5", "bed", 2, "r_fine", 0.02, [0.24, 0.4, 0.6]),
    # the other loading rates on the shipped family (issue 36, item 3): not run yet (about 1 h CPU each to h_tip 0.0071)
    "lr01f": ("loading rate α = 0.1, P2, r_fine 0.9", "lr01", 2, "h_tip", 0.9, [0.02, 0.02 / R2, 0.01, 0.01 / R2]),
    "lr10f": ("loading rate α = 10, P2, r_fine 0.9", "lr10", 2, "h_tip", 0.9, [0.02, 0.02 / R2, 0.01, 0.01 / R2]),
}
# scene, order, h_tip, r_fine of the uniform mesh the scene ships (bedding: the uniform mesh it shipped before it adapted)
SHIPPED = {"lr": ("loading_rate_a1", 2, 0.01414, 0.9), "bed": ("bedding_theta45", 2, 0.25, 10.0),
           "lr01": ("loading_rate_a0.1", 2, 0.01414, 0.9), "lr10": ("loading_rate_a10", 2, 0.01414, 0.9)}
STORE = "indent2d_convergence"   # docs/results/indent2d_convergence.json (camclay9.results_store)


def rungs(ladder):
    """[(scene, order, h_tip, r_fine, tol)] of a ladder, in the scene's own units (tol None: as shipped)."""
    _, skey, order, vary, fixed, values = LADDERS[ladder]
    s = SCENES[skey][1]
    if vary == "tol":
        return [(skey, order, fixed[0] * s, fixed[1] * s, v) for v in values]
    return [(skey, order, v * s, fixed * s, None) if vary == "h_tip" else (skey, order, fixed * s, v * s, None)
            for v in values]


def key(skey, order, h_tip, r_fine, tol=None):
    return f"{skey}:P{order}:h{h_tip:.4g}:r{r_fine:.4g}" + (f"@{tol:g}" if tol else "")


def shipped_rung(rungs, skey):
    """The rung of `rungs` (a store's "rungs") with the shipped scene's order, h_tip and r_fine (SHIPPED), or None."""
    _, order, h_tip, r_fine = SHIPPED[skey]
    return rungs.get(key(skey, order, h_tip, r_fine))


def ladder_rows(res, ladder):
    rows = [res.get(key(*g)) for g in rungs(ladder)]
    return [r for r in rows if r and "failed" not in r]


def estimate(hs, xs):
    """One output of a ladder from its finest three rungs: (value, relative half-width, rule). Where they converge
    (monotone, the differences shrinking, an observed order of 0.5 to 4) their Richardson limit, +- its distance to
    the finest rung; otherwise (not monotone, or the differences not shrinking: the meshes' noise as large as what
    is left of the trend) their mean, +- the larger of half their range and the mean's distance to the finest rung
    (a trend not yet settled shows there). The rule is printed beside the answer."""
    if len(xs) < 3:
        return None
    p, x = richardson(hs, xs)
    if x is not None:
        return x, abs(x - xs[-1]) / abs(x), f"Richardson, p = {p:.2f}"
    m = sum(xs[-3:]) / 3
    return m, max((max(xs[-3:]) - min(xs[-3:])) / 2, abs(m - xs[-1])) / abs(m), "mean of the finest three"


# the ladders that give a scene's converged answer (P2, the fine zone over the whole contact) and its P1 check
REFERENCE = {"lr": ("lr2f", "lr1"), "bed": ("bed2", "bed1"), "lr01": ("lr01f", None), "lr10": ("lr10f", None)}


def reference(res, skey):
    """The converged 2D answer of a scene per output (estimate() on the P2 ladder of REFERENCE, its own +-) and
    the P1 ladder's estimate by the same rule, shown beside it (on the loading rate P1 locks: its distance is
    P1's error, not the answer's). None for lrphi (a P1-against-P2 check only) and for a ladder not run."""
    if skey not in REFERENCE:
        return None
    a, b = REFERENCE[skey]
    out = {}
    for k in KEYS:
        rows = ladder_rows(res, a)
        e = estimate([r["h_tip"] for r in rows], [r["o"][k] for r in rows])
        if e is None:
            return None
        rows1 = ladder_rows(res, b) if b else []
        e1 = estimate([r["h_tip"] for r in rows1], [r["o"][k] for r in rows1])
        out[k] = dict(value=e[0], hw=e[1], rule=e[2], p1=e1[0] if e1 else None)
    return out


def fmt(k, v):
    return f"{v * 1e3:.2f}" if k in ("h_max", "creep", "h_res") else f"{v:.1f}"


def _f(x, spec):
    return "" if x is None else format(x, spec)


def ratio_cell(r):
    return f"{r['cpu'] / (r['umat_calls'] * r['t_call']):.1f}" if r.get("t_call") else ""


INTRO = ("`bench/indent2d_convergence_bench.py` (issue 26): loading_rate_a1 and bedding_theta45 (material, loads, steps as "
         "shipped), with an unload to zero in 20 s added for the residual depth, on ladders of h_tip (h_far = 7.5 h_tip: the "
         "whole mesh refined) and of the fine zone's radius r_fine, P1 and P2. h_max: depth at the end of loading; creep: the "
         "depth gained over the 2000 s hold; h_res: the residual depth; σ̄: the mean of ‖σ‖ over the region under the tip "
         "(|x| < 0.125, −0.25 < y < 0 µm for the loading rate, × 10.8 for the bedding: a/4 by a/2 of each scene's contact "
         "half-width a, cells clipped to it) at the end of the load and of the hold, Δσ̄ its change over the hold (Fig. 13's "
         "quantity); chk: the checkerboard of ‖σ‖ at the end of the hold within a of the tip (RMS of each cell's difference "
         "from its vertices' nodal averages over the RMS of ‖σ‖); vol: |tr εvp| / ‖dev εvp‖ there (area means; 0: isochoric "
         "flow, which locks linear triangles). In brackets: the error against the scene's converged 2D answer (below each "
         "scene). CPU: user + system of the driver, one run per rung, on a shared machine; ×UMAT: CPU over UMAT calls × the "
         "UMAT benchmark's viscoplastic plane-strain time per call measured at the start of the same invocation (the physics "
         "floor is 1). The rungs are kept in docs/results/indent2d_convergence.json, from which this section is written.")
RULE = ("per output, from the P2 ladder's finest three rungs: their Richardson limit where they converge (monotone, the "
        "differences shrinking, an observed order of 0.5 to 4), ± its distance to the finest rung; otherwise their mean, ± "
        "the larger of half their range and the mean's distance to the finest rung (the meshes' noise is as large as what is "
        "left of the trend). The P1 ladder's value by the same "
        "rule is given beside it, not folded into the ±")


def ladder_table(res, lad, ref):
    label, sk, order, vary, fixed, _ = LADDERS[lad]
    rows = ladder_rows(res, lad)
    if not rows:
        return []
    L = [f"**{label}**", "", f"| {vary} [µm] | unknowns | " + " | ".join(LABEL[k] for k in KEYS)
         + " | chk | vol | steps | CPU [s] | UMAT calls | ×UMAT |", "|---" * (len(KEYS) + 8) + "|"]
    for r in rows:
        cells = [fmt(k, r["o"][k]) + (f" ({r['o'][k] / ref[k]['value'] - 1:+.1%})" if ref else "") for k in KEYS]
        L.append(f"| {r[vary]:.4g} | {r['unknowns']} | " + " | ".join(cells)
                 + f" | {r['checker']:.2f} | {_f(r.get('vol'), '.3f')} | {r['steps']} | {r['cpu']:.0f} | {r['umat_calls']:.3g} | {ratio_cell(r)} |")
    if vary == "h_tip" and len(rows) >= 3:
        cells = []
        for k in KEYS:
            p, x = richardson([r["h_tip"] for r in rows], [r["o"][k] for r in rows])
            cells.append(f"{fmt(k, x)} (p = {p:.2f})" if x is not None else (f"erratic (p = {p:.2f})" if p else "not monotone"))
        L.append("| Richardson limit | | " + " | ".join(cells) + " | | | | | | |")
    return L + [""]


def shipped_lines(skey, ref, paper, root=None):
    """The shipped scene itself (docs/results/paper.json, the reproduction's run: no unload, its own mesh of the
    shipped density, h_far rounded; the loading-rate scenes' a half model) against the converged answer: the numbers
    docs/paper.md shows."""
    s = (paper.get("numbers", {}).get("indent", {}) if paper else {}).get(SHIPPED[skey][0])
    if not s or not ref:
        return []
    e = {"h_max": s["depth_end_of_load"] / ref["h_max"]["value"] - 1, "creep": s["creep_depth"] / ref["creep"]["value"] - 1}
    text = (Path(root or repo_root()) / "input" / f"{SHIPPED[skey][0]}.yaml").read_text()
    first = adapted_from(text)
    reruns = {1: "once", 2: "twice"}.get(first[1], "by reruns") if first else ""
    model = (f"a mesh adapted {reruns} to its answer from a first mesh of h_tip {first[0]:g} µm (docs/adapt.md)" if first else
             "the half model x ≥ 0 on a mesh of the shipped density (\"2D indentation: the half model\"), another draw of the "
             "same mesh noise" if half_model_scene(text) else "its own mesh of the shipped density, another draw of the same mesh noise")
    return [f"The shipped scene itself ({SHIPPED[skey][0]}.yaml, as docs/paper.md runs it; {model}): depth at the end of loading {s['depth_end_of_load'] * 1e3:.4g} nm "
            f"({e['h_max']:+.1%}), creep depth {s['creep_depth'] * 1e3:.4g} nm ({e['creep']:+.1%}).", ""]


def adapted_from(text):
    """(its first mesh's h_tip, its reruns) where a scene adapts its mesh (mesh.adapt), else None."""
    mesh = yaml.safe_load(text).get("mesh", {})
    return (mesh["parameters"]["h_tip"], mesh["adapt"].get("levels")) if mesh.get("adapt") else None


def within_table(res, skey, ref, root=None):
    cand = sorted((r for r in res.values() if r.get("scene") == skey and "failed" not in r), key=lambda r: r["cpu"])
    ship = SHIPPED.get(skey)
    adapted = ship and adapted_from((Path(root or repo_root()) / "input" / f"{ship[0]}.yaml").read_text())
    L = ["Within: ✓ all four within their limits (1 %, 5 % for σ̄ hold); ◐ those the scenes report (h_max, creep, σ̄ hold). "
         "Δσ̄ (Fig. 13's quantity) is stated, not in the limits. **Bold**: the shipped scene's mesh parameters"
         + (" before it adapted its mesh (below)." if adapted else "."), "",
         "| model | h_tip | r_fine | unknowns | CPU [s] | " + " | ".join(LABEL[k].split(" [")[0] for k in (*LIMIT, "dsig"))
         + " | within |", "|---" * (7 + len(LIMIT)) + "|"]
    for r in cand:
        e = {k: r["o"][k] / ref[k]["value"] - 1 for k in (*LIMIT, "dsig")}
        ok = "✓" if all(abs(e[k]) <= LIMIT[k] for k in LIMIT) else "◐" if all(abs(e[k]) <= LIMIT[k] for k in REPORTED) else ""
        m = f"P{r['order']}"
        if ship and (r["order"], round(r["h_tip"], 5), r["r_fine"]) == ship[1:] and not r.get("tol"):
            m = f"**{m} (shipped{' before' if adapted else ''})**"
        L.append(f"| {m} | {r['h_tip']:.4g} | {r['r_fine']:.4g} | {r['unknowns']} | {r['cpu']:.0f} | "
                 + " | ".join(f"{e[k]:+.1%}" for k in (*LIMIT, "dsig")) + f" | {ok} |")
    return L + [""]


def store_data(res, command, note, date=None):
    """The store file of this section: the rungs, the command, and each scene's converged answer with its rule."""
    return {"provenance": {"command": command, "date": date or time.strftime("%Y-%m-%d", time.gmtime()), "note": note,
                           "rule": RULE},
            "rungs": res, "reference": {sk: reference(res, sk) for sk in SCENES if reference(res, sk)}}


def section(store, paper=None, root=None):
    """The section of docs/performance.md, from the store (store_data) and the reproduction's store (paper.json),
    followed by the reading written by hand in bench/indent2d_convergence_conclusions.md of the repository `root`
    (default: camclay9.repo_root())."""
    pv, res = store["provenance"], store["rungs"]
    L = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}; {pv['note']}).", INTRO, ""]
    for skey in SCENES:
        ref = store["reference"].get(skey)
        for lad in LADDERS:
            if LADDERS[lad][1] == skey:
                L += ladder_table(res, lad, ref)
        if ref:
            L += [f"**{SCENES[skey][0]}: the converged 2D answer** ({RULE}): "
                  + ", ".join(f"{LABEL[k].split(' [')[0]} {fmt(k, ref[k]['value'])} ± {ref[k]['hw']:.1%} ({ref[k]['rule']}"
                              + (f"; P1: {fmt(k, ref[k]['p1'])}, {ref[k]['p1'] / ref[k]['value'] - 1:+.1%}" if ref[k]['p1'] else "")
                              + ")" for k in KEYS), ""]
            L += within_table(res, skey, ref, root) + shipped_lines(skey, ref, paper, root)
    missing = [SCENES[sk][0] for sk in REFERENCE if sk not in store["reference"]]
    if missing:
        L += [f"**Not run: {', '.join(missing)}** (`--ladders lr01f,lr10f`, about 1 h CPU each on this machine): the mesh "
              "error of the other loading rates is taken to be α = 1's, not measured.", ""]
    conclusions = repo_root(root) / "bench" / "indent2d_convergence_conclusions.md"
    if conclusions.exists():
        L += [conclusions.read_text()]
    return "\n".join(L) + "\n"
