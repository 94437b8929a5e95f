#!/usr/bin/env python3
"""Figs. 9 and 11 of docs/paper.md measured with percentiles by area and by cell count, on the loading-rate scenes as
the reproduction runs them (their meshes adapted by rerun) and on the uniform fine zone they shipped before
(camclay9.paper_measures_study says why). Keeps every number in docs/results/paper_measures.json and writes the
section "Figs. 9 and 11: percentiles by area, not by cell count" of docs/performance.md from it.

    bench/paper_measures_bench.py [--paper out/paper] [--out out/paper_measures] [--jobs 2] [--machine NOTE] [--no-doc]

--paper: the full reproduction's output (tools/reproduce.sh: its runs of loading_rate_a*, and the scene variants it
ran, PAPER/scenes/loading_rate_a*.yaml). The uniform runs: those variants with the uniform zone's mesh and no
mesh.adapt, run here into OUT (kept: a later call reuses a completed run).
"""
import argparse
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import yaml
from camclay9 import driver_command, read_summary, run_command
from camclay9 import paper_fields
from camclay9 import paper_measures_study as study
from camclay9.indent2d_study import SHIPPED
from camclay9.paper_doc_2d import fig9, fig11
from camclay9.performance_doc import publish
from camclay9.results_store import revision

ROOT = Path(__file__).resolve().parents[1]
ALPHAS = ("0.1", "1", "10")
UNIFORM = {"h_tip": SHIPPED["lr"][2], "h_far": 0.106}   # the fine zone the loading-rate scenes shipped until 2026-12-02 (r_fine 0.9)


def uniform_run(paper, out, alpha):
    """The reproduction's variant of loading_rate_a<alpha> on the uniform zone, run into OUT/loading_rate_a<alpha>."""
    run = out / f"loading_rate_a{alpha}"
    if (run / "summary.json").is_file() and read_summary(run)["completed"]:
        return run
    d = yaml.safe_load((paper / "scenes" / f"loading_rate_a{alpha}.yaml").read_text())
    d["mesh"].pop("adapt", None)
    d["mesh"]["parameters"].update(UNIFORM)
    scene = out / f"loading_rate_a{alpha}.yaml"
    scene.write_text(yaml.safe_dump(d, sort_keys=False))
    print(f"run: {scene.name} (uniform zone) into {run}", flush=True)
    run_command(driver_command(scene, run, root=ROOT), timeout=7200, cwd=out)
    return run


def measure(run, alpha, mesh, weight):
    """One row of the store: Figs. 9 and 11 of a run, with the percentiles by `weight`."""
    by = paper_fields.count_percentile if weight == "count" else paper_fields.area_percentile
    r = paper_fields.loading_rate_numbers(run, percentile=by)
    f9 = {k: r[k] for k in ("dev_p99", "tr_p99", "dev_frac", "tr_frac")}
    f9["verdict"] = bool(fig9({alpha: f9}))
    z = {t: {k: r["fig11"][t][k] for k in ("surface", "middle", "beneath", "fill")} for t in study.TIMES}
    for t in study.TIMES:
        z[t]["verdict"] = bool(fig11(alpha, r["fig11"][t]))
    return {"alpha": alpha, "mesh": mesh, "weight": weight, "unknowns": read_summary(run)["mesh"]["unknowns"],
            "fig9": f9, "fig11": z}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--paper", default=str(ROOT / "out" / "paper"), help="the full reproduction's output (default: %(default)s)")
    ap.add_argument("--out", default=str(ROOT / "out" / "paper_measures"), help="the uniform runs' folders (default: %(default)s)")
    ap.add_argument("--jobs", type=int, default=2, help="runs at once (default: %(default)s)")
    ap.add_argument("--machine", default="2 cores")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args(argv)
    paper, out = Path(a.paper).resolve(), Path(a.out).resolve()
    missing = [al for al in ALPHAS if not (paper / f"loading_rate_a{al}" / "fields.h5").is_file()
               or not (paper / "scenes" / f"loading_rate_a{al}.yaml").is_file()]
    if missing:
        raise SystemExit(f"{paper}: no run or scene of loading_rate_a{', '.join(missing)}: run tools/reproduce.sh first")
    out.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(a.jobs) as pool:
        uniform = dict(zip(ALPHAS, pool.map(lambda al: uniform_run(paper, out, al), ALPHAS)))
    rows = [measure(run, al, mesh, w) for al in ALPHAS
            for mesh, run in (("uniform", uniform[al]), ("adapted", paper / f"loading_rate_a{al}")) for w in study.WEIGHTS]
    cmd = "bench/paper_measures_bench.py" + (f" --paper {a.paper}" if Path(a.paper).resolve() != ROOT / "out" / "paper" else "")
    store = {"provenance": {"command": cmd, "date": time.strftime("%Y-%m-%d", time.gmtime()),
                            "rev": revision(ROOT) or "unknown", "machine": a.machine}, "rows": rows}
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)


if __name__ == "__main__":
    main()
