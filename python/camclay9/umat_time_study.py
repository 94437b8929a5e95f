"""The section "UMAT: time per call" of docs/performance.md (issue #2), written from its results store
docs/results/umat_time.json by bench/run_umat_bench.sh (through bench/umat_time_store.py) and checked against it by
tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "machine", "compiler", ...}, "calls", "repetitions", "against" (the git
revision measured as "before", or null), "builds": [label, ...] in the table's order, "rows": [...],
"instructions": [...] (null without valgrind), "accuracy": [[group, largest relative difference as the test printed
it], ...], "earlier": {...}}. Each row {"case", "ntens", build: {"median", "min", "max" [ns per call over the
repetitions], "iterations" (the benchmark's median local iterations)}}; each instructions row {"case", build:
instructions per call}. "earlier": the host file's cost before the closed-form pencil, from an earlier run (its
"rev", "material_us", "host_vp_ns", "host_elastic_ns"), which the reading quotes.
"""
import textwrap

from camclay9 import results_store

STORE = "umat_time"
TITLE = "## UMAT: time per call"
BUILDS = ("before_lib", "after_lib", "before_host", "after_host", "after_nocache")
NAMES = {"before_lib": "library before", "after_lib": "library", "before_host": "host file before",
         "after_host": "host file", "after_nocache": "library without cache"}

SETUP = """Three builds of the same routine. *Library*: `libcamclay9.a` as the driver and C hosts link it
(`-O3 -funroll-loops`, the default Release build): each thread keeps the material of the last PROPS it
saw (ccix_material_cache, compiled with OpenMP into thread-local storage), as does `camclay9_umat.o`.
*Host file*: `camclay9_umat.f90` compiled with a host's plain line (`gfortran -O2 -fPIC`, no
OpenMP flag; docs/umat.md, "Cost of each build route", for other flags): it keeps no module state, so
that no host flag can make threads share it, and derives the material from PROPS in every call. *Library without cache*: the same file compiled with the
library's flags, the library as it would be without its cache."""

CASES = """Each case starts every call from the same state and cycles through 64 strain increments of
~1e-5 (elastic: ~1e-6): *elastic*, both frames inside their surfaces (pc = 60 MPa at -35 MPa);
*viscoplastic*, the paper's start (hard frame far outside with pc0 = 2 MPa, soft frame on its
surface), Woodford viscosities, dt = 10 s; *rate-independent*, eta = 0 in both frames. Plane strain
is NTENS = 4 with the normal in the 1-2 plane. Local iterations are Newton updates of the worse frame."""

INSTRUCTIONS = """Instructions per call (valgrind callgrind, `bench/instructions_per_call.sh`; deterministic, the
same whatever else the machine is doing; mean of NTENS 6 and 4; elastic / vp / ri as above):"""

GOALS = "Goals of issue #2: <= 1 us per viscoplastic call and <= 0.1 us per elastic call (library)."


def checked(store):
    """The store's builds, each known and measured in every row; a clear message naming what is missing otherwise."""
    builds = store.get("builds") or []
    unknown = [b for b in builds if b not in BUILDS]
    needed = ("after_lib", "after_host", "after_nocache") + (("before_lib", "before_host") if store.get("against") else ())
    if unknown or any(b not in builds for b in needed):
        raise ValueError(f"docs/results/{STORE}.json: builds {builds!r} (expected {', '.join(needed)}, in any order)")
    for i, row in enumerate(store["rows"]):
        results_store.require(STORE, f"rows[{i}]", row, ("case", "ntens", *builds))
    return builds


def median(store, build, case, ntens=6):
    """The median ns per call of a build on the case whose name starts with `case`, NTENS 6 (the reading's figures)."""
    return next(r[build]["median"] for r in store["rows"] if r["case"].startswith(case) and r["ntens"] == ntens)


def pct(store, build, base, case):
    """The build's time over the base build's on the case, as the reading gives it: '+4 %'."""
    return f"{100 * (median(store, build, case) / median(store, base, case) - 1):+.0f} %"


