"""The section "2D indentation: the half model" of docs/performance.md (issue 32), written from its results store
docs/results/half_model.json by bench/half_model_bench.py and checked against it by tools/doc_numbers.py.

The loading-rate scenes are mirror-symmetric about the indenter's axis (the wedge, the load, the isotropic soft frame),
so they ship as half models (x >= 0, the mirror plane x = 0, indenter.copies 2). The bench runs each scene as shipped
and on the whole block it is half of (camclay9.indent2d_study.whole_block), on the same mesh parameters, and compares
both with the scene's converged 2D answer (the 2D mesh and element study's, camclay9.indent2d_study.reference).

The store: {"provenance": {"command", "date", "rev", "machine"}, "reference": {scene: {"h_max", "creep" (µm),
"hw_h_max", "hw_creep" (the answer's own relative half-widths), "from"}}, "rows": [...]}, each row {"scene", "model"
("half" or "whole"), "unknowns", "steps", "umat_calls", "cpu_s" and "wall_s" (one per repeat: user + system of the
driver and its gmsh, from wait4; wall), "h_max" (the depth at the end of loading), "creep" (the hold's depth change),
µm, the first repeat's (the repeats give the same answer)}.
"""
import statistics

from camclay9 import results_store

STORE = "half_model"
TITLE = "## 2D indentation: the half model"
ROW_KEYS = ("scene", "model", "unknowns", "steps", "umat_calls", "cpu_s", "wall_s", "h_max", "creep")


def checked(store):
    results_store.require(STORE, "the store", store, ("provenance", "reference", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, ROW_KEYS)
        if r["scene"] not in store["reference"]:
            raise ValueError(f"docs/results/{STORE}.json: rows[{i}]: scene {r['scene']} has no reference")
    return store["rows"]


def error(row, ref, k):
    return row[k] / ref[k] - 1


def pairs(store):
    """[(half row, whole row)] per scene, in the store's order."""
    rows = checked(store)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    by = {(r["scene"], r["model"]): r for r in rows}
    return [(by[(s, "half")], by[(s, "whole")]) for s in scenes if (s, "half") in by and (s, "whole") in by]


def cpu(row):
    """A row's median CPU over its repeats [s]."""
    return statistics.median(row["cpu_s"])


def speedup(half, whole):
    """The whole block's median CPU over the half model's."""
    return cpu(whole) / cpu(half)


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv, ref = store["provenance"], store["reference"]
    rows = checked(store)
    n = len(rows[0]["cpu_s"]) if rows else 0
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}, {pv['machine']}; {n} runs of "
             "each model, CPU: user + system of the driver and its gmsh, median and range). Each loading-rate scene as "
             "shipped, the half x ≥ 0 of the block with the mirror plane x = 0 (`boundary.mirror`) and `indenter.copies: 2` "
             "(its loads are the whole wedge's), and on the whole block it is half of, on the same mesh parameters. "
             "Errors against the scene's converged 2D answer (\"2D indentation: mesh and element study\"; its own "
             "uncertainty in brackets).", "",
             "| scene | model | unknowns | steps | UMAT calls | CPU [s] | depth at the end of loading [nm] | creep depth [nm] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        R = ref[r["scene"]]
        c = r["cpu_s"]
        lines.append(f"| {r['scene']} | {r['model']} | {r['unknowns']} | {r['steps']} | {r['umat_calls'] / 1e6:.1f} M | "
                     f"{cpu(r):.1f} ({min(c):.1f}–{max(c):.1f}) | {r['h_max'] * 1e3:.2f} ({error(r, R, 'h_max'):+.2%}) | "
                     f"{r['creep'] * 1e3:.3f} ({error(r, R, 'creep'):+.2%}) |")
    for s, R in ref.items():
        lines.append(f"| {s} | converged 2D answer | | | | | {R['h_max'] * 1e3:.2f} (± {R['hw_h_max']:.2%}) | "
                     f"{R['creep'] * 1e3:.3f} (± {R['hw_creep']:.2%}) |")
    for half, whole in pairs(store):
        lines += ["", f"- **{half['scene']}**: the half model takes {speedup(half, whole):.2f} times less CPU than the whole "
                  f"block ({half['unknowns'] / whole['unknowns']:.2f} of its unknowns, {half['umat_calls'] / whole['umat_calls']:.2f} "
                  f"of its UMAT calls); the two differ by {half['h_max'] / whole['h_max'] - 1:+.2%} in the depth at the end "
                  f"of loading and {half['creep'] / whole['creep'] - 1:+.2%} in the creep depth: two meshes of one density, "
                  "whose answers scatter so (the 2D study's rungs near h_tip 0.02 µm and its shipped rung against the shipped "
                  "scene show the same between meshes of one density)."]
    return "\n".join(lines) + "\n"
