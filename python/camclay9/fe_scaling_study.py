"""The section "FE scaling: 1 and 2 ranks, direct and GAMG" of docs/performance.md (issue 13, item 4), written from its
results store docs/results/fe_scaling.json by `bench/scaling_bench.py` and checked against it by tools/doc_numbers.py.

The store: {"provenance": {"runs": [{"command", "date", "rev" (the driver's commit), "load" (the 1-minute load average at
the start and the end), "max_steps"}, ...]}, "rows": [...]}, one row per (mesh, ranks, solver), each {"run" (its index in
runs), "cells", "unknowns", "ranks", "solver" (asked for: direct or GAMG), "driver_solver" (the solver the
driver's log names), "steps", "newton", "cutbacks", "krylov", "setups", "solve_wall" (the
stepping's wall clock [s]), "cpu" (the slowest rank's CPU [s]), "rss" (the largest rank's peak resident set [MB]),
"rss_all" (summed over the ranks), "ev" (-log_view's times [s], the largest over the ranks: residual, jacobian, pcsetup,
ksp), "diff" (the axial strain history's largest difference from the 1-rank run on the same mesh, relative to the creep),
"tmesh" (gmsh's seconds), "partition" (2 ranks: type, vertices, copies; else null)}. Values at full digits; the
reading is computed from the rows.
"""
from camclay9 import results_store

STORE = "fe_scaling"
TITLE = "## FE scaling: 1 and 2 ranks, direct and GAMG"
KEYS = ("run", "cells", "unknowns", "ranks", "solver", "driver_solver", "steps", "newton", "cutbacks", "krylov", "setups",
        "solve_wall", "cpu", "rss", "rss_all", "ev", "diff", "tmesh", "partition")
DIRECT, GAMG = "direct", "GAMG"


def merged(old, new, run):
    """The store `old` with the rows `new` of one bench run (described by `run`) in place of its rows of the same mesh,
    ranks and solver; rows ordered by mesh, ranks and solver."""
    runs = list(old.get("provenance", {}).get("runs", [])) + [run]
    key = lambda r: (r["unknowns"], r["ranks"], r["solver"])  # noqa: E731
    fresh = {key(r) for r in new}
    rows = [r for r in old.get("rows", []) if key(r) not in fresh] + [dict(r, run=len(runs) - 1) for r in new]
    used = sorted({r["run"] for r in rows})  # drop the runs no row comes from any more
    rows = [dict(r, run=used.index(r["run"])) for r in rows]
    order = {DIRECT: 0, GAMG: 1}
    rows.sort(key=lambda r: (r["unknowns"], r["ranks"], order.get(r["solver"], 2)))
    return {"provenance": {"runs": [runs[i] for i in used]}, "rows": rows}


