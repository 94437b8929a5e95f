"""The section "FE solver: the triaxial main job" of docs/performance.md (issue 13), written from its results store
docs/results/fe_main_job.json by `bench/fe_solver_bench.py --main-job` and checked against it by tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "rev" (the driver's commit), "load" (the machine's 1-minute load average
at the start and the end)}, "rows": [...]}, one row per set-up in the bench's order (the set-up before issue 13 first,
the reference of the last column), each {"setup", "options", "steps", "newton", "krylov", "setups", "wall" and "cpu" (the
stepping's wall clock and the slowest rank's CPU [s], medians of the repeats), "creep_1h", "creep_10h" (the axial creep
strain 1 h and 10 h into the creep stage)}. Values at full digits; the reading is computed from the rows.
"""
from camclay9 import results_store

STORE = "fe_main_job"
TITLE = "## FE solver: the triaxial main job"
KEYS = ("setup", "options", "steps", "newton", "krylov", "setups", "wall", "cpu", "creep_1h", "creep_10h")


def checked(store):
    results_store.require(STORE, "the store", store, ("provenance", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "load"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, KEYS)
    if len(store["rows"]) != 2:
        raise ValueError(f"docs/results/{STORE}.json: {len(store['rows'])} rows (expected 2: the old set-up, the new default)")
    return store["rows"]


def section(store, root=None):
    """The section's text: the command, one row per set-up, the reading computed from the rows. `root` is unused (the
    uniform call of tools/doc_numbers.py)."""
    (old, new), pv = checked(store), store["provenance"]
    diff = abs(new["creep_10h"] - old["creep_10h"]) / abs(old["creep_10h"])
    same = old["steps"] == new["steps"] and old["newton"] == new["newton"]
    cpu, wall = 1 - new["cpu"] / old["cpu"], 1 - new["wall"] / old["wall"]
    lines = [TITLE, "", f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; the machine's load average "
             f"{pv['load'][0]:.1f} at the start and {pv['load'][1]:.1f} at the end, on 2 cores). `input/triaxial.yaml` on 2 ranks "
             "as `tools/run.sh` runs it (hold to steady state, then 10 h of creep), the set-up before issue 13 "
             f"(`{old['options']}`) against the default, interleaved, medians of the repeats. Wall and CPU of the stepping "
             "(CPU: the slowest rank's).", "",
             "| set-up | steps | Newton its | Krylov its | set-ups | wall [s] | CPU [s] | creep 1 h | creep 10 h | "
             "rel. difference 10 h |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in (old, new):
        d = abs(r["creep_10h"] - old["creep_10h"]) / abs(old["creep_10h"])
        lines.append(f"| {r['setup']} | {r['steps']} | {r['newton']} | {r['krylov']} | {r['setups']} | {r['wall']:.2f} | "
                     f"{r['cpu']:.2f} | {r['creep_1h']:.10e} | {r['creep_10h']:.10e} | {d:.1e} |")
    agree = "bit for bit" if diff == 0 else f"to {diff:.0e} relative"
    lines += ["", f"- **The creep is {'unchanged' if diff < 1e-10 else 'changed'}.** The two agree {agree} at "
              f"10 h{', with the same steps and Newton iterations' if same else ''}.",
              f"- **The default needs {new['setups']} factorisations instead of {old['setups']}** and takes "
              f"{abs(cpu) * 100:.0f} % {'less' if cpu >= 0 else 'more'} CPU and {abs(wall) * 100:.0f} % "
              f"{'less' if wall >= 0 else 'more'} wall. On these 713 tetrahedra the factorisation is small and the "
              "residual's UMAT calls dominate either way; MPI's busy waiting counts as CPU on 2 ranks."]
    return "\n".join(lines) + "\n"
