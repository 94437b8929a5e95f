"""The section "FE solver: defaults by measurement" of docs/performance.md (issue 13, items 2, 3 and 6), written from its
results store docs/results/fe_solver.json by bench/fe_solver_bench.py and checked against it by tools/doc_numbers.py.

The store:
- "provenance": {"command", "date", "rev" (the driver's commit), "load" (the machine's 1-minute load average at the
  start and the end), "machine" (what else ran on it)}, and "merged": the later commands run with --merge, oldest
  first, each {"command", "date", "rev", "load", "machine", "rows" (its rows, "<size> mm: <candidate>")}.
- "history": the bench's short history {"hold_s", "creep_s", "first_dt", "max_dt" [s], "tol" (PROPS tol)}.
- "probe": what the bench asked the solvers themselves, on the mesh of element size "size" ("cells" cells):
  "jacobians" Jacobians of the default run (its whole short history, -ksp_view_mat binary) and over them the largest
  "asymmetry" ||J - J^T||_F / ||J||_F; "petsc_ordering" (PETSc LU's ordering, -ksp_view); "mumps_version"; "orderings":
  {what was asked (ORDERING_PROBES): {"options", "ordering" (what MUMPS reports it used, "" if it reported
  none), "warnings" (its warnings, with -mat_mumps_icntl_4 2)}}.
- "rows": one per (mesh, candidate), keyed by ("size", "candidate"), each {"size" (element size [mm]), "candidate",
  "options", "max_steps" (0: the whole history), "repeats", "cells", "unknowns", "steps", "newton", "krylov",
  "setups" (preconditioner set-ups), "wall" and "cpu" (the stepping's wall clock and CPU [s], medians of the repeats),
  "cpu_runs" (every repeat's CPU), "rss" (max resident set [MB]), "reference" (the candidate whose history it is
  compared with: the first of its mesh in the run), "diff" (the largest difference of the axial strain history from
  the reference's, relative to its creep strain; null if the step times differ), "identical_to" (the earlier
  candidates of its mesh whose history it repeats bit for bit), "dt_first", "dt_last" (the creep stage's first
  step, the deviator's instant load, 0, and its last step [s]), "events" (-log_view: {event: {"count", "s" (its time, the median of the repeats)}} for EVENTS)}.
Values at full digits; the tables print them, and the reading's numbers are computed from the rows and the probe.
"""
from camclay9 import results_store

STORE = "fe_solver"
TITLE = "## FE solver: defaults by measurement"
PLAIN = "-fe_refactor_its 0 -ksp_type preonly"   # a fresh factorisation at every Newton iteration, no Krylov solver
LU, UMFPACK, AMD, PORD = "PETSc LU", "UMFPACK", "MUMPS AMD", "MUMPS PORD"
AUTO, METIS, BLR = "MUMPS, automatic ordering", "MUMPS, METIS asked", "MUMPS, BLR 1e-8"
DEFAULT, MSV, LBLR, GAMG = ("lagged MUMPS (default)", "the same, MatSetValues instead of COO", "lagged MUMPS, BLR 1e-8",
                            "GAMG (lagged set-up)")
BLR_OPTS = "-mat_mumps_icntl_35 1 -mat_mumps_cntl_7 1e-8"
CANDIDATES = {  # name: options added to the driver's defaults, in the order they run
    LU: PLAIN + " -pc_factor_mat_solver_type petsc", UMFPACK: PLAIN + " -pc_factor_mat_solver_type umfpack",
    AMD: PLAIN + " -mat_mumps_icntl_7 0", PORD: PLAIN + " -mat_mumps_icntl_7 4", AUTO: PLAIN,
    METIS: PLAIN + " -mat_mumps_icntl_7 5", BLR: PLAIN + " " + BLR_OPTS, DEFAULT: "", MSV: "-fe_coo false",
    LBLR: BLR_OPTS, GAMG: "-pc_type gamg"}