def checked(store):
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    for i, run in enumerate(store["provenance"]["runs"]):
        results_store.require(STORE, f"provenance.runs[{i}]", run, ("command", "date", "rev", "load", "max_steps"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
        results_store.require(STORE, f"rows[{i}].ev", r["ev"], ("residual", "jacobian", "pcsetup", "ksp"))
    return store["rows"]


def kb(r):
    """The resident set summed over the ranks per unknown [kB]."""
    return 1024 * r["rss_all"] / r["unknowns"]


def table(store):
    lines = ["| cells | unknowns | ranks | solver | partition: shared vertices | Newton its | Krylov its | set-ups | wall [s] | "
             "CPU [s] (slowest rank) | residual+UMAT per Newton it. [ms] | Jacobian | PC set-up | Krylov solve | "
             "max RSS per rank [MB] | RSS all ranks [MB] | kB per unknown (all ranks) | axial strain vs 1-rank run |",
             "|" + "---|" * 18]
    for r in checked(store):
        per, p = 1e3 / max(r["newton"], 1), r["partition"]
        part = f"{p['copies']} of {p['vertices']} ({p['type']})" if p else "-"
        ev = r["ev"]
        lines.append(f"| {r['cells']} | {r['unknowns']} | {r['ranks']} | {r['solver']} | {part} | {r['newton']} | {r['krylov']} | "
                     f"{r['setups']} | {r['solve_wall']:.1f} | {r['cpu']:.1f} | {ev['residual'] * per:.0f} | {ev['jacobian'] * per:.0f} | "
                     f"{ev['pcsetup'] * per:.0f} | {ev['ksp'] * per:.0f} | {r['rss']:.0f} | {r['rss_all']:.0f} | {kb(r):.1f} | "
                     f"{r['diff']:.0e} |")
    return "\n".join(lines)


def find(rows, solver, ranks, n=None):
    """The rows of solver on ranks, by unknowns (n: the one nearest n unknowns, or None)."""
    sel = sorted((r for r in rows if r["solver"] == solver and r["ranks"] == ranks), key=lambda r: r["unknowns"])
    if n is None:
        return sel
    return min(sel, key=lambda r: abs(r["unknowns"] - n)) if sel else None


def reading(rows):
    """The reading, every number from the rows."""
    d1, g1, g2 = find(rows, DIRECT, 1), find(rows, GAMG, 1), find(rows, GAMG, 2)
    worst = max(r["diff"] for r in rows)
    out = [f"- **Correctness.** Every run agrees with the 1-rank run on its mesh to {worst:.0e} or better: 2 ranks against 1, "
           "and GAMG against direct (the 1-rank direct run is the reference where it ran, else the 1-rank GAMG run)."]
    if len(d1) >= 2:
        a, b = d1[0], d1[-1]
        out.append(f"- **Memory of the direct solve** grows faster than the unknowns: {kb(a):.0f} kB per unknown at {a['unknowns']} "
                   f"unknowns, {kb(b):.0f} kB at {b['unknowns']} ({b['rss'] / 1024:.1f} GB on one rank): the fill of a 3D "
                   "factorisation. This is why GAMG takes over above `-fe_gamg_above` unknowns.")
    if g1:
        lo, hi = min(kb(r) for r in g1), max(kb(r) for r in g1)
        its = [r["krylov"] / max(r["newton"], 1) for r in g1]
        big = g1[-1]
        out.append(f"- **Memory of GAMG** stays between {lo:.1f} and {hi:.1f} kB per unknown on one rank from {g1[0]['unknowns']} to "
                   f"{big['unknowns']} unknowns ({big['rss'] / 1024:.1f} GB at {big['unknowns']}), and its Krylov iterations per "
                   f"Newton iteration (rtol 1e-10) stay between {min(its):.0f} and {max(its):.0f}: the near null space works.")
    pairs = [(r, find(rows, r["solver"], 1, r["unknowns"])) for r in rows if r["ranks"] == 2]
    pairs = [(two, one) for two, one in pairs if one and one["unknowns"] == two["unknowns"]]
    if pairs:
        two, one = max(pairs, key=lambda p: (p[0]["unknowns"], p[0]["solver"] == GAMG))
        share = [p[0]["partition"]["copies"] / p[0]["partition"]["vertices"] for p in pairs if p[0]["partition"]]
        speed = [p[1]["solve_wall"] / p[0]["solve_wall"] for p in pairs if p[0]["unknowns"] > 4e4]
        out.append(f"- **2 ranks** split the memory: {two['solver']} at {two['unknowns']} unknowns takes {two['rss']:.0f} MB on its "
                   f"largest rank against {one['rss']:.0f} MB on one, {two['rss_all']:.0f} MB in all "
                   f"({kb(two):.1f} kB per unknown against {kb(one):.1f}). The graph partitioner (docs/parallel.md, \"The "
                   f"partition\") puts {min(share) * 100:.1f}-{max(share) * 100:.1f} % of the vertices on both ranks.")
        if speed:
            out.append(f"- **Speed-up.** Above 4e4 unknowns the stepping's wall time on 2 ranks is {min(speed):.2f} to "
                       f"{max(speed):.2f} times shorter than on one, on this machine's 2 cores (how quiet they were: the load "
                       "averages above). The CPU column includes the set-up and, on 2 ranks, MPI's busy waiting: the "
                       "stepping's wall clock is the measure here.")
    if g2 and g1:
        r2 = g2[-1]
        r1 = find(rows, GAMG, 1, r2["unknowns"])
        out.append(f"- **GAMG on 2 ranks** needs {r2['krylov'] / max(r2['newton'], 1):.0f} Krylov iterations per Newton "
                   f"iteration at {r2['unknowns']} unknowns, against {r1['krylov'] / max(r1['newton'], 1):.0f} on one rank.")
    return out


def section(store, root=None):
    """The section's text: the commands, the method, the table and the reading. `root` is unused (the uniform call of
    tools/doc_numbers.py)."""
    rows, runs = checked(store), store["provenance"]["runs"]
    cmds = "; ".join(f"`{r['command']}` ({r['date']}, the driver at {r['rev']}, load average {r['load'][0]:.1f} at the start "
                     f"and {r['load'][1]:.1f} at the end)" for r in runs)
    steps = sorted({r["max_steps"] for r in runs})
    lines = [TITLE, "", f"Commands: {cmds}.", "",
             "**Method.**",
             f"- **The run.** The triaxial cylinder (P1 tets, mesh made once by gmsh and read by every run), one 100 s step at "
             f"the confinement, then the first {'/'.join(str(s - 1) for s in steps)} steps of the creep (dt from 0.01 s). One "
             "BLAS thread per rank. One run each. Direct: GMRES around MUMPS' LU kept across steps, asked for with "
             "`-fe_gamg_above 2000000000` (by default the driver takes GAMG itself above `-fe_gamg_above` = 1e5 unknowns); "
             "GAMG: `-pc_type gamg` (rigid-body near null space), set up again only when its iterations grow.",
             "- **The parts of a Newton iteration** are -log_view's times (wall, the largest over the ranks) divided by the Newton "
             "iterations. The residual is evaluated about three times per step (at the start, after each Newton update, and once "
             "more with the UMAT's step control on), so it can exceed the iteration. The set-ups (factorisations or GAMG "
             "hierarchies) weigh far more in these short runs than in a long one, where they are amortised.",
             "- **Wall and CPU.** Wall: the stepping's wall clock (the stage runner's). CPU: the slowest rank's process CPU time "
             "from the solver's set-up on, its initial field output included, so it exceeds the wall on the large meshes.",
             "- **Memory.** The largest resident set of a rank (getrusage) and the sum over the ranks; about 55 MB per rank is "
             "the executable, PETSc and MPI.",
             "- **The last column** is the largest difference of each run's axial strain history from the 1-rank run on the "
             "same mesh, relative to the creep.",
             "- **The machine.** 2 cores; the 2-rank runs use both, so their wall times compete with anything else running.",
             "", table(store), "", "**Reading** (computed from the rows).", *reading(rows)]
    return "\n".join(lines) + "\n"
