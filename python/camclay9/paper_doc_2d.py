"""docs/paper.md's 2D studies (Yin, Liu & Borja 2021, §4, Figs. 7-15): the paper's words, our numbers
(camclay9.paper_fields, camclay9.paper_numbers) and a verdict for every figure that states a result. Each verdict follows a rule written here
from the paper's sentence, not from our runs; the rule is printed with the verdict.
"""
from camclay9.paper_fields import HOLD_TIMES, ZONE_CUTOFFS, ZONE_LEVELS
from camclay9.paper_numbers import ALPHAS, THETAS_BEDDING, stated_text

TILT = 2.0        # deg: a principal flow axis within this of the load axis is no tilt (Fig. 15)
TIMES11 = tuple(f"{t:g}" for t in HOLD_TIMES)   # Fig. 11's panels: its rules are evaluated at each of these hold times


def _f(x, fmt=".3g"):
    return "—" if x is None else format(x, fmt)


def _v(ok):
    return "**agrees**" if ok else "**differs**"


def _lr(ind):
    return {a: ind.get(f"loading_rate_a{a}") or {} for a in ALPHAS}


def fig10b(s, key="fig10b"):
    """Fig. 10: "at the conclusion of the creep stage, an inelastic zone forms at a finite distance away from the
    indenter tip, and not directly below it". Rule: the ring means peak away from the tip (ring centre >= a/4) and at
    least 10 % above the innermost ring. key "fig10b": of the hold's growth of |evp| (the zone the creep forms, the
    sentence's subject); "fig10b_total": of the total |evp| at the hold's end (what the paper's Fig. 10 draws, the
    loading's strain included)."""
    b = s[key]
    return b["r_peak"] >= 0.25 and b["peak_over_tip_ring"] >= 1.1


def fig11(alpha, z):
    """Fig. 11 at one hold time. alpha 0.1: "the inelastic zones develop from the top surface ... on the left and right
    sides of the indenter": the sector beside the indent (0-30 deg from the surface) holds the largest share. alpha 10:
    "develops throughout the entire circular region": the zone fills at least half its half-disc and no sector holds
    more than half. alpha 1 ("merge into a circular region, although the maximum ... close to the top surface"):
    fills at least half its half-disc."""
    if alpha == "0.1":
        return z["surface"] >= max(z["middle"], z["beneath"])
    if alpha == "10":
        return z["fill"] >= 0.5 and max(z["surface"], z["middle"], z["beneath"]) <= 0.5
    return z["fill"] >= 0.5


FIG11_RULE = ("rules: α = 0.1 the sector beside the indent holds the largest share; α = 10 the zone fills ≥ half its "
              "half-disc with no sector above half; α = 1 fills ≥ half; the zone: Δ‖εvp‖ above 10 % of its 99th percentile (by area) "
              "within 3a; each rule at every hold time of the paper's panels, " + ", ".join(f"{t} s" for t in TIMES11)
              + "; percentiles by area since 2026-12-02: by cell count they moved with the mesh, docs/performance.md, "
              "\"Figs. 9 and 11: percentiles by area, not by cell count\"")


def fig11_times(alpha, s):
    """The verdict at each hold time, and how many of the (zone level, cutoff) pairs give the same verdict there."""
    out = {}
    for t in TIMES11:
        ok = fig11(alpha, s["fig11"][t])
        sens = s.get("fig11_sens", {}).get(t, {})
        out[t] = (ok, sum(fig11(alpha, z) == ok for z in sens.values()), len(sens))
    return out


def fig11_text(alpha, s):
    """'agrees at 100 s (9/9 pairs), differs at 500 s (7/9), ...': each hold time's verdict and its robustness."""
    return ", ".join(f"{'agrees' if ok else 'differs'} at {t} s" + (f" ({same}/{n})" if n else "")
                     for t, (ok, same, n) in fig11_times(alpha, s).items())


def fig11_verdict(alpha, s):
    """One verdict where every hold time gives the same, else each time's: '**agrees** at 100 s, **differs** at 500, 2000 s'."""
    t = fig11_times(alpha, s)
    oks = [ok for ok, _, _ in t.values()]
    if all(oks) or not any(oks):
        return _v(oks[0])
    return ", ".join(f"{_v(v)} at " + ", ".join(k for k, (ok, _, _) in t.items() if ok == v) + " s" for v in (True, False))