SHORTLIST = (AUTO, DEFAULT, MSV, LBLR, GAMG)   # the largest mesh's candidates
# what the bench asks MUMPS on the first mesh (its first step), with its diagnostics on (-mat_mumps_icntl_4 2) but for
# the quiet one: {name: (what is asked, options)}
ORDERING_PROBES = {"automatic": ("ICNTL(7) = 7", PLAIN + " -mat_mumps_icntl_4 2"),
                   "METIS": ("ICNTL(7) = 5", PLAIN + " -mat_mumps_icntl_4 2 -mat_mumps_icntl_7 5"),
                   "SCOTCH": ("ICNTL(7) = 3", PLAIN + " -mat_mumps_icntl_4 2 -mat_mumps_icntl_7 3"),
                   "METIS, quiet": ("ICNTL(7) = 5", PLAIN + " -mat_mumps_icntl_7 5")}
EVENTS = ("CC9 residual+UMAT", "CC9 Jacobian", "PCSetUp", "KSPSolve")
KEYS = ("size", "candidate", "options", "max_steps", "repeats", "cells", "unknowns", "steps", "newton", "krylov", "setups",
        "wall", "cpu", "cpu_runs", "rss", "reference", "diff", "identical_to", "dt_first", "dt_last", "events")
RUN = ("command", "date", "rev", "load", "machine")
PROBE = ("size", "cells", "jacobians", "asymmetry", "petsc_ordering", "mumps_version", "orderings")


def checked(store):
    """The store's parts, each key checked (a missing one names the file and the key); the meshes the reading needs:
    (the whole-history meshes, coarse first, and the largest shortlisted one), each {candidate: row}."""
    results_store.require(STORE, "the store", store, ("provenance", "history", "probe", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], RUN)
    for i, m in enumerate(store["provenance"].get("merged", [])):
        results_store.require(STORE, f"provenance.merged[{i}]", m, RUN + ("rows",))
    results_store.require(STORE, "history", store["history"], ("hold_s", "creep_s", "first_dt", "max_dt", "tol"))
    results_store.require(STORE, "probe", store["probe"], PROBE)
    for k, o in store["probe"]["orderings"].items():
        results_store.require(STORE, f"probe.orderings.{k}", o, ("options", "ordering", "warnings"))
    meshes = {}
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
        results_store.require(STORE, f"rows[{i}].events", r["events"], EVENTS)
        for e in EVENTS:
            results_store.require(STORE, f"rows[{i}].events.{e}", r["events"][e], ("count", "s"))
        meshes.setdefault(r["size"], {})[r["candidate"]] = r
    whole = [s for s in sorted(meshes, reverse=True) if all(r["max_steps"] == 0 for r in meshes[s].values())]
    first = [s for s in sorted(meshes) if s not in whole]
    if not whole or not first:
        raise ValueError(f"docs/results/{STORE}.json: rows of a whole-history mesh and of a mesh run for its first steps "
                         "expected")
    for size, names in [(s, CANDIDATES) for s in whole] + [(first[0], SHORTLIST)]:
        missing = [n for n in names if n not in meshes[size]]
        if missing:
            raise ValueError(f"docs/results/{STORE}.json: the {size:g} mm mesh lacks the rows of {', '.join(missing)}")
    return [meshes[s] for s in whole], meshes[first[0]]


def ms(r):
    """CPU per Newton iteration [ms]."""
    return 1e3 * r["cpu"] / max(r["newton"], 1)


def each(r, event):
    """An event's time per call [ms] (-log_view)."""
    e = r["events"][event]
    return 1e3 * e["s"] / max(e["count"], 1)


def spread(runs):
    """The repeats' range relative to their smallest."""
    return (max(runs) - min(runs)) / min(runs)


def change(new, old):
    """'N % less' or 'N % more' for new against old."""
    d = new / old - 1
    return f"{abs(d) * 100:.0f} % {'less' if d <= 0 else 'more'}"


def run_line(p, what=""):
    load = f"load average {p['load'][0]:.1f} at the start and {p['load'][1]:.1f} at the end, on 2 cores"
    return (f"- `{p['command']}` ({p['date']}, the driver at {p['rev']}; {load}; {p['machine']}){what}.")


