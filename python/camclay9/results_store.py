"""The results store: the numbers that README.md and docs/*.md quote from runs, as JSON files in docs/results/
(committed: the documents show them). Each file is written by the generator or bench that made its numbers
(tools/reproduce.py: paper.json; bench/indent2d_convergence_bench.py --doc: indent2d_convergence.json; ...), and
the documents are written from it: docs/paper.md and the generated sections of docs/performance.md by their
generators, the numbers quoted in README.md and in the hand-written readings by tools/doc_numbers.py --write from
the quotes of camclay9.doc_quotes. tools/doc_numbers.py (CTest docs.numbers) fails when a document's number
differs from the store.

A file holds {"provenance": {...}, ...}: where its numbers come from (command, date, and for numbers taken over
from an earlier document rather than from a run, which and to what digits).
"""
import json
import statistics
import subprocess
from pathlib import Path

from camclay9.launch import repo_root


def store_dir(store=None):
    """The store's folder: `store`, or (None) docs/results of the repository (camclay9.repo_root: the one of the
    script being run, else of the current directory, as camclay9 finds the driver)."""
    return Path(store) if store is not None else repo_root() / "docs" / "results"


def revision(root=None):
    """The repository's commit (short hash) for a store's provenance: what the bench's tree was, with "+changes" when
    its tracked files differ from that commit (the run's code is then not the commit's); "" outside git."""
    cwd = root or repo_root()
    out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=cwd, capture_output=True, text=True, timeout=60)
    rev = out.stdout.strip()
    if rev and subprocess.run(["git", "diff", "--quiet", "HEAD", "--"], cwd=cwd, timeout=60).returncode == 1:
        rev += "+changes"
    return rev


def path(name, store=None):
    return store_dir(store) / f"{name}.json"


def load(name, store=None):
    """The store file `name` (docs/results/<name>.json) as a dict; {} if it does not exist."""
    p = path(name, store)
    return json.loads(p.read_text(encoding="utf-8")) if p.is_file() else {}


def save(name, data, store=None):
    """Write the store file `name`, one value a line, so that a change shows as a small diff (keys in the order the
    generator made them: the documents list some of them in that order)."""
    p = path(name, store)
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(json.dumps(data, indent=1, default=float, ensure_ascii=False) + "\n", encoding="utf-8")
    return p


def int_keys(d):
    """JSON keeps dict keys as strings: the triaxial theta keys back to ints (0, 90) where they were ints."""
    return {int(k) if isinstance(k, str) and k.lstrip("-").isdigit() else k: v for k, v in d.items()}


def require(name, where, d, keys):
    """Check that the part `where` of store file `name` (the dict d) has every key of `keys`; a ValueError naming the
    file, the part, the missing keys and those expected otherwise (a store written before a key was added)."""
    missing = [k for k in keys if not isinstance(d, dict) or k not in d]
    if missing:
        raise ValueError(f"docs/results/{name}.json: {where} lacks {', '.join(missing)} (expected {', '.join(keys)})")


def variant_rows(name, store, row_keys, variants, top=("provenance", "rows")):
    """The rows of a store of repeated runs by variant (a bench built on indent_convergence_bench.repeated), checked:
    the store's top keys, its provenance's (command, date, rev, machine), each row's keys and a variant of
    `variants`; a ValueError naming the file and what is wrong."""
    require(name, "the store", store, top)
    require(name, "provenance", store["provenance"], ("command", "date", "rev", "machine"))
    for i, r in enumerate(store["rows"]):
        require(name, f"rows[{i}]", r, row_keys)
        if r["variant"] not in variants:
            raise ValueError(f"docs/results/{name}.json: rows[{i}]: variant {r['variant']!r}, expected one of {variants}")
    return store["rows"]


def median_cpu(row):
    """A repeated run's median CPU over its repeats (its cpu_s) [s]."""
    return statistics.median(row["cpu_s"])


def relative_error(row, ref, name):
    """The relative error of a row's output `name` against a reference row's (None where either lacks it)."""
    a, b = row["outputs"].get(name), ref["outputs"].get(name) if ref else None
    return None if a is None or not b else a / b - 1


def variant_cells(row, ref, names, fmt="+.2%"):
    """A repeated run's table cells: its CPU (median, and the range over several repeats) and, per output of `names`,
    its value (the reference row itself, ref None) or its error against ref in `fmt` (blank where it has none)."""
    c = row["cpu_s"]
    cpu = f"{median_cpu(row):.1f}" + (f" ({min(c):.1f}–{max(c):.1f})" if len(c) > 1 else "")
    if ref is None:
        return cpu, [f"{row['outputs'][o]:.6g}" if o in row["outputs"] else "" for o in names]
    return cpu, ["" if relative_error(row, ref, o) is None else format(relative_error(row, ref, o), fmt) for o in names]
