"""The section "Indentation speed: the contact solve and the physics" of docs/performance.md, written from its results
store docs/results/indent_speed.json by bench/indent_speed_bench.py (or, without running, its --from-store) and checked
against it by tools/doc_numbers.py.

The store: {"provenance": {...}, "rows": [...]}.

"provenance": "command", "date", "rev" (the driver's commit), "machine" (the cores and what else ran), "load"
({"start": [...], "end": [...]}: the machine's load averages over 1, 5 and 15 min when the bench started and when it
ended), "repeats", "long" (a scene whose first run took more CPU [s] than this ran once), "umat_case" (the UMAT
benchmark's case whose time per call the ratio uses).

"rows": one per scene and driver in the bench's order, each {"scene", "driver" ("this tree"; with --against REV also
"before (REV)", with --elementary "this tree, elementary controller"), "options" (the driver's extra options),
"kinematics" (the scene's: 3d, axisymmetric, plane_strain), "order", "cells", "unknowns" (the run's mesh line), "cpu" (the
median of the runs' CPU [s]: user + system of the driver and of the gmsh it starts), "cpu_runs", "wall_runs" (each
run's CPU and wall time [s], in order), "steps", "rejected" (all cutbacks), "stalled" (of them, Newton stalled:
-indent_stall_window), "not_converged" (Newton's limit, a cycling active set, the linear solver), "newton", "krylov", "factorisations", "umat_calls" (the
first run's counts), "same_runs" (whether every run gave the first run's counts and outputs), "umat_ns" (the UMAT
benchmark's median time per call [ns], measured just before the scene's runs), "ratio" (cpu / (umat_calls x umat_ns):
the run's cost in UMAT calls at the benchmark's rate), "rss_mb" (the first run's peak resident memory [MB]), "outputs"
({"load": at the end of loading [µN], "creep_depth": the hold's change of depth [µm], "final_depth": the depth at the
end of the last stage [µm], "final_stage": that stage's name}), "log_view" ({group of EVENTS: seconds, "total": the
run's -log_view time}: the first run's -log_view, wall seconds, the largest over ranks; an event's time includes the
events inside it)}. Values at full digits; the section's reading is computed from the rows.
"""
import math

from camclay9 import results_store

STORE = "indent_speed"
TITLE = "## Indentation speed: the contact solve and the physics"
# The last commit whose docs/performance.md had issue 25's before/after (this tree against revision 1baa50c).
ISSUE25_AT = "6e97f27"
THIS = "this tree"
# -log_view groups: {column: PETSc events summed}; the contact solve holds the factorisation, the triangular solves and
# the matrix-free products
EVENTS = {"contact solve": ["CC9 contact solve"], "factorisation": ["MatLUFactorNum", "MatLUFactorSym"],
          "triangular solves": ["MatSolve"], "matrix-free K products": ["CC9 tangent apply"],
          "assembly of K": ["CC9 Jacobian"], "residual + UMAT": ["CC9 residual+UMAT"], "contact terms": ["CC9 contact"]}
PROVENANCE = ("command", "date", "rev", "machine", "load", "repeats", "long", "umat_case")
KEYS = ("scene", "driver", "options", "kinematics", "order", "cells", "unknowns", "cpu", "cpu_runs", "wall_runs", "steps",
        "rejected", "stalled", "not_converged", "newton", "krylov", "factorisations", "umat_calls", "same_runs", "umat_ns", "ratio", "rss_mb",
        "outputs", "log_view")
OUTPUTS = ("load", "creep_depth", "final_depth", "final_stage")