def fig9(R):
    """Fig. 9: "the deviatoric viscoplastic strain ... more intense and more concentrated, the volumetric weaker and
    more pervasive". Rule, for every alpha: dev's 99th percentile within 2a above tr's, and dev above 10 % of its own
    99th percentile over a smaller share of the half-disc r < 2a than tr."""
    return all(r["dev_p99"] > r["tr_p99"] and r["dev_frac"] < r["tr_frac"] for r in R.values())


def fig13(alpha, v):
    """Fig. 13: the stress "at a point in contact with the tip" increases during the hold for alpha 0.1 and decreases
    for 1 and 10. Rule: the sign of the region mean's change over the whole hold (its largest value over the hold's
    outputs is printed beside it: an early rise that falls back shows there)."""
    return (v["change_end"] > 0) == (alpha == "0.1")


def fig15(f):
    """Fig. 15: "the material flows from the stronger BP direction to the weaker BN direction". Rule: the principal
    axis of the hold's displacement increments tilts from the load axis by more than TILT toward BN's side."""
    if abs(f["beta"]) < TILT:
        return None
    return f["beta"] * f["beta_bn"] > 0


def summary_rows(n, trends):
    ind, f13 = n["indent"], n["fig13"]
    t = {k: x for k, x in zip(("rate", "aniso"), trends)}
    S = _lr(ind)
    rows = [f"| 7, 8 | faster loading: shallower indent, more creep (§4.1) | {t['rate']['detail']} | {_v(t['rate']['ok'])} |"]
    R = {a: s.get("regions") for a, s in S.items()}
    if all(R.values()):
        rows.append("| 9 | ‖dev εvp‖ more intense, more concentrated; tr εvp weaker, more pervasive (§4.1) | dev/tr 99th percentile "
                    + ", ".join(f"{r['dev_p99'] / r['tr_p99']:.0f}×" for r in R.values()) + " for α = 0.1, 1, 10; share of the "
                    "half-disc r < 2a above 10 % of its own 99th percentile, dev / tr: "
                    + ", ".join(f"{r['dev_frac']:.2f} / {r['tr_frac']:.2f}" for r in R.values()) + " | "
                    + _v(fig9(R)) + " |")
    ev = [s.get("evp_start") for s in S.values()]
    if all(ev):
        rows.append("| 10 (a) | before creep, faster loading → less viscoplastic strain around the tip (§4.1) | mean ‖εvp‖ within 0.5 µm: "
                    + " > ".join(f"{e['mean']:.3g}" for e in ev) + " | " + _v(ev[0]["mean"] > ev[1]["mean"] > ev[2]["mean"]) + " |")
    if all(s.get("fig10b") and s.get("fig10b_total") for s in S.values()):
        rows.append("| 10 (b) | at the end of creep the inelastic zone lies away from the tip, not below it (§4.1) | ring means "
                    "around the tip, peak at r / peak over the innermost ring, for α = 0.1, 1, 10: the hold's growth of ‖εvp‖ "
                    + ", ".join(f"{s['fig10b']['r_peak']:.2f} a / {s['fig10b']['peak_over_tip_ring']:.2f}×" for s in S.values())
                    + "; the total ‖εvp‖ " + ", ".join(f"{s['fig10b_total']['r_peak']:.2f} a / "
                                                       f"{s['fig10b_total']['peak_over_tip_ring']:.2f}×" for s in S.values())
                    + " | growth: " + ", ".join(f"α = {a}: {_v(fig10b(s))}" for a, s in S.items()) + "; total: "
                    + ", ".join(f"α = {a}: {_v(fig10b(s, 'fig10b_total'))}" for a, s in S.items()) + " |")
    if all(s.get("fig11") for s in S.values()):
        rows.append("| 11 | α = 0.1: zones from the surface beside the indent; α = 10: the whole circular region (§4.1) | share "
                    "beside / beneath, fill of the half-disc, at " + " / ".join(f"{t} s" for t in TIMES11) + ": " + "; ".join(
                        f"α = {a}: " + " / ".join(f"{s['fig11'][t]['surface']:.2f}, {s['fig11'][t]['beneath']:.2f}, "
                                                  f"{s['fig11'][t]['fill']:.2f}" for t in TIMES11) for a, s in S.items())
                    + " | " + "; ".join(f"α = {a}: {fig11_verdict(a, s)}" for a, s in S.items()) + " |")
    if all(R.values()):
        rows.append("| 12 | α = 0.1: sides relax; α = 1, 10: relaxation beneath the tip (§4.1) | Δ‖σ‖ beneath / beside: "
                    + ", ".join(f"{r['dsig_beneath']:+.3g} / {r['dsig_sides']:+.3g} MPa" for r in R.values())
                    + f" for α = 0.1, 1, 10 | α = 1, 10: {_v(all(R[a]['dsig_beneath'] < 0 for a in ('1', '10')))}; "
                    f"α = 0.1: {_v(R['0.1']['dsig_sides'] < 0 < R['0.1']['dsig_beneath'])} |")
    if f13:
        ours = ", ".join(f"α = {a}: {v['change_end']:+.3g} MPa (largest after its start {v['change_max']:+.3g}, {v['outputs']} outputs)"
                         for a, v in f13.items())
        rows.append(f"| 13 | ‖σ‖ beneath the tip rises for α = 0.1, falls for α = 1, 10 (§4.1) | region mean over the hold, {ours} | "
                    + "; ".join(f"α = {a}: {_v(fig13(a, v))}" for a, v in f13.items()) + " |")
    rows.append(f"| 14 | anisotropy weak in indentation creep (§4.2) | {t['aniso']['detail']}{thickness_note(ind)} | {_v(t['aniso']['ok'])} |")
    f = (ind.get("bedding_theta45") or {}).get("flow")
    if f:
        v = fig15(f)
        rows.append(f"| 15 | at θ = 45 the material flows from BP toward BN (§4.2) | principal axis of the hold's flow "
                    f"{abs(f['beta']):.1f}° from the load axis, on {'BN' if f['beta'] * f['beta_bn'] > 0 else 'BP'}'s side | "
                    + ("not distinguishable (tilt < 2°)" if v is None else _v(v)) + " |")
    return rows


