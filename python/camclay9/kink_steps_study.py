"""The section "Time steps across contact kinks" of docs/performance.md, written from its results store
docs/results/kink_steps.json by bench/kink_steps_bench.py and checked against it by tools/doc_numbers.py.

What the step control does where nodes enter contact at nearly every loading step (docs/driver.md, "Stages, steps
and error control": a step across a kink is not rejected on its estimate, and its estimate sets the next step shortened
by at most half). The kerogen sector (nanoindent_kerogen_sector.yaml) on the meshes of its own adaptation
(-adapt_levels 2: level 0 is the shipped mesh), each run on the same mesh file by the driver of this tree ("after")
and by an earlier driver whose kink steps could hold the next step but never shorten it ("before").

The store: {"provenance": {"command", "date", "rev", "machine"}, "before_rev", "reference" {"P", "creep", "h_res",
"from"} (µN, nm, nm), "rows": [...]}, each row {"driver" (DRIVERS), "level", "unknowns", "steps", "load_steps",
"load_kinks" (loading steps across which a node entered or left contact), "load_dt_median" [s], "umat_calls",
"cpu_s", "outputs" {"P", "creep", "h_res"} (µN, nm, nm)}.
"""
from camclay9 import results_store

STORE = "kink_steps"
TITLE = "## Time steps across contact kinks"
DRIVERS = ("before", "after")
ROW_KEYS = ("driver", "level", "unknowns", "steps", "load_steps", "load_kinks", "load_dt_median", "umat_calls", "cpu_s",
            "outputs")
OUTPUTS = (("P", "load at 200 nm [µN]"), ("creep", "creep depth [nm]"), ("h_res", "residual depth [nm]"))


def checked(store):
    """The store's rows, its keys checked (a ValueError naming the file and what is wrong)."""
    results_store.require(STORE, "the store", store, ("provenance", "before_rev", "reference", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, ROW_KEYS)
        if r["driver"] not in DRIVERS:
            raise ValueError(f"docs/results/{STORE}.json: rows[{i}].driver '{r['driver']}', expected one of {DRIVERS}")
    return store["rows"]


def row(store, driver, level):
    """The row of (driver, level); None if it did not run."""
    return next((r for r in checked(store) if (r["driver"], r["level"]) == (driver, level)), None)


def error(store, r, name):
    """A row's output `name` relative to the store's reference."""
    return r["outputs"][name] / store["reference"][name] - 1


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv, ref = store["provenance"], store["reference"]
    rows = sorted(checked(store), key=lambda r: (r["level"], DRIVERS.index(r["driver"])))
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; *before*: the driver at "
             f"{store['before_rev']}; {pv['machine']}; CPU: user + system of the driver). The kerogen sector "
             "(nanoindent_kerogen_sector.yaml) on the meshes of its own adaptation (`-adapt_levels 2`; level 0 is the "
             "shipped mesh), each mesh run by both drivers from the same mesh file. *before*: a step across which a node "
             "entered or left contact (a kink) could hold the next step at its length but never shorten it; *after*: its "
             "estimate sets the next step, shortened by at most half (docs/driver.md, \"Stages, steps and error "
             f"control\"). Errors against {ref['from']}. Loading steps: those of the load stage; across a kink: those "
             "across which a node entered or left contact.", "",
             "| level | unknowns | driver | steps | loading steps | across a kink | median loading step [s] | UMAT calls | "
             "CPU [s] | " + " | ".join(h for _, h in OUTPUTS) + " |",
             "|---" * (9 + len(OUTPUTS)) + "|"]
    for r in rows:
        cells = [f"{r['outputs'][n]:.5g} ({error(store, r, n):+.2%})" for n, _ in OUTPUTS]
        lines.append(f"| {r['level']} | {r['unknowns']} | {r['driver']} | {r['steps']} | {r['load_steps']} | "
                     f"{r['load_kinks']} | {r['load_dt_median']:.3g} | {r['umat_calls'] / 1e6:.1f} M | {r['cpu_s']:.0f} | "
                     + " | ".join(cells) + " |")
    lines.append("")
    for lv in sorted({r["level"] for r in rows}):
        a, b = row(store, "before", lv), row(store, "after", lv)
        if a and b:
            lines.append(f"- **Level {lv}** ({b['unknowns']} unknowns): {a['load_kinks']} of {a['load_steps']} loading "
                         f"steps across a kink before, {b['load_kinks']} of {b['load_steps']} after; steps {a['steps']} "
                         f"before, {b['steps']} after; creep depth {error(store, a, 'creep'):+.2%} before, "
                         f"{error(store, b, 'creep'):+.2%} after; CPU {a['cpu_s']:.0f} s before, {b['cpu_s']:.0f} s after.")
    return "\n".join(lines) + "\n"
