"""The section "Figs. 9 and 11: percentiles by area, not by cell count" of docs/performance.md, written from its results
store docs/results/paper_measures.json by bench/paper_measures_bench.py and checked against it by tools/doc_numbers.py.

Figs. 9 and 11 of docs/paper.md are judged on thresholds taken from a field's 99th percentile near the tip (and Fig.
11's half-disc from the zone's 95th-percentile radius; camclay9.paper_fields). Taken over the cells by their count, a
percentile weighs a small cell as much as a large one, so it moves with the mesh: on a mesh adapted to the answer, whose
cells crowd near the tip, the threshold rises and the zone shrinks. Taken by area it is a property of the field. The
bench measures both on the loading-rate scenes as docs/paper.md runs them (their adapted meshes) and on the uniform fine
zone they shipped before, the same scene variants otherwise.

The store: {"provenance": {"command", "date", "rev", "machine"}, "rows": [...]}, each row {"alpha" ("0.1", "1", "10"),
"mesh" (MESHES), "weight" (WEIGHTS), "unknowns", "fig9" {"dev_p99", "tr_p99", "dev_frac", "tr_frac", "verdict"},
"fig11" {"100", "500", "2000": {"surface", "middle", "beneath", "fill", "verdict"}}}; verdict true where the paper's
claim holds by docs/paper.md's rule (camclay9.paper_doc_2d).
"""
from camclay9 import results_store
from camclay9.paper_doc_2d import TIMES11 as TIMES

STORE = "paper_measures"
TITLE = "## Figs. 9 and 11: percentiles by area, not by cell count"
MESHES = ("uniform", "adapted")
WEIGHTS = ("count", "area")
ROW_KEYS = ("alpha", "mesh", "weight", "unknowns", "fig9", "fig11")


def checked(store):
    """The store's rows, its keys checked (a ValueError naming the file and what is wrong)."""
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, ROW_KEYS)
        if r["mesh"] not in MESHES or r["weight"] not in WEIGHTS:
            raise ValueError(f"docs/results/{STORE}.json: rows[{i}]: mesh '{r['mesh']}', weight '{r['weight']}': "
                             f"expected one of {MESHES} and of {WEIGHTS}")
    return store["rows"]


def row(store, alpha, mesh, weight):
    """The row of (alpha, mesh, weight); None if it was not measured."""
    return next((r for r in checked(store) if (r["alpha"], r["mesh"], r["weight"]) == (alpha, mesh, weight)), None)


def _v(ok):
    return "agrees" if ok else "differs"


def _fig11(z):
    return " / ".join(f"{z[t]['surface']:.2f}, {z[t]['middle']:.2f}, {z[t]['beneath']:.2f}; {z[t]['fill']:.2f} "
                      f"({_v(z[t]['verdict'])})" for t in TIMES)


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv = store["provenance"]
    rows = sorted(checked(store), key=lambda r: (float(r["alpha"]), MESHES.index(r["mesh"]), WEIGHTS.index(r["weight"])))
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; {pv['machine']}). Figs. 9 and 11 of "
             "docs/paper.md as numbers, each loading-rate scene as docs/paper.md runs it (*adapted*: its meshes made by "
             "rerun, the reproduction's own run) and on the uniform fine zone it shipped before (*uniform*: h_tip 0.0141 µm "
             "within 0.9 µm, h_far 0.106 µm; the same variant otherwise), with the percentiles taken over the cells by "
             "their count (*count*, docs/paper.md before 2026-12-02) and by their area (*area*, since). Fig. 9: "
             "‖dev εvp‖ / |tr εvp| of the 99th percentiles within 2a, and the share of the half-disc r < 2a above 10 % "
             "of each one's own, dev / tr (the claim: dev the more intense and more concentrated). Fig. 11, at 100 / "
             "500 / 2000 s into the hold: the zone's shares beside the indent, between and beneath it, and its fill of "
             "its half-disc; the verdicts by docs/paper.md's rules.", "",
             "| α | mesh | unknowns | percentile by | Fig. 9: dev/tr; shares | Fig. 11: beside, between, beneath; fill |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        f9 = r["fig9"]
        lines.append(f"| {r['alpha']} | {r['mesh']} | {r['unknowns']} | {r['weight']} | {f9['dev_p99'] / f9['tr_p99']:.0f}×; "
                     f"{f9['dev_frac']:.2f} / {f9['tr_frac']:.2f} ({_v(f9['verdict'])}) | {_fig11(r['fig11'])} |")
    lines.append("")
    for alpha in sorted({r["alpha"] for r in rows}, key=float):
        u, a = row(store, alpha, "uniform", "area"), row(store, alpha, "adapted", "area")
        uc, ac = row(store, alpha, "uniform", "count"), row(store, alpha, "adapted", "count")
        if u and a and uc and ac:
            d = max(abs(u["fig11"][t][k] - a["fig11"][t][k]) for t in TIMES for k in ("surface", "middle", "beneath", "fill"))
            dc = max(abs(uc["fig11"][t][k] - ac["fig11"][t][k]) for t in TIMES for k in ("surface", "middle", "beneath", "fill"))
            lines.append(f"- **α = {alpha}**: Fig. 11's shares and fill on the two meshes differ by at most {d:.2f} by area, "
                         f"{dc:.2f} by count; Fig. 11's verdicts by area {', '.join(_v(u['fig11'][t]['verdict']) for t in TIMES)} "
                         f"(uniform) and {', '.join(_v(a['fig11'][t]['verdict']) for t in TIMES)} (adapted), by count "
                         f"{', '.join(_v(uc['fig11'][t]['verdict']) for t in TIMES)} (uniform).")
    return "\n".join(lines) + "\n"