def head(store):
    """The title, the commands with their provenance, and the method."""
    pv, h, rows = store["provenance"], store["history"], store["rows"]
    merged = [run_line(m, f": its rows, on the {', '.join(sorted({x.split(' mm')[0] for x in m['rows']}, key=float))} mm "
                          "mesh") for m in pv.get("merged", [])]
    ratios = [r["wall"] / r["cpu"] for r in rows]
    noise = max([spread(r["cpu_runs"]) for r in rows if len(r["cpu_runs"]) > 1] or [0])
    return [TITLE, "", "Issue 13, items 2, 3 and 6. Commands (one rank, one BLAS thread):", run_line(pv), *merged, "",
            "**Method.** The triaxial cylinder of `input/triaxial.yaml` (P1 tetrahedra) runs on a short history: one "
            f"{h['hold_s']:g} s step at the confinement, then {h['creep_s'] / 3600:g} h of creep under the deviator with "
            f"adaptive steps from dt = {h['first_dt']:g} s (at most {h['max_dt']:g} s) and PROPS tol {sci(h['tol'])}. Each "
            "candidate runs in turn, once per round; the rounds repeat, and the tables give medians of the repeats. Every "
            "run has `-log_view`.",
            "- Wall and CPU cover the stepping only (meshing excluded): the stage runner's wall clock and the process's "
            "CPU clock from the solver's set-up on. The choice is made on **CPU time**: the machine is shared, so the "
            f"wall clocks are {min(ratios):.1f} to {max(ratios):.1f} times the CPU times, and noisy. The repeats of one "
            f"candidate differ by up to {noise * 100:.0f} % in CPU.",
            "- The last column is the largest difference of the axial strain history from the mesh's first row, in the "
            "same run, relative to the creep strain.",
            "- The step-control error of this history (section \"FE: triaxial cylinder\") is far larger than any of these "
            "differences, so the solver choice does not change the answer.", "",
            "The candidates: the options each adds to the driver's defaults (GMRES, right-preconditioned, rtol 1e-10, "
            "around MUMPS' LU kept across Newton iterations and steps):", "", "| candidate | options |", "|---|---|",
            *[f"| {n} | `{o}` |" if o else f"| {n} | (none) |" for n, o in CANDIDATES.items()]]


