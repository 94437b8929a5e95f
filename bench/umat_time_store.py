#!/usr/bin/env python3
"""The results store of bench/run_umat_bench.sh: its runs' per-call times, instruction counts and accuracy into
docs/results/umat_time.json, then the section "UMAT: time per call" of docs/performance.md written from it
(camclay9.umat_time_study, which tools/doc_numbers.py checks). Called by the script:

    bench/umat_time_store.py WORK --labels L1,L2,.. --calls N --repetitions R [--against REV] --command C
                             --machine M --compiler F [--no-doc]

WORK holds LABEL.runs (one line per case and repetition: "case|NTENS|ns per call|local iterations"), instructions.txt
("LABEL kind instructions per call", absent without valgrind) and accuracy.txt (test_against_jacobi check's group
lines: the group, then its largest relative difference).
"""
import argparse
import statistics
import time
from pathlib import Path

from camclay9 import results_store
from camclay9 import umat_time_study as study
from camclay9.performance_doc import replace_section

# The host file's cost before the closed-form pencil: measured by this script at a309f2a, quoted by the reading since.
EARLIER = {"rev": "a309f2a", "material_us": "4.4-4.7", "host_vp_ns": 5698, "host_elastic_ns": 4570,
           "note": "measured by bench/run_umat_bench.sh at a309f2a (not rerun): the cost the closed-form pencil replaced"}


def times(path):
    """[{"case", "ntens", "median", "min", "max", "iterations"}] of one build's runs, in the benchmark's order."""
    runs = {}
    for n, line in enumerate(path.read_text().splitlines(), 1):
        parts = line.split("|")
        if len(parts) != 4:
            raise SystemExit(f"{path}:{n}: '{line}' (expected case|NTENS|ns per call|iterations)")
        t, it = runs.setdefault((parts[0], int(parts[1])), ([], []))
        t.append(float(parts[2]))
        it.append(float(parts[3]))
    return [{"case": c, "ntens": k, "median": statistics.median(t), "min": min(t), "max": max(t),
             "iterations": statistics.median(it)} for (c, k), (t, it) in runs.items()]


def rows(work, labels):
    """One row per case and NTENS, each build's times under its label."""
    per = {label: times(work / f"{label}.runs") for label in labels}
    out = []
    for i, first in enumerate(per[labels[0]]):
        row = {"case": first["case"], "ntens": first["ntens"]}
        for label in labels:
            r = per[label][i]
            if (r["case"], r["ntens"]) != (row["case"], row["ntens"]):
                raise SystemExit(f"{work}/{label}.runs: row {i} is {r['case']}, {r['ntens']} (expected {row['case']}, "
                                 f"{row['ntens']}: the builds run the same cases)")
            row[label] = {k: r[k] for k in ("median", "min", "max", "iterations")}
        out.append(row)
    return out


def instructions(path, labels):
    """[{"case": kind, label: instructions per call}] or None (no valgrind: no file)."""
    if not path.is_file():
        return None
    out = {}
    for line in path.read_text().split("\n"):
        if line.strip():
            label, kind, n = line.split()
            out.setdefault(kind, {"case": kind})[label] = int(n)
    return list(out.values())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("work", type=Path)
    for opt in ("--labels", "--command", "--machine", "--compiler"):
        ap.add_argument(opt, required=True)
    ap.add_argument("--calls", type=int, required=True)
    ap.add_argument("--repetitions", type=int, required=True)
    ap.add_argument("--against", default="")
    ap.add_argument("--no-doc", action="store_true", help="print the section; write neither the store nor the document")
    a = ap.parse_args()
    labels = a.labels.split(",")
    accuracy = [line.rsplit(None, 1) for line in (a.work / "accuracy.txt").read_text().splitlines() if line.strip()]
    store = {"provenance": {"command": a.command, "date": time.strftime("%Y-%m-%d", time.gmtime()),
                            "machine": a.machine, "compiler": a.compiler},
             "calls": a.calls, "repetitions": a.repetitions, "against": a.against or None, "builds": labels,
             "rows": rows(a.work, labels), "instructions": instructions(a.work / "instructions.txt", labels),
             "accuracy": [[g.strip(), v] for g, v in accuracy], "earlier": EARLIER}
    text = study.section(store)   # the section from the store's numbers, as tools/doc_numbers.py checks it
    print(text)
    if not a.no_doc:
        replace_section(study.TITLE, text)
        results_store.save(study.STORE, store)
        print(f"written: docs/performance.md, docs/results/{study.STORE}.json")


if __name__ == "__main__":
    main()