def thickness_note(ind):
    c3 = [(ind.get(f"bedding_theta{t}_t3") or {}).get("creep_depth") for t in THETAS_BEDDING]
    if not all(c3):
        return ""
    return f"; at t = 3 µm (Berkovich-equivalent) max/min {max(c3) / min(c3):.3f}"


def loading_rate(n, trends, images, rel, img):
    ind, f13 = n["indent"], n["fig13"]
    S = _lr(ind)
    L = ["## Loading rate (§4.1, Figs. 7–13)", "",
         "**Paper.** “as the loading rate increases, the depth of indentation decreases … During the creep stage, however, "
         "larger viscoplastic deformations develop in materials that were subjected to higher loading rates” (§4.1, Fig. 7); "
         "“at a higher loading rate, creep deformation develops faster and the indent extends deeper” (Fig. 8). “Prior to "
         "creep, an increase of α from 0.1 to 10 leads to a significant decrease in the magnitude of the viscoplastic "
         "strain around the indenter tip” (Fig. 10); “at the conclusion of the creep stage, an inelastic zone forms at a "
         "finite distance away from the indenter tip, and not directly below it” (Fig. 10); “For α = 0.1, the inelastic "
         "zones develop from the top surface of the material on the left and right sides of the indenter … For α = 10, "
         "the inelastic zone develops throughout the entire circular region surrounding the indenter” (Fig. 11); for "
         "α = 0.1 “two fan-shaped regions on the two sides of the indent experience a reduction in stress”, for α = 1 and "
         "10 “stresses relax in the zones directly beneath the indenter” (Fig. 12); the stress “at a point in contact with "
         "the tip” increases during the hold for α = 0.1 and decreases for α = 1 and 10 (Fig. 13).", "",
         "**Ours** (the shipped scenes' model: README, “Which model each scene uses”; regions of the undeformed mesh, a = "
         f"{_f((S['1'].get('regions') or {}).get('a_ref'), 'g')} µm the contact half-width rounded; camclay9.paper_fields).", "",
         "| α | h at end of load [µm] | creep depth in 2000 s [µm] | mean / max ‖εvp‖ within 0.5 µm, start of hold | "
         "Δ‖σ‖ over the hold, region beneath the tip [MPa] | ‖σ‖ checkerboard within a |", "|---|---|---|---|---|---|"]
    for a, s in S.items():
        if not s:
            continue
        e, d = s.get("evp_start") or {}, f13.get(a, {})
        L.append(f"| {a} | {_f(s['depth_end_of_load'], '.4g')} | {_f(s['creep_depth'], '.4g')} | {_f(e.get('mean'))} / "
                 f"{_f(e.get('max'))} | {_f(d.get('change_end'), '+.3g')} (min {_f(d.get('change_min'), '+.3g')}, max "
                 f"{_f(d.get('change_max'), '+.3g')}) | {_f(s.get('checker'), '.2f')} |")
    L += fields_tables(S)
    L += ["", f"**Verdicts.** Figs. 7, 8: {_v(trends[0]['ok'])} ({trends[0]['detail']})."]
    L += fields_verdicts(S, f13)
    L += [""]
    for fid in ("fig7", "fig8", "fig13", "fig9", "fig10", "fig11", "fig12"):
        L.append(img(images, fid, rel))
    return L


