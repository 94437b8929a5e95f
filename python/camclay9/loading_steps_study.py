"""The section "Indentation: the direct solver and the loading steps" of docs/performance.md, written from its results
store docs/results/loading_steps.json by bench/loading_steps_bench.py and checked against it by tools/doc_numbers.py.

Two changes to what an indentation run costs, each measured against the run before it and against a reference of
finer time steps on the same mesh:
- the direct contact solve of a 2D model on one rank by UMFPACK with METIS' ordering instead of MUMPS (whose Debian
  build orders by PORD only): the same systems solved, so the same answer to round-off;
- the loading stage's steps by the output measure relative to the stage (steps.error.relative_to: stage,
  docs/driver.md) instead of relative to each step, at the same tol.

Variants (VARIANTS): "before" (MUMPS, the loading relative to each step), "UMFPACK" (UMFPACK with METIS' ordering, the
default for 2D on one rank and forced in 3D, the old steps), "shipped" (the scene as shipped), "reference" (the scene as shipped at tol 5e-3 in every stage whose tol is
1.5e-2: the time-step reference; one run).

The store: {"provenance": {"command", "date", "rev", "machine"}, "rows": [...]}, each row {"scene", "variant",
"unknowns", "steps", "newton", "krylov", "factorisations", "umat_calls", "solve_s" (the driver's own wall time in the
linear solves, first repeat), "cpu_s" and "wall_s" (one per repeat: user + system of the driver and its gmsh, from
wait4; wall), "outputs" {name: value} (indent_convergence_bench's outputs: loads µN, depths µm; the first repeat's)}.
"""
from camclay9 import results_store

STORE = "loading_steps"
TITLE = "## Indentation: the direct solver and the loading steps"
VARIANTS = ("before", "UMFPACK", "shipped", "reference")
ROW_KEYS = ("scene", "variant", "unknowns", "steps", "newton", "krylov", "factorisations", "umat_calls", "solve_s",
            "cpu_s", "wall_s", "outputs")
OUTPUTS = ("load at end of loading", "depth at end of loading", "creep depth", "residual depth")


def checked(store):
    return results_store.variant_rows(STORE, store, ROW_KEYS, VARIANTS, ("provenance", "rows"))


cpu = results_store.median_cpu


def rows_of(store, scene):
    return {r["variant"]: r for r in checked(store) if r["scene"] == scene}


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv = store["provenance"]
    rows = checked(store)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    n = max((len(r["cpu_s"]) for r in rows if r["variant"] != "reference"), default=0)
    names = [o for o in OUTPUTS if any(o in r["outputs"] for r in rows)]
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}, {pv['machine']}; {n} runs of "
             "each variant, one of the reference; CPU: user + system of the driver and its gmsh, median and range). Each "
             "scene as shipped on its own mesh. *before*: MUMPS for the contact solve and the loading steps relative to "
             "each step; *UMFPACK*: UMFPACK with METIS' ordering (the driver's choice in 2D on one rank; in 3D asked for "
             "by option, the driver keeping MUMPS there), the loading steps still relative to each step; *shipped*: the "
             "scene as shipped (the driver's package, the loading steps relative to the stage); "
             "*reference*: the shipped scene at tol 5e-3 where it has 1.5e-2 (the time-step reference on the same mesh; "
             "its errors against the shipped run's are the time steps' alone). Errors against the reference.", "",
             "| scene | variant | steps | Newton its | Krylov its | UMAT calls | linear solves [s] | CPU [s] | "
             + " | ".join(names) + " |", "|---" * (8 + len(names)) + "|"]
    for s in scenes:
        by = rows_of(store, s)
        ref = by.get("reference")
        for v in VARIANTS:
            if v not in by:
                continue
            r = by[v]
            c, errs = results_store.variant_cells(r, None if v == "reference" else ref, names)
            lines.append(f"| {s} | {v} | {r['steps']} | {r['newton']} | {r['krylov']} | {r['umat_calls'] / 1e6:.1f} M | "
                         f"{r['solve_s']:.1f} | {c} | " + " | ".join(errs) + " |")
    lines.append("")
    for s in scenes:
        by = rows_of(store, s)
        if "before" in by and "shipped" in by:
            b, sh = by["before"], by["shipped"]
            lines.append(f"- **{s}**: {cpu(sh):.1f} s CPU against {cpu(b):.1f} s ({cpu(sh) / cpu(b):.2f}), "
                         f"{sh['steps']} steps against {b['steps']}; the outputs move by at most "
                         f"{max(abs(sh['outputs'][o] / b['outputs'][o] - 1) for o in names if o in b['outputs'] and b['outputs'][o]):.3%}.")
        if "UMFPACK" in by and "before" in by:
            b, u = by["before"], by["UMFPACK"]
            lines.append(f"  UMFPACK alone: linear solves {u['solve_s']:.1f} s against MUMPS' {b['solve_s']:.1f} s with the "
                         f"same step control ({u['solve_s'] / b['solve_s']:.2f}); CPU {cpu(u):.1f} s against {cpu(b):.1f} s.")
    return "\n".join(lines) + "\n"
