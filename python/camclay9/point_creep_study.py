"""The section "Material point: triaxial creep, accuracy against cost" of docs/performance.md (issue #3), written from
its results store docs/results/point_creep.json by bench/point_creep_accuracy.py and checked against it by
tools/doc_numbers.py. The bench draws the section's plot (docs/point_creep_accuracy.png) from the same store.

The store: {"provenance": {"command", "date", "machine"}, "shipped_tol" (the scene's PROPS(20)), "rows": [...]}, each
row {"tol" (PROPS(20) of the run), "steps", "cutbacks", "wall_s" (median over the repeats of the driver's own timing
of the run [s]), "walls_s" (each repeat's), "err_1h", "err_10h" (the creep strain's relative error against the Radau
integration at 1 h and 10 h)}.
"""

from camclay9 import results_store

STORE = "point_creep"
TITLE = "## Material point: triaxial creep, accuracy against cost"
KEYS = ("tol", "steps", "cutbacks", "wall_s", "err_1h", "err_10h")


def short(x):
    """A tolerance as the text gives it: 2e-7, not 2e-07."""
    return f"{x:.0e}".replace("e-0", "e-")


def section(store, root=None):
    """The section's text: the command, what was run and measured, one table row per tolerance, the plot. `root` is
    unused (no hand-written reading); it is there for tools/doc_numbers.py's uniform call."""
    pv, rows = store["provenance"], store["rows"]
    for i, r in enumerate(rows):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}; {pv['machine']}). The shipped scene",
             "`input/point/triaxial_creep_theta0.yaml` (hold at -35 MPa to a viscoplastic rate of 1e-13 /s, then",
             "sigma_d = 40 MPa for 10 h, adaptive steps driven by the UMAT's PNEWDT) with the step tolerance",
             "PROPS(20) over four decades. Wall time: median over the repeats of the driver's own timing of",
             "the run (no process start-up). Error: relative error of the creep strain against an independent",
             f"Radau integration (rtol 1e-10) with the same hold. The shipped default is tol = {short(store['shipped_tol'])}.", "",
             "| tol (PROPS 20) | steps | cutbacks | median wall [ms] | error at 1 h | error at 10 h |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {r['tol']:.0e} | {r['steps']} | {r['cutbacks']} | {r['wall_s'] * 1e3:.2f} | {r['err_1h']:.2e} | "
              f"{r['err_10h']:.2e} |" for r in rows]
    lines += ["", "![accuracy against cost](point_creep_accuracy.png)"]
    return "\n".join(lines) + "\n"