def fields_tables(S):
    if not all(s.get("regions") and s.get("fig11") for s in S.values()):
        return []
    L = ["", "Figs. 9–12 as numbers (end of the hold unless said; the regions: beneath |x| < a/4, beside a/2 < |x| < 3a/2, "
         "both −a/2 < y < 0, cells clipped to them; rings around the tip of width a/6; percentiles by area, not by cell count; Fig. 11's zone: Δ‖εvp‖ above 10 % of "
         "its 99th percentile within 3a, its sectors 0–30°, 30–60°, 60–90° from the surface):", "",
         "| α | ‖dev εvp‖ / \\|tr εvp\\| (99th percentiles within 2a) | share of r < 2a above 10 % of it, dev / tr | ring of "
         "the peak, peak / innermost ring: hold's growth of ‖εvp‖; total ‖εvp‖ | Fig. 11 at " + " / ".join(f"{t} s" for t in TIMES11)
         + ": share beside, between, beneath; fill | Δ‖σ‖ beneath / beside [MPa] |", "|---|---|---|---|---|---|"]
    for a, s in S.items():
        r, b, bt, z = s["regions"], s["fig10b"], s["fig10b_total"], s["fig11"]
        zz = " / ".join(f"{z[k]['surface']:.2f}, {z[k]['middle']:.2f}, {z[k]['beneath']:.2f}; {z[k]['fill']:.2f}" for k in TIMES11)
        L.append(f"| {a} | {r['dev_p99']:.3g} / {r['tr_p99']:.3g} | {r['dev_frac']:.2f} / {r['tr_frac']:.2f} | "
                 f"r = {b['r_peak']:.2f} a, {b['peak_over_tip_ring']:.2f}; r = {bt['r_peak']:.2f} a, {bt['peak_over_tip_ring']:.2f} | "
                 f"{zz} | {r['dsig_beneath']:+.3g} / {r['dsig_sides']:+.3g} |")
    return L


def fields_verdicts(S, f13):
    L = []
    R = {a: s.get("regions") for a, s in S.items()}
    ev = [s.get("evp_start") for s in S.values()]
    if all(ev):
        ok = ev[0]["mean"] > ev[1]["mean"] > ev[2]["mean"]
        L.append(f"Fig. 10 (before creep; rule: the mean ‖εvp‖ within 0.5 µm of the tip at the start of the hold falls from "
                 f"α = 0.1 to 1 to 10): {_v(ok)}.")
    if all(s.get("fig10b") and s.get("fig10b_total") for s in S.values()):
        L.append("Fig. 10 (end of creep; rule: the ring means peak at r ≥ a/4 and ≥ 1.1× the innermost ring). The paper's "
                 "sentence is about the zone the creep forms, so the rule is applied to the hold's growth of ‖εvp‖: "
                 + "; ".join(f"α = {a}: {_v(fig10b(s))} (peak at r = {s['fig10b']['r_peak']:.2f} a, "
                             f"{s['fig10b']['peak_over_tip_ring']:.2f}×)" for a, s in S.items())
                 + ". Its Fig. 10 draws the total ‖εvp‖, the loading's strain included, which peaks at the tip: "
                 + "; ".join(f"α = {a}: {_v(fig10b(s, 'fig10b_total'))} (r = {s['fig10b_total']['r_peak']:.2f} a, "
                             f"{s['fig10b_total']['peak_over_tip_ring']:.2f}×)" for a, s in S.items()) + ".")
    if all(s.get("fig11") for s in S.values()):
        L.append(f"Fig. 11 ({FIG11_RULE}; in brackets, of the {len(ZONE_LEVELS) * len(ZONE_CUTOFFS)} zones with levels "
                 f"{', '.join(f'{x:g}' for x in ZONE_LEVELS)} and cutoffs {', '.join(f'{x:g}a' for x in ZONE_CUTOFFS)}, how many "
                 "give the same verdict): " + "; ".join(f"α = {a}: {fig11_verdict(a, s)}: {fig11_text(a, s)}" for a, s in S.items()) + ".")
    if all(R.values()):
        r01 = R["0.1"]
        L += [f"Fig. 9 (rule: for every α, dev's 99th percentile (by area) within 2a above tr's, and dev above 10 % of its own 99th "
              f"percentile over a smaller share of r < 2a than tr): {_v(fig9(R))}.",
              f"Fig. 12, α = 1 and 10 (rule: Δ‖σ‖ beneath the tip < 0): {_v(all(R[a]['dsig_beneath'] < 0 for a in ('1', '10')))}. "
              f"α = 0.1 (rule: the sides relax, Δ‖σ‖ beside < 0 < beneath): {_v(r01['dsig_sides'] < 0 < r01['dsig_beneath'])}: "
              f"ours is {r01['dsig_beneath']:+.3g} MPa beneath and {r01['dsig_sides']:+.3g} MPa beside."]
    if f13:
        L.append("Fig. 13 (rule: the sign of Δ‖σ‖ over the whole hold, its mean over the region beneath the tip, not one "
                 "cell; the paper's “point in contact with the tip” is not placed more closely; in brackets the largest "
                 "Δ‖σ‖ over the hold's outputs after its start, and their number): " + "; ".join(
                     f"α = {a}: {v['change_end']:+.3g} MPa ({v['change_max']:+.3g}, {v['outputs']} outputs), {_v(fig13(a, v))}"
                     for a, v in f13.items()) + ".")
    return L


