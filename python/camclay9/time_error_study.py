"""The section "Stated time-step error" of docs/performance.md (docs/adapt.md, "The time-step error"), written from its
results store docs/results/time_error.json by bench/time_error_bench.py and checked against it by tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "machine", ...}, "cases": {case: {"stage", "quantity", "reference",
"uncertainty", "rows": [...]}}} in the bench's order of cases, the rows in its order of controls (the shipped one
first); each row {"control" (the value as the scene's text has it), "steps", "cpu_s" [s], "value" (the stage's change
of the quantity), "stated" (its stated time-step error), "true" (value - reference), "effectivity" (stated / |true|,
null where it is not measured)}. The reference is the finest two controls' values extrapolated to zero (first order),
its uncertainty the finest run's distance from it.
"""

from camclay9 import results_store

STORE = "time_error"
TITLE = "## Stated time-step error"
CASE_KEYS = ("stage", "quantity", "reference", "uncertainty", "rows")
ROW_KEYS = ("control", "steps", "cpu_s", "value", "stated", "true", "effectivity")


def checked(store):
    """The store's cases, each with the keys the table needs; a clear message naming the missing ones otherwise."""
    cases = store.get("cases")
    if not isinstance(cases, dict) or not cases:
        raise ValueError(f"docs/results/{STORE}.json: 'cases' is {cases!r} (expected {{case: {{{', '.join(CASE_KEYS)}}}}})")
    for case, r in cases.items():
        results_store.require(STORE, f"cases.{case}", r, CASE_KEYS)
        for i, row in enumerate(r["rows"]):
            results_store.require(STORE, f"cases.{case}.rows[{i}]", row, ROW_KEYS)
    return cases


def table_rows(case, r):
    """The table's lines for one case: its controls, then its reference."""
    ref = abs(r["reference"])
    lines = []
    for row in r["rows"]:
        eff = "—" if row["effectivity"] is None else f"{row['effectivity']:.2f}"
        lines.append(f"| {case} | {r['quantity']} over '{r['stage']}' | {row['control']} | {row['steps']} | {row['cpu_s']:.1f} | "
                     f"{row['value']:.6g} | {100 * row['true'] / ref:+.3f} % | {100 * row['stated'] / ref:.3f} % | {eff} |")
    lines.append(f"| {case} | reference | | | | {r['reference']:.6g} | ± {100 * r['uncertainty'] / ref:.3f} % | | |")
    return lines


def section(store, root=None):
    """The section's text: the command, its date and machine, how the true error is found, then the table. `root` is
    unused (the section has no hand-written reading: docs/adapt.md reads it); it is there for tools/doc_numbers.py's
    uniform call."""
    pv, cases = store["provenance"], checked(store)
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}; {pv['machine']}; cases and references in its docstring). "
             "Each held stage's change is "
             "stated with the sum of its steps' local error estimates (docs/adapt.md, \"The time-step error\"); here "
             "against its true error, from the finest two controls extrapolated (first order). Effectivity = stated / true. "
             "kerogen_sector_load varies the load stage's control alone (the hold's stays 0.015): its true error is the "
             "share of the load stage's steps, which the stated error, the hold's own, does not hold (no effectivity).",
             "", "| case | change of | control | steps | CPU [s] | value | true error | stated | effectivity |",
             "|---|---|---|---|---|---|---|---|---|"]
    for case, r in cases.items():
        lines += table_rows(case, r)
    return "\n".join(lines) + "\n"
