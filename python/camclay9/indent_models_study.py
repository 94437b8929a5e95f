"""The section "Indentation: 3D half model, sector and axisymmetric twin" of docs/performance.md (issue 12, item 3),
written from its results store docs/results/indent_models.json by bench/indent_models_bench.py and checked against
it by tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "rev" (the driver's commit), "repeats"}, "rows": [...]}, one row per
model in the bench's order, each {"model" (the bench's key: half, sector, hexhalf, mirrored, axi), "label", "P" (the
indenter's whole load at the end of loading [µN]), "creep" (the hold's change of depth [nm]), "h_res" (the residual
depth [nm]), "steps", "wall", "cpu" (medians of the repeats [s])}. Values at full digits; the reading is computed
from the rows.
"""
from camclay9 import results_store

STORE = "indent_models"
TITLE = "## Indentation: 3D half model, sector and axisymmetric twin"
KEYS = ("model", "label", "P", "creep", "h_res", "steps", "wall", "cpu")
OUT = ("P", "creep", "h_res")


def checked(store):
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "repeats"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
    return {r["model"]: r for r in store["rows"]}


def half_over_sector(store):
    """The half model's CPU over the sector's (the kerogen scene as shipped on each), or None without both rows."""
    cpu = {r["model"]: r["cpu"] for r in store.get("rows", [])}
    return cpu["half"] / cpu["sector"] if {"half", "sector"} <= cpu.keys() else None


def section(store, root=None):
    """The section's text: the command, one row per model against the half model, the reading computed from the rows.
    `root` is unused (the uniform call of tools/doc_numbers.py)."""
    rows, pv = checked(store), store["provenance"]
    ref = rows.get("half")
    rel = lambda r, k: "ref." if r is ref or not ref else f"{r[k] / ref[k] - 1:+.1%}"
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; medians of {pv['repeats']} runs "
             "each on a shared 2-core machine: read the CPU time). The nanoindentation on kerogen (Cam-Clay IX, φ = 0; load "
             "to 200 nm, hold 60 s, unload in 20 s) as shipped on each model, against the 3D half model; each model's error "
             "against the converged 3D answer is in \"3D indentation: mesh convergence and the cheapest model\". P is the "
             "indenter's whole load at h = 200 nm (the scenes' indenter.copies).", "",
             "| model | P [µN] | creep depth [nm] | residual depth [nm] | steps | wall / CPU [s] |", "|---|---|---|---|---|---|"]
    for r in rows.values():
        lines.append(f"| {r['label']} | {r['P']:.2f} ({rel(r, 'P')}) | {r['creep']:.2f} ({rel(r, 'creep')}) | "
                     f"{r['h_res']:.1f} ({rel(r, 'h_res')}) | {r['steps']} | {r['wall']:.0f} / {r['cpu']:.0f} |")
    lines.append("")
    s, m = rows.get("sector"), rows.get("mirrored")
    if s and m:
        d = {k: abs(s[k] / m[k] - 1) for k in OUT}
        lines.append(f"- **The sector is exact for this scene.** Against the half model made of three mirror images of its "
                     f"mesh (tip held on the axis) it differs by {d['P']:.0e} in P, {d['creep']:.0e} in the creep depth and "
                     f"{d['h_res']:.0e} in the residual depth, at {s['cpu'] / m['cpu']:.2f} of its CPU time.")
    own = [rows[k] for k in ("sector", "hexhalf") if k in rows]
    if ref and own:
        sp = {k: max(abs(r[k] / ref[k] - 1) for r in own) for k in OUT}
        lines.append(f"- **The 3D models' differences are their meshes'.** The cube (with its scene's element sizes), the "
                     f"hexagon's half and the sector (with the sector's) are meshed independently: against the cube P differs "
                     f"by up to {sp['P']:.1%}, the creep depth by {sp['creep']:.1%} and the residual depth by {sp['h_res']:.1%}.")
    if ref and "axi" in rows:
        lines.append("- **The axisymmetric twin** differs from the 3D models by the tip's shape (a cone of the Berkovich's "
                     "projected area) besides its mesh: README, \"Which model each scene uses\".")
    return "\n".join(lines) + "\n"
