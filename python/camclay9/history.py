"""history.csv of a run: one row per converged step, read by column name.

The driver writes three layouts today (docs/driver.md, "Output"); each starts with its own leading columns:

  fe           time,stage,step,dt,newton_its,cutbacks,...          (fe/fe_stepper.c)
  indentation  time,stage,stage_name,step,dt,newton_its,...        (stepping/indent_stepper.c)
  point        time,step,segment,dt,newton_its,local_its,...      (point/point_solve.c)

`read_history` returns a numpy structured array (one record per row, `h["depth"]`, `h[h["stage"] == 1]`): the
columns named in INTEGER as int64, `stage_name` as str, every other column as float64, whatever the layout (it does
not insist on one: `history_layout` tells which). A caller reads columns by name and names those it needs (`need=`),
so a later change of the layouts touches this module only. Errors are ValueError (FileNotFoundError for a missing
file) naming the file, the line, the column and the value.
"""
import csv
from pathlib import Path

import numpy as np

LAYOUTS = {
    "fe": ("time", "stage", "step", "dt", "newton_its", "cutbacks"),
    "indentation": ("time", "stage", "stage_name", "step", "dt", "newton_its", "cutbacks"),
    "point": ("time", "step", "segment", "dt", "newton_its", "local_its", "cutbacks"),
}
INTEGER = frozenset({"stage", "step", "segment", "newton_its", "local_its", "cutbacks", "active_nodes",
                     "active_changes", "umat_calls", "flags"})
TEXT = frozenset({"stage_name"})


def history_path(run):
    """RUN/history.csv for a run directory, or the file itself."""
    run = Path(run)
    return run if run.suffix == ".csv" else run / "history.csv"


def layout(names):
    """'fe', 'indentation' or 'point' from the leading columns; ValueError for none of them."""
    for kind, lead in LAYOUTS.items():
        if tuple(names[:len(lead)]) == lead:
            return kind
    raise ValueError(f"columns {','.join(names[:7])}...: not a history.csv layout of the driver (expected one of "
                     + "; ".join(f"{k}: {','.join(v)}" for k, v in LAYOUTS.items()) + ")")


def _value(path, line, name, text):
    if name in TEXT:
        return text
    try:
        return int(text) if name in INTEGER else float(text)
    except ValueError:
        what = "an integer" if name in INTEGER else "a number"
        raise ValueError(f"{path}:{line}: column '{name}' has '{text}': expected {what}") from None


def read_history(run, need=()):
    """The history of RUN (a run directory or its history.csv) as a structured array, at least 1-D.

    need: column names that must be there (ValueError naming the file and the missing ones)."""
    path = history_path(run)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file (the driver's history)")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or not rows[0]:
        raise ValueError(f"{path}: empty, expected a header line of column names")
    names = [n.strip() for n in rows[0]]
    missing = [n for n in need if n not in names]
    if missing:
        raise ValueError(f"{path}: column(s) {', '.join(repr(n) for n in missing)} missing from the header line "
                         f"(columns: {', '.join(names)})")
    if len(set(names)) != len(names):
        raise ValueError(f"{path}:1: a column name is repeated: {','.join(names)}")
    body = [r for r in rows[1:] if r]
    values = []
    for line, r in enumerate(body, start=2):
        if len(r) != len(names):
            raise ValueError(f"{path}:{line}: {len(r)} values, expected {len(names)} (one per column of the header)")
        values.append(tuple(_value(path, line, n, v) for n, v in zip(names, r)))
    width = max([len(v[names.index("stage_name")]) for v in values] + [1]) if "stage_name" in names else 1
    dtype = [(n, f"<U{width}" if n in TEXT else np.int64 if n in INTEGER else np.float64) for n in names]
    return np.atleast_1d(np.array(values, dtype=dtype))


def history_layout(h):
    """The layout ('fe', 'indentation', 'point') of an array read by read_history."""
    return layout(list(h.dtype.names))
