"""The section "FE: triaxial cylinder" of docs/performance.md (issue #4), written from its results store
docs/results/fe_triaxial.json by bench/fe_triaxial.py and checked against it by tools/doc_numbers.py. README.md and
docs/paper.md quote the same store (camclay9.doc_quotes, camclay9.paper_doc).

The store: {"provenance": {"command", ...}, "rows": [...], "shipped": {"size", "tol"}}, each row {"size" [mm], "tol",
"ranks", "cells", "steps", "newton" (Newton iterations), "wall" [s] (median of the repeats), "assembly_ms" and
"rest_ms" (the element loop with its UMAT calls, and the rest of the wall time, per Newton iteration [ms]),
"err_1h", "err_10h" (the creep's relative error against the finest run at 1 h and 10 h)}.
"""

from camclay9 import results_store

STORE = "fe_triaxial"
TITLE = "## FE: triaxial cylinder"
KEYS = ("size", "tol", "ranks", "cells", "steps", "newton", "wall", "assembly_ms", "rest_ms", "err_1h", "err_10h")


def finest(rows):
    """The row the errors are against: the smallest element size, then the tightest tolerance."""
    return min(rows, key=lambda r: (r["size"], r["tol"]))


def section(store, root=None):
    """The section's text: the command, what was run and how the errors are measured, then one table row per run of
    the store. `root` is unused (no hand-written reading); it is there for tools/doc_numbers.py's uniform call."""
    rows = store["rows"]
    for i, r in enumerate(rows):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
    ref = finest(rows)
    lines = [TITLE, "",
             f"Command: `{store['provenance']['command']}` (medians of the repeats). The scene",
             "`input/triaxial.yaml` (hold to steady state, then 10 h of creep) at three element sizes and two step",
             "tolerances (PROPS 20), P1 tetrahedra, direct solver (MUMPS on 2 ranks). Wall time includes meshing",
             "and MPI start-up; the assembly time is the element loop with its UMAT calls (rank 0's clock);",
             f"the rest is mostly the LU factorisations. Errors: relative to the finest run (size {ref['size']:g}, tol "
             f"{ref['tol']:.0e}); between".replace("e-0", "e-"),
             "meshes they include a different draw of the phi field (phi is drawn per element), so they do not fall",
             "monotonically with the element size; between tolerances on one mesh they are the time-stepping error.", "",
             "| element size [mm] | tol | ranks | cells | steps | Newton its | wall [s] | assembly per Newton it. [ms] | "
             "rest per Newton it. [ms] | creep error 1 h | creep error 10 h |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['size']:g} | {r['tol']:g} | {r['ranks']} | {r['cells']} | {r['steps']} | {r['newton']} | "
                     f"{r['wall']:.1f} | {r['assembly_ms']:.2f} | {r['rest_ms']:.2f} | {r['err_1h']:.1e} | {r['err_10h']:.1e} |")
    return "\n".join(lines) + "\n"
