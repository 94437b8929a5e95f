"""The section "Contact solve: direct against field split" of docs/performance.md (issue 33, docs/contact.md), written
from its results store docs/results/contact_solver.json by bench/contact_solver_bench.py and checked against it by
tools/doc_numbers.py.

The store: {"provenance": {"command", "date", ...}, "rows": [...]}, each row {"case", "solver", "unknowns", "steps",
"newton", "krylov", "cpu" [s], "mem" [MB], "repeats"} as the bench measured it (CPU the median of the repeats, memory
the largest); a case may lack a direct row (beyond its memory: no ratios). "provenance" may hold "merged"
{"command", "date", "cases"}: those cases rerun by the bench's --merge. A row may also hold "cpu_ratio" and
"mem_ratio", its CPU and memory over the direct path's on the same case as a table printed them from the run's full
digits, where the store keeps only the table's digits of CPU and memory (rows taken over from an earlier table; the
provenance says so); else the ratios are computed.
"""

STORE = "contact_solver"
TITLE = "## Contact solve: direct against field split"


def ratios(row, direct):
    """The row's CPU and peak memory over the direct path's on the same case."""
    return (row.get("cpu_ratio", row["cpu"] / direct["cpu"]), row.get("mem_ratio", row["mem"] / direct["mem"]))


def section(store, root=None):
    """The section's text: the command and its date, then one table row per (case, solver) of the store. `root` is
    unused (the section has no hand-written reading: docs/contact.md reads it, its numbers quoted by
    camclay9.doc_quotes); it is there for tools/doc_numbers.py's uniform call."""
    pv, rows = store["provenance"], store["rows"]
    once = list(dict.fromkeys(r["case"] for r in rows if r["repeats"] == 1))   # the bench's ONCE cases
    fewer = f" (one run for {', '.join(once)})" if once and max(r["repeats"] for r in rows) > 1 else ""
    merged = pv.get("merged")
    also = (f" Cases {', '.join(merged['cases'])}: `{merged['command']}` ({merged['date']})." if merged else "")
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}; a shared 2-core machine, one rank).{also} The first steps of the "
             "kerogen nanoindentation on each path (the bench's docstring gives the cases): CPU is user + system of the driver, "
             f"median of the repeats{fewer}; memory the driver's peak resident set. 'fieldsplit, before': the field split "
             "as it was before its GAMG hierarchy was kept (set up at every Newton iteration, the full Schur factorisation). "
             "A case without a direct row is beyond the direct path's memory.", "",
             "| case | unknowns | steps | solver | Newton its | Krylov its | CPU [s] | CPU / direct | peak memory [MB] | memory / direct |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    direct = {r["case"]: r for r in rows if r["solver"] == "direct"}
    for r in rows:
        cpu_ratio, mem_ratio = ((f"{x:.2f}" for x in ratios(r, direct[r["case"]])) if r["case"] in direct else ("—", "—"))
        lines.append(f"| {r['case']} | {r['unknowns']} | {r['steps']} | {r['solver']} | {r['newton']} | {r['krylov']} | "
                     f"{r['cpu']:.2f} | {cpu_ratio} | {r['mem']:.0f} | {mem_ratio} |")
    return "\n".join(lines) + "\n"