def table(rows):
    lines = ["| cells | unknowns | solver | steps | Newton its | Krylov its | set-ups | wall [s] | CPU [s] | CPU ms per "
             "Newton it. | max RSS [MB] | axial strain vs reference |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        diff = "—" if r["diff"] is None else f"{r['diff']:.1e}"
        lines.append(f"| {r['cells']} | {r['unknowns']} | {r['candidate']} | {r['steps']} | {r['newton']} | {r['krylov']} | "
                     f"{r['setups']} | {r['wall']:.2f} | {r['cpu']:.2f} | {ms(r):.1f} | {r['rss']:.0f} | {diff} |")
    return lines


def tables(store):
    """One table per kind of run (the whole history; the first steps), then where the time goes."""
    groups = {}
    for r in store["rows"]:
        groups.setdefault((r["max_steps"], r["repeats"]), []).append(r)
    out = []
    for (cap, repeats), rows in groups.items():
        sizes = " and ".join(f"{s:g}" for s in dict.fromkeys(r["size"] for r in rows))
        runs = f"medians of {repeats}" if repeats > 1 else "one run each"
        if cap:
            what = (f"The {sizes} mm mesh, the first {cap} steps (the hold step, then the creep stage's first {cap - 1}, the "
                    f"last of them {rows[0]['dt_last']:.2g} s; {runs}):")
        else:
            what = f"The {sizes} mm meshes, the whole short history ({runs}):"
        out += ["", what, "", *table(rows)]
    out += ["", "Where the time goes (`-log_view` of the same runs, medians of the repeats; the events' wall times, as "
            "loaded as the wall column). PCSetUp: the factorisations (for GAMG the event is logged more often than the set-ups "
            "the driver counts); KSPSolve: the Krylov solves with their triangular solves (PCApply), without the PCSetUp.",
            "",
            "| cells | solver | residual+UMAT calls | ms each | Jacobians | ms each | PCSetUp | ms each | KSPSolve [s] |",
            "|---|---|---|---|---|---|---|---|---|"]
    for r in store["rows"]:
        ev = r["events"]
        res = "CC9 residual+UMAT"
        out.append(f"| {r['cells']} | {r['candidate']} | {ev[res]['count']} | {each(r, res):.2f} | {ev['CC9 Jacobian']['count']} "
                   f"| {each(r, 'CC9 Jacobian'):.2f} | {ev['PCSetUp']['count']} | {each(r, 'PCSetUp'):.2f} | "
                   f"{ev['KSPSolve']['s']:.2f} |")
    return out


def section(store, root=None):
    """The section's text: the commands, the method, the tables, the reading computed from the rows and the probe.
    `root` is unused (the uniform call of tools/doc_numbers.py)."""
    full, short = checked(store)
    return "\n".join(head(store) + tables(store) + reading(store, full, short)) + "\n"


def signed(new, old):
    """new against old as a signed percentage."""
    return f"{(new / old - 1) * 100:+.0f} %"


def sci(x):
    """1e-06 as 1e-6."""
    m, e = f"{x:.0e}".split("e")
    return f"{m}e{int(e)}"


def tangent(probe):
    a = sci(probe["asymmetry"])
    where = (f"over the {probe['jacobians']} Jacobians of the default run on the {probe['cells']}-cell mesh (written by "
             "`-ksp_view_mat binary`, read by the bench)")
    if probe["asymmetry"] < 1e-12:
        return [f"- **The tangent is symmetric to roundoff**: ‖J − Jᵀ‖_F/‖J‖_F is at most {a} {where}."]
    return [f"- **The tangent is unsymmetric.** ‖J − Jᵀ‖_F/‖J‖_F reaches {a} {where}: the viscoplastic consistent "
            "tangent. So the candidates are LU (MUMPS, UMFPACK, PETSc's own); Cholesky (CHOLMOD) would not be exact."]


def native(probe, big):
    lu, auto = big[LU], big[AUTO]
    fresh = [big[n] for n in (LU, UMFPACK, AMD, PORD, AUTO, METIS, BLR)]
    slow = max(fresh, key=ms) is lu
    order = probe["petsc_ordering"]
    nd = ("nested dissection (`nd`, `-ksp_view`), so the nested-dissection variant of the issue is what it ran"
          if order == "nd" else f"`{order}` (`-ksp_view`)")
    return [f"- **PETSc's native LU is {'the slow one' if slow else 'not the slowest'}.** Its ordering is {nd}. On "
            f"{lu['cells']} tets it costs {ms(lu) / ms(auto):.1f}× MUMPS (automatic ordering) per Newton iteration; a "
            f"factorisation (PCSetUp) takes {each(lu, 'PCSetUp') / each(auto, 'PCSetUp'):.1f}× as long."]


def orderings(probe, full):
    big = full[-1]
    names = {AMD: "AMD", PORD: "PORD", AUTO: "automatic", METIS: "METIS asked"}
    v = {n: ms(big[n]) for n in names}
    sp = (max(v.values()) - min(v.values())) / min(v.values())
    noise = max(spread(big[n]["cpu_runs"]) for n in names)
    out = [f"- **The MUMPS orderings differ by {sp * 100:.0f} %** per Newton iteration on {big[AUTO]['cells']} tets ("
           + ", ".join(f"{names[n]} {v[n]:.1f} ms" for n in names) + f"), {'less than' if sp < noise else 'against'} the "
           f"{noise * 100:.0f} % between the repeats of one of them."]
    o = probe["orderings"]
    missing = [k for k in ("METIS", "SCOTCH") if any("not available" in w for w in o[k]["warnings"])]
    if missing:
        asked = "; ".join(f"for {k} ({ORDERING_PROBES[k][0]}), it prints \"{o[k]['warnings'][0]}\"" for k in missing)
        quiet = "" if o["METIS, quiet"]["warnings"] else " Without the diagnostics it says nothing."
        out.append(f"- **This MUMPS ({probe['mumps_version']}, Debian's) has no {' and no '.join(missing)}.** With its "
                   f"diagnostics on (`-mat_mumps_icntl_4 2`) and asked {asked}; it then orders by "
                   f"{o['METIS']['ordering'] or 'its default'} on the {probe['cells']}-cell mesh.{quiet} ParMETIS and PT-Scotch, the tools of the parallel "
                   "analysis (ICNTL(28) = 2), were not probed: that needs more than one rank.")
    twins = []
    for m in full:
        twin = [names[n] for n in (AMD, PORD) if n in m[AUTO]["identical_to"]]
        twins.append(f"{twin[0]}'s bit for bit" if twin else "neither AMD's nor PORD's")
    depends = ": the choice depends on the matrix" if len({x for x in twins}) > 1 else ""
    same = all(AUTO in m[METIS]["identical_to"] for m in full)
    out += [f"  - MUMPS' automatic choice (ICNTL(7) = 7) is {o['automatic']['ordering']} on the {probe['cells']}-cell mesh "
            "(the probe). Its history is " + ", ".join(f"{x} on {m[AUTO]['cells']} tets" for x, m in zip(twins, full))
            + f"{depends}. The rows 'METIS asked' {'repeat' if same else 'do not all repeat'} the automatic choice's "
            "history bit for bit on every mesh.",
            "  - The default is MUMPS' automatic choice: the driver asks for no ordering. `-mat_mumps_icntl_7` overrides it."]
    return out


def blr(full, short):
    lagged = full + [short]
    noise = max(spread(r["cpu_runs"]) for m in full for r in (m[BLR], m[AUTO], m[LBLR], m[DEFAULT]))
    fresh_cpu = ", ".join(f"{signed(ms(m[BLR]), ms(m[AUTO]))} on {m[AUTO]['cells']} tets" for m in full)
    lagged_cpu = ", ".join(f"{signed(ms(m[LBLR]), ms(m[DEFAULT]))} on {m[DEFAULT]['cells']} tets" for m in lagged)
    out = [f"- **BLR (ICNTL(35) = 1, CNTL(7) = 1e-8)** changes the CPU per Newton iteration by {fresh_cpu} with a fresh "
           f"factorisation at every iteration, and by {lagged_cpu} inside the lagged GMRES (the repeats of one candidate: up "
           "to {:.0f} %). It is not the default.".format(noise * 100)]
    same = [(m[AUTO]["cells"], m[DEFAULT]["cells"] if DEFAULT in m[LBLR]["identical_to"] else None) for m in full
            if AUTO in m[BLR]["identical_to"]]
    rest = [m for m in lagged if DEFAULT not in m[LBLR]["identical_to"]]
    if same:
        out.append("  - Its history is that without BLR bit for bit on " + " and ".join(f"{c} tets" for c, _ in same)
                   + " with a fresh factorisation" + (", and inside the lagged GMRES too" if all(x for _, x in same) else "")
                   + ": there it changed no bit of the answer.")
    if rest:
        its = all(m[LBLR]["newton"] == m[DEFAULT]["newton"] for m in rest)
        worst = max(m[LBLR]["diff"] for m in rest)
        out.append("  - Inside the lagged GMRES on " + " and ".join(f"{m[DEFAULT]['cells']} tets" for m in rest) + ", its "
                   f"approximation is harmless: {'the same' if its else 'other'} Newton iterations, and the answer of the "
                   f"reference (the mesh's first row) to {sci(worst)}.")
    return out


def lagging(full):
    big = full[-1]
    d, a = big[DEFAULT], big[AUTO]
    same = all(m[DEFAULT]["newton"] == m[AUTO]["newton"] for m in full)
    gain = [1 - ms(m[DEFAULT]) / ms(m[AUTO]) for m in full]   # the CPU the lag saves
    out = ["- **Lagging removes almost all factorisations.** The factorisation is kept across Newton iterations and steps: "
           "GMRES (right-preconditioned, rtol 1e-10) with the old LU as its preconditioner. It is rebuilt at a stage's "
           "start, when a solve needs more than 20 Krylov iterations per Newton iteration (`-fe_refactor_its`), or more "
           f"than twice the fresh preconditioner's. On this history that means {d['setups']} factorisations instead of "
           f"{a['setups']} on {d['cells']} tets, with {'the same' if same else 'other'} Newton iterations and the answer "
           f"of the reference to {sci(max(m[DEFAULT]['diff'] for m in full))}. Against MUMPS refactored at every "
           "iteration, its CPU per Newton iteration is "
           + " and ".join(f"{signed(ms(m[DEFAULT]), ms(m[AUTO]))} on {m[DEFAULT]['cells']} tets" for m in full) + "."]
    if len(full) > 1 and all(x < y for x, y in zip(gain, gain[1:])):
        cost = [each(m[AUTO], "PCSetUp") / each(m[AUTO], "CC9 residual+UMAT") for m in full]
        out.append("  - The lag pays more as the mesh grows, because a factorisation grows faster than a residual "
                   "evaluation: one costs " + " and ".join(f"{c:.1f} residual evaluations on {m[AUTO]['cells']} tets"
                                                            for c, m in zip(cost, full)) + " (-log_view).")
    return out


def coo(full, short):
    meshes = full + [short]
    jac = ", ".join(f"{each(m[DEFAULT], 'CC9 Jacobian'):.1f} against {each(m[MSV], 'CC9 Jacobian'):.1f} ms on "
                    f"{m[DEFAULT]['cells']} tets" for m in meshes)
    cpu = ", ".join(f"{signed(m[DEFAULT]['cpu'], m[MSV]['cpu'])} on {m[DEFAULT]['cells']} tets" for m in meshes)
    out = ["- **COO assembly.** `MatSetPreallocationCOO`/`MatSetValuesCOO` replace `MatSetValues`. The Jacobian event "
           f"(-log_view) takes {jac} per assembly. The whole run's CPU: {cpu}."]
    grown = [(m, (m[DEFAULT]["rss"] - m[MSV]["rss"]) * 1024 / m[DEFAULT]["cells"]) for m in meshes]
    m, kb = grown[-1]
    out.append(f"  - Memory: the resident set is {m[DEFAULT]['rss'] - m[MSV]['rss']:.0f} MB larger on {m[DEFAULT]['cells']} "
               f"tets, {kb:.1f} kB per tet (the element matrices, 12 × 12 doubles per P1 tet, and PETSc's COO maps)."
               if kb > 0 else f"  - Memory: no larger resident set on {m[DEFAULT]['cells']} tets.")
    return out


def gamg(full, short):
    meshes = full + [short]
    its = [m[GAMG]["krylov"] / m[GAMG]["newton"] for m in meshes]
    g, d = short[GAMG], short[DEFAULT]
    return [f"- **GAMG** needs {min(its):.0f} to {max(its):.0f} GMRES iterations per Newton iteration at rtol 1e-10 on these "
            "meshes, with " + ", ".join(f"{m[GAMG]['setups']} set-ups on {m[GAMG]['cells']} tets" for m in meshes) + ".",
            f"  - On {g['cells']} tets it takes {change(g['cpu'], d['cpu'])} CPU than the lagged direct solve "
            f"({ms(g) / 1e3:.2f} against {ms(d) / 1e3:.2f} s per Newton iteration) and its resident set is "
            f"{change(g['rss'], d['rss'])} ({g['rss']:.0f} against {d['rss']:.0f} MB).",
            "  - Why direct stays the default below `-fe_gamg_above` (the driver's default: 1e5 unknowns): over a long run "
            "the direct solve's set-up is amortised further and GAMG's Krylov work is not; the whole main job needs only a "
            "few factorisations (section \"FE solver: the triaxial main job\"). Where GAMG takes over is measured on larger "
            "meshes in the section \"FE scaling: 1 and 2 ranks, direct and GAMG\"."]


def increment(full, short):
    big = full[-1]
    one = all(r["steps"] == r["newton"] for m in full for r in m.values())
    d, lu, s, a = big[DEFAULT], big[LU], short[DEFAULT], short[AUTO]
    return [("Each step of this history takes one Newton iteration, so the CPU per Newton iteration is the CPU per "
             "increment." if one else "Some steps take more than one Newton iteration: the CPU per increment is the "
             "CPU per Newton iteration times the Newton iterations per step."),
            f"- On {d['cells']} tets, one rank: {ms(d):.0f} ms with the default, against {ms(lu):.0f} ms with PETSc's LU "
            f"(the one-rank default before issue 13): "
            + (f"{ms(lu) / ms(d):.1f}× less." if ms(lu) > ms(d) else f"{change(ms(d), ms(lu))}."),
            f"- On {s['cells']} tets: {ms(s) / 1e3:.2f} s, against {ms(a) / 1e3:.2f} s for MUMPS refactored at every "
            f"iteration, over only {s['max_steps']} steps, where the set-ups weigh more than in a long run.",
            "- The comparison with CalculiX on shared meshes is the section \"CalculiX on the same mesh (issue 13)\"."]


def loops(full, short):
    share = lambda r, e: r["events"][e]["s"] / r["wall"]
    parts = [(m[DEFAULT], {"res": share(m[DEFAULT], "CC9 residual+UMAT"), "jac": share(m[DEFAULT], "CC9 Jacobian"),
                           "ksp": share(m[DEFAULT], "PCSetUp") + share(m[DEFAULT], "KSPSolve")}) for m in (full[-1], short)]
    where = "; ".join(f"on {r['cells']} tets {p['res'] * 100:.0f} % (the Jacobian's assembly {p['jac'] * 100:.0f} %, the "
                      f"linear solves with their set-ups {p['ksp'] * 100:.0f} %)" for r, p in parts)
    most = [r["cells"] for r, p in parts if p["res"] > max(p["jac"], p["ksp"])]
    verdict = (f"It is the largest part on {' and '.join(f'{c} tets' for c in most)}" if most
               else "It is not the largest part on either mesh")
    per = sorted({r["events"]["CC9 residual+UMAT"]["count"] / r["steps"] for r, _ in parts})
    return ["- **Boundary values.** The fixed components are zeroed from a list of constrained points and components made "
            "once at set-up (`fe_constraint_to_global`, driver/src/fe/fe_constraint.h); `DMPlexInsertBoundaryValues` is not "
            "called.",
            "- **Reactions** are summed over the ranks for a converged state only (`fe_problem_reactions`), not at every "
            "residual.",
            "- **The residual after convergence** is skipped when it would repeat SNES's last one (tol = 0). With tol > 0 it "
            "is needed: the UMAT's step control is on only for the converged state.",
            "- **Basis gradients are cached.** The physical gradients of the basis functions are computed once per "
            "quadrature point at set-up (fe_problem.c), and both loops apply the strain-displacement operator from them "
            "(fe_kernel.h) without forming B.",
            f"- **Where the time goes now** (-log_view, the default solver). The residual with its UMAT calls takes, of the "
            f"stepping's wall time, {where}. {verdict}; the first steps of the largest mesh weigh the set-ups more than a "
            f"long run does. It is evaluated {' to '.join(f'{x:.1f}' for x in per)} times per step: at the start, after the Newton update, "
            "and at the converged state with the UMAT's step control.",
            "- **Project events.** `-log_view` shows them: `CC9 residual+UMAT`, `CC9 Jacobian`, `CC9 contact`, "
            "`CC9 contact solve`, `CC9 tangent apply`, `CC9 field output` and `CC9 checkpoint` (driver/src/io/log_events.c)."]


def reading(store, full, short):
    return (["", "**Reading.**"] + tangent(store["probe"]) + native(store["probe"], full[-1])
            + orderings(store["probe"], full) + blr(full, short) + lagging(full) + coo(full, short) + gamg(full, short)
            + ["", "**Per increment (item 2's target).**"] + increment(full, short)
            + ["", "**Element loops (item 6).**"] + loops(full, short))
