"""The section "3D indentation on 1 and 2 ranks" of docs/performance.md (issue 25, item 6), written from its results
store docs/results/indent_ranks.json by bench/indent_ranks.py and checked against it by tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "rev" (the driver's commit), "machine", "note" (optional: what was not
run by the command)}, "rows": [...]}, each row {"scene", "ranks", "wall_s" (the run's wall time [s]), "cpu_s" (user
+ system of mpiexec and the driver's ranks [s]), "h_res" (the depth at the run's end, the residual depth [µm]; not
in rows taken over from a table)}, the scenes in the bench's order, each on 1 rank then on 2; a 2-rank row also
{"h_res_vs_1": its residual depth relative to the 1-rank run's, minus 1}. Values at full digits. The section's
hand-written reading takes its ranges from these rows.
"""

from camclay9 import results_store

STORE = "indent_ranks"
TITLE = "## 3D indentation on 1 and 2 ranks"
KEYS = ("scene", "ranks", "wall_s", "cpu_s")
MINUS = "\u2212"


def checked(store):
    """The store's rows, each scene on 1 then 2 ranks; a clear message naming what is missing otherwise."""
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    rows = store["rows"]
    for i, r in enumerate(rows):
        results_store.require(STORE, f"rows[{i}]", r, KEYS + (("h_res_vs_1",) if r.get("ranks") == 2 else ()))
    if [r["ranks"] for r in rows] != [1, 2] * (len(rows) // 2) or not rows:
        raise ValueError(f"docs/results/{STORE}.json: rows' ranks are {[r['ranks'] for r in rows]} (expected each scene "
                         "on 1 then on 2)")
    return rows


def sci(x):
    """A small signed number as the table gives it: −9.2e-8, +9.0e-11."""
    m, e = f"{x:+.1e}".split("e")
    return f"{m}e{int(e)}".replace("-", MINUS, 1) if x < 0 else f"{m}e{int(e)}"


def pairs(rows):
    """[(1-rank row, 2-rank row)] per scene."""
    return list(zip(rows[0::2], rows[1::2]))


def speedups(rows):
    """(wall on 1 rank / wall on 2, CPU on 2 / CPU on 1) per scene: the reading's ranges."""
    return [(one["wall_s"] / two["wall_s"], two["cpu_s"] / one["cpu_s"]) for one, two in pairs(rows)]


def section(store, root=None):
    """The section's text: the command and machine, one row per run, the reading with its ranges from the rows.
    `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    rows, pv = checked(store), store["provenance"]
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}, {pv['machine']}; one run "
             "each).", "", "| scene | ranks | wall [s] | CPU [s] | residual depth, 2 ranks against 1 |", "|---|---|---|---|---|"]
    for one, two in pairs(rows):
        lines.append(f"| {one['scene']} | 1 | {one['wall_s']:.1f} | {one['cpu_s']:.1f} | |")
        lines.append(f"| {two['scene']} | 2 | {two['wall_s']:.1f} | {two['cpu_s']:.1f} | "
                     f"{sci(two['h_res_vs_1'])} |")
    walls, cpus = zip(*speedups(rows))
    lines += ["", pv["note"]] if pv.get("note") else []
    lines += ["", f"Two ranks give one scene {min(walls):.1f}–{max(walls):.1f}× in wall time for {min(cpus):.1f}–"
              f"{max(cpus):.1f}× the CPU (the kept factorisation and its triangular",
              "solves scale poorly at these sizes). `tools/reproduce.sh` runs two scenes at once on the two cores, so "
              "it keeps the", "3D scenes on one rank each: there a second rank only takes a core from the other job."]
    return "\n".join(lines) + "\n"