def bedding(n, trends, images, rel, img):
    ind = n["indent"]
    L = ["## Bedding orientation (§4.2, Figs. 14–15)", "",
         "**Paper.** “anisotropy in the creep response does not strongly manifest itself during an indentation "
         "experiment” (§4.2, Fig. 14), in contrast with “strongly anisotropic creep behavior … from triaxial creep "
         "simulations on the same shale” (§4.2, §5); “the material flows from the stronger BP direction to the weaker "
         "BN direction” (Fig. 15).", "",
         "**Ours.** The thickness of the plane-strain model is not the paper's (it gives none): 1 µm as shipped, and as a "
         "sensitivity check 3 µm, about the Berkovich-equivalent thickness at 15 mN (equal mean pressure: t = 4.9 h_B, "
         "h_B ≈ 0.62 µm; the fine zone scaled with the indent, its cells 0.125 µm, the far field "
         "coarser, within 1 % at θ = 45 and 90 of fine meshes in the depth at the end of loading and the creep depth: "
         "tools/reproduce.py; one mesh each). At 1 µm every angle starts from one mesh (θ = 0 and 90, whose bedding keeps the mirror plane x = 0, on the "
         "half model, the others on the whole block meshed as that half and its mirror image) and reruns once on a mesh made "
         "from its own error indicator (docs/adapt.md), which states the creep depth's mesh error beside its time-step error "
         "(README, Which model each scene uses). The flow's direction: the "
         "principal axis of the hold's displacement increments within 2a of the tip (a = 5 µm; the vertices weighed by their areas since 2026-12-02, not by their count), as an angle from the "
         "downward load axis; the bedding normal's axis (BN) is at −θ on that convention, the planes' (BP) at 90° − θ.", "",
         "| θ | h at end of load [µm] | creep depth in 2000 s [µm] | flow axis [°] | at t = 3 µm: h at end of load, creep depth [µm] |",
         "|---|---|---|---|---|"]
    for t in THETAS_BEDDING:
        s, s3 = ind.get(f"bedding_theta{t}"), ind.get(f"bedding_theta{t}_t3")
        if s:
            f = s.get("flow") or {}
            L.append(f"| {t} | {_f(s['depth_end_of_load'], '.4g')} | {_f(s['creep_depth'], '.4g')}"
                     f"{stated_text(s, 'creep_mesh_error', 'creep_time_error')} | {_f(f.get('beta'), '+.1f')} | "
                     + (f"{_f(s3['depth_end_of_load'], '.4g')}, {_f(s3['creep_depth'], '.4g')}" if s3 else "—") + " |")
    f = (ind.get("bedding_theta45") or {}).get("flow")
    v15 = fig15(f) if f else None
    L += ["", f"**Verdicts.** Fig. 14: {_v(trends[1]['ok'])} ({trends[1]['detail']}){thickness_note(ind)}. Fig. 15 (rule: the "
          f"principal flow axis tilts by more than {TILT:g}° toward BN's side): "
          + ("no run" if not f else ("not distinguishable" if v15 is None else _v(v15)))
          + (f" (θ = 45: {f['beta']:+.1f}°, BN at {f['beta_bn']:+.0f}°)" if f else "") + ".", ""]
    for fid in ("fig14", "fig15"):
        L.append(img(images, fid, rel))
    return L
