"""The section "Time-step error: the floor" of docs/performance.md, written from its results store
docs/results/error_floor.json by bench/error_floor_bench.py and checked against it by tools/doc_numbers.py.

What the output measure's floor (steps.error.floor, docs/driver.md "Error measures") does to a shipped indentation
scene: the scene as shipped (no floor), with the floor in every stage the output measure controls, and a reference of
finer time steps on the same mesh (tol 5e-3 where the scene has 1.5e-2, no floor).

The store: {"provenance": {"command", "date", "rev", "machine"}, "floor": f, "rows": [...]}, each row {"scene",
"variant" (VARIANTS), "steps", "newton", "rejected", "stalled", "umat_calls", "cpu_s" and "wall_s" (one per repeat),
"outputs" {name: value} (loads µN, depths µm; the first repeat's)}.
"""
from camclay9 import results_store

STORE = "error_floor"
TITLE = "## Time-step error: the floor"
VARIANTS = ("shipped", "floor", "reference")
ROW_KEYS = ("scene", "variant", "steps", "newton", "rejected", "stalled", "umat_calls", "cpu_s", "wall_s", "outputs")
OUTPUTS = ("depth at end of loading", "creep depth", "residual depth")


def checked(store):
    return results_store.variant_rows(STORE, store, ROW_KEYS, VARIANTS, ("provenance", "floor", "rows"))


cpu = results_store.median_cpu


def rows_of(store, scene):
    return {r["variant"]: r for r in checked(store) if r["scene"] == scene}


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv, f = store["provenance"], store["floor"]
    rows = checked(store)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    n = max((len(r["cpu_s"]) for r in rows if r["variant"] != "reference"), default=0)
    names = [o for o in OUTPUTS if any(o in r["outputs"] for r in rows)]
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}, {pv['machine']}; {n} runs of "
             "each variant, one of the reference; CPU: user + system of the driver and its gmsh, median and range). "
             f"*shipped*: the scene as shipped (no floor); *floor*: the same with `floor: {f:g}` in every stage the output "
             "measure controls; *reference*: the shipped scene at tol 5e-3 where it has 1.5e-2 (the time-step reference on "
             "the same mesh). Errors against the reference; stalled: steps redone because Newton stalled.", "",
             "| scene | variant | steps | rejected | stalled | Newton its | UMAT calls | CPU [s] | " + " | ".join(names) + " |",
             "|---" * (8 + len(names)) + "|"]
    for s in scenes:
        by = rows_of(store, s)
        ref = by.get("reference")
        for v in VARIANTS:
            if v not in by:
                continue
            r = by[v]
            c, errs = results_store.variant_cells(r, None if v == "reference" else ref, names, "+.3%")
            lines.append(f"| {s} | {v} | {r['steps']} | {r['rejected']} | {r['stalled']} | {r['newton']} | "
                         f"{r['umat_calls'] / 1e6:.1f} M | {c} | " + " | ".join(errs) + " |")
    lines.append("")
    for s in scenes:
        by = rows_of(store, s)
        if "shipped" in by and "floor" in by:
            a, b = by["shipped"], by["floor"]
            lines.append(f"- **{s}**: with the floor {b['steps']} steps against {a['steps']} "
                         f"({b['steps'] / a['steps'] - 1:+.0%}), {b['umat_calls'] / a['umat_calls'] - 1:+.1%} UMAT calls, "
                         f"CPU {cpu(b):.1f} s against {cpu(a):.1f} s ({cpu(b) / cpu(a):.2f}).")
    return "\n".join(lines) + "\n"
