"""The section "BLAS kernels: OpenBLAS' own pick and the cores named" of docs/performance.md, written from its
results store docs/results/blas_kernels.json by bench/blas_kernels_bench.py and checked against it by
tools/doc_numbers.py.

The 3D contact solve factors its matrix with MUMPS, whose dense frontal kernels are the BLAS's (Debian's
libblas.so.3: OpenBLAS, tools/setup.sh). Debian builds OpenBLAS with DYNAMIC_ARCH: it picks its kernels by the CPU
when it is loaded, and the variable OPENBLAS_CORETYPE names the core to use instead (OpenBLAS' README, "Support for
multiple targets in a single library"). A CPU newer than the library is not recognised, and it falls back to a core
without AVX2 (camclay9.blas): on the 2-core machines of 2026-12-02 (an Intel Xeon of family 6, model 207) to its SSE3
kernels ("Prescott"), though it has kernels for their AVX-512 and AVX2. The bench runs the same scenes under OpenBLAS' own pick and under the cores named
(Haswell: AVX2; SkylakeX: AVX-512), the runs alternating, and checks that the answers agree. tools/blas_core.py names
the core where OpenBLAS fell back; tools/reproduce.sh uses it.

The store: {"provenance": {"command", "date", "rev", "machine"}, "cpu_model", "openblas_core" (OpenBLAS' own pick on
this machine), "rows": [...]}, each row {"case", "what", "coretype" ("default": OpenBLAS' own pick, or the core named),
"unknowns", "steps", "cpu_s" (the repeats' CPU seconds: user + system of the driver), "factor_s" and "solve_s" (the
repeats' seconds in the factorisations (MatLUFactorNum) and the triangular solves (MatSolve), -log_view),
"outputs" {"depth", "load"} (the last step's)}.
"""
import statistics

from camclay9 import results_store
from camclay9.blas import FALLBACKS

STORE = "blas_kernels"
TITLE = "## BLAS kernels: OpenBLAS' own pick and the cores named"
ROW_KEYS = ("case", "what", "coretype", "unknowns", "steps", "cpu_s", "factor_s", "solve_s", "outputs")


def checked(store):
    """The store's rows, its keys checked (a ValueError naming the file and what is wrong)."""
    results_store.require(STORE, "the store", store, ("provenance", "cpu_model", "openblas_core", "rows"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    for i, r in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", r, ROW_KEYS)
    return store["rows"]


def med(values):
    return statistics.median(values)


def by_core(store, case):
    """{coretype: row} of a case."""
    return {r["coretype"]: r for r in checked(store) if r["case"] == case}


def ratio(a, b):
    """The medians' ratio a / b as text ("—" where b's is 0: no such event, e.g. no factorisation in 2D's log)."""
    return f"{med(a) / med(b):.2f}×" if med(b) > 0 else "—"


def agreement(a, b):
    """The largest relative difference of the two rows' outputs."""
    return max(abs(a["outputs"][k] / b["outputs"][k] - 1) for k in ("depth", "load") if b["outputs"][k])


def section(store, root=None):
    """The section's text. `root` is unused; it is there for tools/doc_numbers.py's uniform call."""
    pv = store["provenance"]
    rows = checked(store)
    n = len(rows[0]["cpu_s"]) if rows else 0
    core = store["openblas_core"]
    fallback = ": a fallback, OpenBLAS not recognising the CPU (tools/blas_core.py)" if core in FALLBACKS else ""
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}, the driver at {pv['rev']}; {pv['machine']}; CPU: {store['cpu_model']}, "
             f"OpenBLAS' own pick {core}{fallback}). "
             "Each case run {n} times under OpenBLAS' own kernels "
             "(*default*) and {n} times under each core named by `OPENBLAS_CORETYPE` (Haswell: AVX2; SkylakeX: AVX-512), "
             "the runs alternating, one at a time; "
             "medians of CPU (user + system of the driver), and of the seconds in the direct solver's factorisations and "
             "triangular solves (MUMPS in 3D, UMFPACK in 2D; `-log_view`: MatLUFactorNum, MatSolve). The answers: the "
             "depth and load at the last step.".format(n=n), "",
             "| case | what | kernels | unknowns | steps | CPU [s] | factorisations [s] | solves [s] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['case']} | {r['what']} | {r['coretype']} | {r['unknowns']} | {r['steps']} | "
                     f"{med(r['cpu_s']):.1f} | {med(r['factor_s']):.2f} | {med(r['solve_s']):.2f} |")
    lines.append("")
    for case in dict.fromkeys(r["case"] for r in rows):
        rs = by_core(store, case)
        a = rs.get("default")
        for core, b in rs.items():
            if a and core != "default":
                lines.append(f"- **{case}**, {core} against OpenBLAS' pick: CPU {med(a['cpu_s']):.1f} s against "
                             f"{med(b['cpu_s']):.1f} s ({med(a['cpu_s']) / med(b['cpu_s']):.2f}×); the factorisations "
                             f"{ratio(a['factor_s'], b['factor_s'])} as long, the solves {ratio(a['solve_s'], b['solve_s'])}; "
                             f"the answers agree to {agreement(a, b):.1e}.")
    return "\n".join(lines) + "\n"
