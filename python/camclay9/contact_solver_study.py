"""The section "Contact solve: direct against field split" of docs/performance.md (issue 33, docs/contact.md), written
from its results store docs/results/contact_solver.json by bench/contact_solver_bench.py and checked against it by
tools/doc_numbers.py.

The store: {"provenance": {"command", "date", ...}, "rows": [...]}, each row {"case", "solver", "unknowns", "steps",
"newton", "krylov", "cpu" [s], "mem" [MB], "repeats", "ranks" (1 if absent)} as the bench measured it (CPU the median of
the repeats, summed over the ranks; memory the largest process's, the largest of the repeats); on more than one rank
also "mem_all" (the ranks' peaks summed [MB], the driver's 'memory:' line) and "partition" ({"type", "vertices",
"copies"}: the driver's 'partition:' line); a whole run's row also "outputs" ({"P" [µN], "creep", "h_res" [nm]}) and,
on fixed steps, "stages" ({stage: {"steps", "solves", "krylov"}}: its solves' Krylov iterations by stage, from its log,
adding up to "krylov"); a row run with -log_view "events" ({event: seconds}); a run stopped and resumed from its checkpoints (the bench's --keep
--budget) "parts", their number (its CPU and Krylov iterations summed over them, its memory the largest part's); a case may lack a direct row (beyond its memory: no ratios). "provenance" may hold "merged", a list of
{"command", "date", "rows" (or "cases"), "note" (optional)}: those rows (cases) rerun by the bench's --merge, in order. A row may also hold "cpu_ratio" and
"mem_ratio", its CPU and memory over the direct path's on the same case as a table printed them from the run's full
digits, where the store keeps only the table's digits of CPU and memory (rows taken over from an earlier table; the
provenance says so); else the ratios are computed.
"""
import re

STORE = "contact_solver"
FORCING = "fieldsplit, forcing term"   # the bench's solver with GMRES' tolerance by the forcing term
TITLE = "## Contact solve: direct against field split"
# fixed steps, equal on every mesh: the load's 20 s (the depth of 200 nm near 205 s; BN's 13.3 s, 5 um near 140 s), the
# hold's and the unload's 2.5 s (the shipped scenes' unload takes at most 1 s). The unload's steps are half the 5 s they
# were: at 1.03 M unknowns the first 5 s unload step stalled (14 Newton iterations, the merit settled near 1e-5 of the
# load) and was cut back, and the unload's solves took 113 Krylov iterations each against the hold's 75; at 101 k and
# 190 k the last 5 s step, which releases the whole contact, stalled and was cut back (at 101 k, traced with the Newton
# monitor, in a two-cycle of the soft frame). On 2.5 s steps 190 k cuts no step back (140 Newton iterations in the whole
# run against 171), 1.03 M one (the forcing term: 60 unload solves of 48 Krylov iterations) and BN's 1.03 M none;
# 101 k still cuts its release back once, and there the 2.5 s steps cost a little more than the 5 s ones (161 Newton
# iterations against 157). The hold's steps are a quarter of the 10 s they were: at 1.03 M unknowns the second 10 s
# step did not converge (its Newton settled near 1e-5 of the load, its solves needed up to 500 Krylov iterations), while
# from the same state 2.5 s steps converged in 2 Newton iterations of about 75 Krylov iterations each (restarts from
# that run's checkpoint of its first hold step, by hand, with the Newton monitor). A 10 s step outruns the soft frame's
# softening time at points near the yield surface, whose backward-Euler solution then jumps (theory.md §3.4): Newton
# cannot settle those points, and the finer the mesh the more of them there are
FIXED_STEPS = [{"count": 30}, {"count": 24}, {"count": 8}]
# Newton on them to a residual of 1e-6 of the load (the driver's default 1e-10): fixed steps have no error measure to
# stop Newton by its estimated error, and from about 1e5 unknowns on, the hold's 10 s steps ended in a two-cycle of a
# few points of the soft frame switching branch (theory.md §3.4) far below any output's tolerance, which the stall test
# cuts back again and again (docs/contact.md, "The Newton loop")
FIXED_RTOL = ["-indent_rtol", "1e-6"]


def merges(provenance):
    """The provenance's merges, oldest first."""
    return list(provenance.get("merged", []))


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
    also = "".join(f" {'Rows ' + '; '.join(m['rows']) if 'rows' in m else 'Cases ' + ', '.join(m['cases'])}: `{m['command']}` "
                   f"({m['date']}{'; ' + m['note'] if m.get('note') else ''})." for m in merges(pv))
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}; a shared 2-core machine, one rank).{also} The first steps of the "
             "kerogen nanoindentation on each path (the bench's docstring gives the cases): CPU is user + system of the driver, "
             f"median of the repeats{fewer}; memory the driver's peak resident set. 'fieldsplit': on P2 the p-multigrid to P1 "
             "on the displacement block; 'fieldsplit, GAMG on P2': GAMG on the P2 block itself (-indent_fieldsplit_pmg false); "
             "'fieldsplit, before': that as it was before its GAMG hierarchy was kept (set up at every Newton iteration, the full "
             "Schur factorisation); 'fieldsplit, LU on u': the displacement block solved exactly (a fresh LU at every Newton "
             "iteration), so that its Krylov iterations are the Schur estimate's. "
             "A case without a direct row is beyond the direct path's memory.", "",
             "| case | unknowns | steps | solver | Newton its | Krylov its | CPU [s] | CPU / direct | peak memory [MB] | memory / direct |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    direct = {r["case"]: r for r in rows if r["solver"] == "direct"}
    for r in rows:
        cpu_ratio, mem_ratio = ((f"{x:.2f}" for x in ratios(r, direct[r["case"]])) if r["case"] in direct else ("—", "—"))
        how = [f"{r.get('ranks')} ranks"] * (r.get("ranks", 1) > 1) + [f"in {r.get('parts')} parts"] * (r.get("parts", 1) > 1)
        ranks = f" ({', '.join(how)})" if how else ""   # parts: stopped and resumed from its checkpoints
        mem = f"{r['mem']:.0f}" + (f" ({r['mem_all']:.0f} in all)" if "mem_all" in r else "")
        lines.append(f"| {r['case']}{ranks} | {r['unknowns']} | {r['steps']} | {r['solver']} | {r['newton']} | {r['krylov']} | "
                     f"{r['cpu']:.2f} | {cpu_ratio} | {mem} | {mem_ratio} |")
    return "\n".join(lines + partitions(rows) + breakdown(rows) + outputs_table(rows) + stage_table(rows)) + "\n"