def time_table(store, builds):
    def cell(t):
        return f"{t['median']:.0f} ({t['min']:.1f} - {t['max']:.1f})"
    if store["against"]:
        head = ["| case | NTENS | library before | library after | change | host file before | host file after | change | "
                "library without cache | no cache / library | local iterations |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    else:
        head = ["| case | NTENS | library | host file | library without cache | no cache / library | local iterations |",
                "|---|---|---|---|---|---|---|"]
    lines = []
    for r in store["rows"]:
        lib, host, nocache = r["after_lib"], r["after_host"], r["after_nocache"]
        cells = [cell(lib), cell(host)]
        if store["against"]:
            bl, bh = r["before_lib"], r["before_host"]
            cells = [cell(bl), cell(lib), f"{100 * (lib['median'] / bl['median'] - 1):+.1f} %",
                     cell(bh), cell(host), f"{100 * (host['median'] / bh['median'] - 1):+.1f} %"]
        lines.append(f"| {r['case']} | {r['ntens']} | {' | '.join(cells)} | {cell(nocache)} | "
                     f"{nocache['median'] / lib['median']:.2f} | {r[builds[0]]['iterations']:.1f} |")
    return head + lines


def instructions_table(store, builds):
    if not store.get("instructions"):
        return ["(valgrind not installed: no instruction counts)"]
    names = dict(NAMES, **({"after_lib": "library after", "after_host": "host file after"} if store["against"] else {}))
    lines = ["| case | " + " | ".join(names[b] for b in builds) + " |", "|---|" + "---|" * len(builds)]
    return lines + [f"| {r['case']} | " + " | ".join(str(r[b]) for b in builds) + " |" for r in store["instructions"]]


def meaning(store):
    """The reading: what the host file derives in every call, then the run's figures (NTENS 6 medians)."""
    e = store["earlier"]
    lines = ["**What it means.** A host file derives its material in every call: the checks of PROPS, the bedding",
             "normal and Walpole's basis of it, the Walpole coefficients of both frames (ccix_walpole), and, only in",
             "a step that yields, the closed-form diagonalisation of the frame's pencil (H, C^-1) (ccix_pencil). This",
             f"replaced a 6 x 6 Cholesky, Jacobi and inverses that cost {e['material_us']} us per material (`{e['rev']}`: "
             f"{e['host_vp_ns']} ns"]
    nocache = (f"Without its cache the library would take {pct(store, 'after_nocache', 'after_lib', 'viscoplastic')}",
               f"per viscoplastic and {pct(store, 'after_nocache', 'after_lib', 'elastic')} per elastic call (NTENS 6, "
               "medians above), so it keeps the cache. The")
    if store["against"]:
        lines += [f"per viscoplastic and {e['host_elastic_ns']} ns per elastic call in the host file). Against "
                  f"`{store['against']}`, the host file",
                  f"takes {pct(store, 'after_host', 'before_host', 'viscoplastic')} per viscoplastic and "
                  f"{pct(store, 'after_host', 'before_host', 'elastic')} per elastic call (its material was kept in module "
                  "variables,",
                  f"shared by threads), the library {pct(store, 'after_lib', 'before_lib', 'viscoplastic')} and "
                  f"{pct(store, 'after_lib', 'before_lib', 'elastic')}. {nocache[0]}", nocache[1]]
    else:
        lines += [f"per viscoplastic and {e['host_elastic_ns']} ns per elastic call in the host file). {nocache[0]}", nocache[1]]
    return lines + ["library's cache now also holds what a call would otherwise derive on demand (both frames' pencils",
                    "and stiffness matrices, Cbar's DDSDDE: `material_prepare`), computed by the same routines: library,",
                    "object and host files give the same numbers bit for bit (`umat.host_against_jacobi`)."]


def accuracy(store):
    groups = ", ".join(f"{g} {v}" for g, v in store["accuracy"])
    return textwrap.fill(
        "Accuracy, measured in the same run: the host file against the UMAT with the Jacobi derivation "
        f"(`{store['earlier']['rev']}`, numbers stored in tests/umat/data/jacobi_reference.txt; 64 calls, phi 0, 0.5, 1, NTENS 4 and 6, inclined "
        f"normals; largest difference relative to each group): {groups}.", width=100, break_on_hyphens=False)


def section(store, root=None):
    """The section's text: the command, what is measured, the times, the instructions, the reading, the accuracy.
    `root` is unused (the reading is written here, its figures from the store); it is there for tools/doc_numbers.py's
    uniform call."""
    pv, builds = store["provenance"], checked(store)
    n, reps = store["calls"], store["repetitions"]
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({reps} repetitions of",
             f"{n} calls per case and build; the builds take turns, one repetition each; CPU time (`cpu_time`),",
             f"median and range of the per-call time in ns over the repetitions). Machine: {pv['machine']}, shared",
             f"with other jobs. Compiler: {pv['compiler']}. Measured {pv['date']}.", "", SETUP]
    if store["against"]:
        lines.append(f"*Before*: the UMAT of revision `{store['against']}`, built and measured by the same script "
                     f"(`--against {store['against']}`).")
    lines += ["", CASES, "", *time_table(store, builds), "", INSTRUCTIONS, "", *instructions_table(store, builds), "",
              *meaning(store), "", accuracy(store), "", GOALS]
    return "\n".join(lines) + "\n"