def checked(store):
    """The store's rows, every key there; a ValueError naming the file and the missing key otherwise."""
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], PROVENANCE)
    results_store.require(STORE, "provenance.load", store["provenance"]["load"], ("start", "end"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
        results_store.require(STORE, f"rows[{i}].outputs", r["outputs"], OUTPUTS)
        results_store.require(STORE, f"rows[{i}].log_view", r["log_view"], (*EVENTS, "total"))
    if not any(r["driver"] == THIS for r in store["rows"]):
        raise ValueError(f"docs/results/{STORE}.json: no row of driver '{THIS}'")
    return store["rows"]


def several(rows):
    return len({r["driver"] for r in rows}) > 1


def name(r, both):
    """A row's first cell: the scene, and its driver where the store holds more than one."""
    return f"{r['scene']} ({r['driver']})" if both else r["scene"]


KINEMATICS = {"3d": "3D", "axisymmetric": "axisymmetric", "plane_strain": "plane strain"}


def model(r):
    return f"{KINEMATICS.get(r['kinematics'], r['kinematics'])}, P{r['order']}, {r['unknowns']:,}"


def cost_table(rows):
    both = several(rows)
    lines = ["| scene | model, unknowns | CPU [s] | runs' CPU [s] | ratio | steps | rejected (stalled, not converged) | "
             "Newton | Krylov | factorisations | UMAT calls | t_call [ns] |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        runs = ", ".join(f"{c:.2f}" for c in r["cpu_runs"])
        lines.append(f"| {name(r, both)} | {model(r)} | {r['cpu']:.2f} | {runs} | {r['ratio']:.2f} | {r['steps']} | "
                     f"{r['rejected']} ({r['stalled']}, {r['not_converged']}) | {r['newton']} | {r['krylov']} | {r['factorisations']} | {r['umat_calls']:,} | "
                     f"{r['umat_ns']:.1f} |")
    return lines


def sig(x, n=5):
    """At least n significant digits, without an exponent, thousands apart by a comma (1,059,684; 547.18; 0.13531)."""
    return f"{x:,.{max(0, n - 1 - math.floor(math.log10(abs(x))))}f}" if x else "0"


def outputs_table(rows):
    both = several(rows)
    lines = ["| scene | load at the end of loading [µN] | creep depth [nm] | final depth [µm] | at the end of |",
             "|---|---|---|---|---|"]
    for r in rows:
        o = r["outputs"]
        lines.append(f"| {name(r, both)} | {sig(o['load'])} | {sig(1e3 * o['creep_depth'])} | {sig(o['final_depth'])} | "
                     f"{o['final_stage']} |")
    return lines


def split_table(rows):
    both = several(rows)
    lines = ["| scene | -log_view total [s] | " + " | ".join(EVENTS) + " |", "|---|---|" + "---|" * len(EVENTS)]
    for r in rows:
        s = r["log_view"]
        lines.append(f"| {name(r, both)} | {s['total']:.1f} | "
                     + " | ".join(f"{s[k]:.1f} ({100 * s[k] / s['total']:.0f} %)" for k in EVENTS) + " |")
    return lines


def span(rows, value, fmt):
    """'a (scene) to b (scene)': the smallest and the largest of value(row) over rows."""
    lo, hi = min(rows, key=value), max(rows, key=value)
    return f"{fmt(value(lo))} ({lo['scene']}) to {fmt(value(hi))} ({hi['scene']})"


def reading(rows):
    """The reading's bullets, every number computed from the rows of this tree's driver."""
    t = [r for r in rows if r["driver"] == THIS]
    d3, d2 = [r for r in t if r["kinematics"] == "3d"], [r for r in t if r["kinematics"] != "3d"]
    share = lambda k: lambda r: r["log_view"][k] / r["log_view"]["total"]  # noqa: E731
    pct, x2 = (lambda v: f"{100 * v:.0f} %"), (lambda v: f"{v:.2f}")
    walls = [w / c for r in t for w, c in zip(r["wall_runs"], r["cpu_runs"])]
    stalls = ", ".join(f"{r['scene']} {r['stalled']}" for r in t if r["stalled"]) or "none"
    out = [f"- **The ratio to the physics** goes from {span(t, lambda r: r['ratio'], x2)}"
           + (f"; the 3D scenes {min(r['ratio'] for r in d3):.2f}–{max(r['ratio'] for r in d3):.2f}, the 2D ones "
              f"{min(r['ratio'] for r in d2):.2f}–{max(r['ratio'] for r in d2):.2f}" if d3 and d2 else "")
           + f"; t_call, measured under the same load, went from {span(t, lambda r: r['umat_ns'], lambda v: f'{v:.0f} ns')}.",
           f"- **Where the time goes** (share of the -log_view total): the residual with the UMAT calls "
           f"{span(t, share('residual + UMAT'), pct)}; the contact solve {span(t, share('contact solve'), pct)}, of which the "
           f"factorisation {span(t, share('factorisation'), pct)} and the triangular solves "
           f"{span(t, share('triangular solves'), pct)}.",
           f"- **The kept factorisation**: {span(t, lambda r: r['factorisations'] / r['newton'], x2)} factorisations per "
           f"Newton iteration, {span(t, lambda r: r['krylov'] / r['newton'], x2)} Krylov iterations per Newton iteration.",
           f"- **Rejected steps**: {span(t, lambda r: r['rejected'] / r['steps'], pct)} of the steps. Of the "
           f"{sum(r['rejected'] for r in t)} rejections, {sum(r['stalled'] for r in t)} are steps whose Newton stalled "
           f"(-indent_stall_window; {stalls}) and {sum(r['not_converged'] for r in t)} whose Newton ran to its limit; "
           "the others asked for by the error measure or the UMAT (PNEWDT < 1). loading_rate_a1's stalls are backward Euler's jumps where the soft "
           "frame's step outruns its softening (theory.md §3.4)."]
    rep = [r for r in t if len(r["cpu_runs"]) > 1]
    if rep:
        spread = lambda r: (max(r["cpu_runs"]) - min(r["cpu_runs"])) / r["cpu"]  # noqa: E731
        same = sum(r["same_runs"] for r in rep)
        out.append(f"- **The repeats**: the runs' CPU spreads by {span(rep, spread, pct)} of its median; "
                   + ("every repeated run gave the first run's counts and outputs." if same == len(rep) else
                      f"{len(rep) - same} of {len(rep)} repeated scenes gave other counts or outputs than their first run."))
    out.append(f"- **Wall against CPU**: the runs took {min(walls):.2f}–{max(walls):.2f}× their CPU in wall time.")
    return out + against(rows)


def against(rows):
    """A bullet per other driver (--against, --elementary): its CPU and outputs against this tree's, per scene."""
    mine = {r["scene"]: r for r in rows if r["driver"] == THIS}
    out = []
    for label in dict.fromkeys(r["driver"] for r in rows if r["driver"] != THIS):
        pairs = [(r, mine[r["scene"]]) for r in rows if r["driver"] == label and r["scene"] in mine]
        if not pairs:
            continue
        cpu = [r["cpu"] / m["cpu"] for r, m in pairs]
        dev = max(abs(r["outputs"][k] / m["outputs"][k] - 1) for r, m in pairs for k in OUTPUTS[:3] if m["outputs"][k])
        out.append(f"- **{label}** takes {min(cpu):.2f}–{max(cpu):.2f}× this tree's CPU; its outputs differ from this "
                   f"tree's by up to {dev:.1e} relative.")
    return out


def section(store, root=None):
    """The section's text: the command, the method, the tables, the reading computed from the rows. `root` is unused
    (the uniform call of tools/doc_numbers.py)."""
    rows, pv = checked(store), store["provenance"]
    ld = lambda v: ", ".join(f"{x:.2f}" for x in v)  # noqa: E731
    once = [r["scene"] for r in rows if r["driver"] == THIS and len(r["cpu_runs"]) == 1]
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; {pv['machine']}; the load averages over "
             f"1, 5 and 15 min were {ld(pv['load']['start'])} at the start and {ld(pv['load']['end'])} at the end).", "",
             "Each shipped indentation scene (`input/*.yaml`, unchanged) on one rank. CPU is user + system time of the driver "
             "and of the gmsh it starts to mesh the scene. "
             + (f"A scene whose first run took at most {pv['long']:g} s of CPU ran {pv['repeats']} times and its CPU is their "
                "median; a longer one ran once" + (f" ({', '.join(once)})" if once else "") if pv["repeats"] > 1 else
                "Each scene ran once") + ". The machine was shared, so wall time says little: compare "
             "CPU seconds. The ratio to the physics is CPU / (UMAT calls × t_call), t_call the UMAT benchmark's median time "
             f"per call ({pv['umat_case']}; `build/bench/umat_bench`), measured just before the scene's runs. The counts "
             "and outputs are the first run's; the time split is that run's -log_view (wall seconds; an event's time "
             "includes the events inside it: the contact solve holds the factorisation, the triangular solves and the "
             "matrix-free products).", "",
             f"Issue 25's before/after (this tree against revision 1baa50c, the 2D scenes then on P1) is in git history: "
             f"docs/performance.md at {ISSUE25_AT}.", ""]
    lines += cost_table(rows) + [""]
    lines += ["Outputs, as the runs' summary.json reports them: the load at the end of loading, the creep depth (the hold's change of "
              "depth) and the depth at the end of the last stage: the residual depth where the scene unloads, the depth at "
              "the end of the hold where it does not (the 2D plane-strain scenes).", ""] + outputs_table(rows) + [""]
    lines += ["Where the time goes (-log_view of the first run: seconds, and the share of the total):", ""]
    lines += split_table(rows) + [""] + reading(rows)
    return "\n".join(lines) + "\n"