def stage_table(rows):
    """The rows with a stage split (the bench's fixed-step cases, from the solves' Krylov iterations in their logs):
    each stage's Krylov iterations per solve and its solves, the solves of rejected attempts included."""
    rows = sorted((r for r in rows if r.get("stages")), key=lambda r: (re.match(r"[a-z]+", r["case"])[0], r["unknowns"]))
    if not rows:
        return []
    names = list(dict.fromkeys(n for r in rows for n in r["stages"]))
    cell = lambda d: f"{d['krylov'] / d['solves']:.1f} ({d['solves']})" if d and d["solves"] else "—"
    return ["", "Krylov iterations per solve by stage (in brackets: the stage's solves, those of attempts cut back included), "
            "from each solve's count in the run's log:", "",
            "| case | solver | unknowns | " + " | ".join(names) + " |", "|---|---|---|" + "---|" * len(names)] + [
            f"| {r['case']} | {r['solver']} | {r['unknowns']} | " + " | ".join(cell(r["stages"].get(n)) for n in names) + " |"
            for r in rows]


def breakdown(rows):
    """The -log_view events of the rows run with it [s, the largest over the ranks]: the project's (CC9 ...: the
    residual with its UMAT calls, the Jacobian's assembly, the contact terms, the matrix-free tangent, the whole contact
    solve) and PETSc's inside the contact solve (the multigrid's set-up, the displacement block's and the Schur
    complement's solves, the matrix products, the wait for ghost values)."""
    rows = [r for r in rows if r.get("events")]
    if not rows:
        return []
    names = list(dict.fromkeys(e for r in rows for e in r["events"]))
    return ["", "Where the time goes (-log_view, seconds, the largest over the ranks):", "",
            "| case | solver | " + " | ".join(names) + " |", "|---|---|" + "---|" * len(names)] + [
            f"| {r['case']} | {r['solver']} | " + " | ".join(f"{r['events'][e]:.1f}" if e in r["events"] else "—" for e in names)
            + " |" for r in rows]


def partitions(rows):
    """How each 2-rank row's partition cut its mesh (the driver's 'partition:' line): the vertices held by a rank that
    does not own them."""
    parts = [r for r in rows if "partition" in r]
    return ["", "Partitions (2 ranks): " + "; ".join(
        f"{r['case']}, {r['solver']}: {r['partition']['type']}, {r['partition']['copies']} of {r['partition']['vertices']} "
        f"vertices also on the other rank ({100 * r['partition']['copies'] / r['partition']['vertices']:.0f} %)" for r in parts) + "."] if parts else []


def outputs_table(rows):
    """The rows that ran a whole load, hold and unload with their outputs (the bench's fix... and bnfix... cases: equal
    fixed steps on every mesh), each output also relative to the finest mesh's of its family (the case's name without
    its size): the mesh's share alone, the time steps' being equal."""
    rows = sorted((r for r in rows if "outputs" in r), key=lambda r: r["unknowns"])
    if not rows:
        return []
    family = lambda r: re.match(r"[a-z]+", r["case"])[0]
    # the finest rung of each family: its largest row of the field split, tight or with the forcing term (whose outputs
    # agree with the tight solves' to the digits printed on the same steps), the tight one where both ran (the rows
    # sorted by size, the tight one last); the other solvers' rows of that mesh are compared with it
    fine = {family(r): r["outputs"] for r in sorted(rows, key=lambda r: (r["unknowns"], r["solver"] == "fieldsplit"))
            if r["solver"] in ("fieldsplit", FORCING)}
    rel = lambda r, k: f"{r['outputs'][k]:.5g} ({100 * (r['outputs'][k] / fine[family(r)][k] - 1):+.2f}%)"
    return ["", "Reported outputs of the whole runs on equal fixed steps (in brackets: against the finest rung of the same "
            "scene): the load at the end of loading, the creep depth and the residual depth. The steps' own error is the same "
            "on every mesh and is in every row (these fixed steps give a creep depth well below the shipped scenes' adaptive "
            "steps'), so the differences between rows are the mesh's share alone (a row with more steps had some of its steps "
            "cut back). Newton stops at a residual of 1e-6 of the load; the row 'Newton to 1e-10' runs to the driver's default "
            "on the same mesh.", "",
            "| case | unknowns | steps | P [µN] | creep [nm] | h_res [nm] |", "|---|---|---|---|---|---|"] + [
            f"| {r['case']}{'' if r['solver'] == 'fieldsplit' else ', ' + r['solver']} | {r['unknowns']} | {r['steps']} | "
            f"{rel(r, 'P')} | {rel(r, 'creep')} | {rel(r, 'h_res')} |"
            for r in sorted(rows, key=lambda r: (family(r), r["unknowns"]))]
