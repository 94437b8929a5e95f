#!/usr/bin/env python3
"""BLAS kernels (camclay9.blas, tools/blas_core.py): the same scenes under OpenBLAS' own pick of kernels and under the cores named by
OPENBLAS_CORETYPE, the runs alternating, one at a time. Keeps every number in docs/results/blas_kernels.json
(camclay9.blas_kernels_study) and writes the section "BLAS kernels" of docs/performance.md from it.

    bench/blas_kernels_bench.py [--repeats 3] [--cores Haswell,SkylakeX] [--out out/blas_kernels] [--machine NOTE]
                                [--no-doc]

Cases: sector0.0707, the kerogen sector (nanoindent_kerogen_sector.yaml) at h_tip 0.07071 um (about 20 k unknowns), its
first 30 steps, where MUMPS' factorisations dominate; sector, the shipped kerogen sector whole (5 882 unknowns);
lr1, loading_rate_a1's first mesh (2D, UMFPACK), whole, without its rerun (-adapt_levels 0)."""
import argparse
import re
import time
from pathlib import Path

from camclay9 import driver_command, mesh_line, read_history, run_measured, summary_line
from camclay9 import blas_kernels_study as study
from camclay9.blas import openblas_core
from camclay9.performance_doc import publish
from camclay9.results_store import revision

ROOT = Path(__file__).resolve().parents[1]
INPUT = ROOT / "input"
CASES = {
    "sector0.0707": ("the kerogen sector at h_tip 0.0707 µm, its first 30 steps", "nanoindent_kerogen_sector.yaml",
                     {"h_tip: 0.12,": "h_tip: 0.07071,"}, ["-max_steps", "30"]),
    "sector": ("the kerogen sector as shipped, whole", "nanoindent_kerogen_sector.yaml", {}, []),
    "lr1": ("loading_rate_a1's first mesh (2D), whole", "loading_rate_a1.yaml", {}, ["-adapt_levels", "0"]),
}


def scene(case, out):
    _, name, repl, _ = CASES[case]
    text = (INPUT / name).read_text().replace("../meshes/", f"{ROOT}/meshes/")
    for a, b in repl.items():
        assert a in text, f"{case}: '{a}' not in {name}"
        text = text.replace(a, b)
    path = out / f"{case}.yaml"
    path.write_text(text)
    return path


def event_seconds(log, event):
    """The seconds of a -log_view event (its time column) in the driver's log; 0 where it did not occur."""
    m = re.search(rf"^{event}\s+\d+\s+[\d.]+\s+([\d.eE+-]+)", log, re.M)
    return float(m.group(1)) if m else 0.0


def one(case, core, k, out):
    """One run of a case under a core (None: OpenBLAS' own pick): its CPU, factorisation and solve seconds, outputs."""
    run = out / f"{case}_{core or 'default'}_{k}"
    prefix = ["env", f"OPENBLAS_CORETYPE={core}"] if core else ["env", "-u", "OPENBLAS_CORETYPE"]
    log = out / f"{run.name}.log"
    rc, cpu, _, _ = run_measured(driver_command(scene(case, out), run, options=[*CASES[case][3], "-log_view"], root=ROOT,
                                                prefix=prefix), log, timeout=3600, cwd=out)
    text = log.read_text()
    if rc not in (0, 3):   # 3: stopped by -max_steps, as asked
        raise SystemExit(f"{case} ({core or 'default'}): the driver failed ({rc}):\n{text[-2000:]}")
    last = read_history(run)[-1]
    return {"cpu": cpu, "factor": event_seconds(text, "MatLUFactorNum"), "solve": event_seconds(text, "MatSolve"),
            "steps": summary_line(text, index=0)["steps"], "unknowns": mesh_line(text)["unknowns"],
            "outputs": {"depth": float(last["depth"]), "load": float(last["load"])}}


def cpu_model():
    info = Path("/proc/cpuinfo").read_text()
    get = lambda key: re.search(rf"^{key}\s*:\s*(.*)$", info, re.M).group(1).strip()
    return f"{get('model name')}, family {get('cpu family')} model {get('model')}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cores", default="Haswell,SkylakeX", help="the cores named by OPENBLAS_CORETYPE, beside OpenBLAS' own pick")
    ap.add_argument("--cases", default=",".join(CASES))
    ap.add_argument("--out", default="out/blas_kernels")
    ap.add_argument("--machine", default="a 2-core machine, one run at a time")
    ap.add_argument("--no-doc", action="store_true")
    a = ap.parse_args()
    out = Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    cores = [None, *a.cores.split(",")]
    runs = {}
    for k in range(a.repeats):
        for case in a.cases.split(","):
            for core in cores:   # alternating: a machine that slows or speeds up over the bench moves every core alike
                r = one(case, core, k, out)
                runs.setdefault((case, core), []).append(r)
                print(f"{case} {core or 'default'} #{k}: CPU {r['cpu']:.1f} s, factorisations {r['factor']:.2f} s, "
                      f"solves {r['solve']:.2f} s", flush=True)
    rows = []
    for (case, core), rs in runs.items():
        rows.append({"case": case, "what": CASES[case][0], "coretype": core or "default", "unknowns": rs[0]["unknowns"],
                     "steps": rs[0]["steps"], "cpu_s": [r["cpu"] for r in rs], "factor_s": [r["factor"] for r in rs],
                     "solve_s": [r["solve"] for r in rs], "outputs": rs[0]["outputs"]})
    store = {"provenance": {"command": f"bench/blas_kernels_bench.py --repeats {a.repeats} --cores {a.cores}",
                            "date": time.strftime("%Y-%m-%d", time.gmtime()), "rev": revision(ROOT), "machine": a.machine},
             "cpu_model": cpu_model(), "openblas_core": openblas_core() or "not OpenBLAS", "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
