"""history.csv of a run: one row per converged step, read by column name.

Every scene kind writes one layout (docs/driver.md, "history.csv"; driver/src/stepping/history_columns.c): the
shared leading columns LEAD, then the kind's own, declared once in the driver by name and format:

  time,stage,stage_name,step,dt,newton_its,cutbacks, then
  fe           pressure_<group>..., eps_11..., sig_11..., ... reaction_z     (stepping/fe_stepper.c)
  indentation  load, depth, active_nodes, ... evp_rate                      (stepping/indent_stepper.c)
  point        local_its, eps_11..., sig_11..., ... pc_hard, pc_soft, flags  (stepping/point_stepper.c)

A point scene's segment is its stage. A history written before the one layout (issue 35) still reads: an old point
history's `segment` column comes back as `stage` (its `stage_name` is missing, as in an old FE history).

`read_history` returns a numpy structured array (one record per row, `h["depth"]`, `h[h["stage"] == 1]`): the
columns named in INTEGER as int64, `stage_name` as str, every other column as float64. A caller reads columns by
name and names those it needs (`need=`); `history_layout` tells the kind by the kind's own columns. Errors are
ValueError (FileNotFoundError for a missing file) naming the file, the line, the column and the value.
"""
import csv
from pathlib import Path

import numpy as np

LEAD = ("time", "stage", "stage_name", "step", "dt", "newton_its", "cutbacks")
# The kind by a column only its history has (the first match wins).
KIND_COLUMN = (("point", "local_its"), ("indentation", "depth"), ("fe", "eps_spread"))
RENAMED = {"segment": "stage"}  # old name -> name in the one layout
INTEGER = frozenset({"stage", "step", "newton_its", "local_its", "cutbacks", "active_nodes", "active_changes",
                     "umat_calls", "flags"})
TEXT = frozenset({"stage_name"})


def history_path(run):
    """RUN/history.csv for a run directory, or the file itself."""
    run = Path(run)
    return run if run.suffix == ".csv" else run / "history.csv"


def layout(names):
    """'fe', 'indentation' or 'point' from the kind's own columns; ValueError for none of them."""
    if "time" in names and "stage" in names and "step" in names:
        for kind, column in KIND_COLUMN:
            if column in names:
                return kind
    raise ValueError(f"columns {','.join(names[:7])}...: not a history.csv layout of the driver (expected "
                     f"{','.join(LEAD)}, then a point's local_its, an indentation's depth or an FE scene's "
                     "eps_spread among the kind's own)")


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
    if "stage" not in names:  # written before the one layout: a point's segment is its stage
        names = [RENAMED.get(n, n) for n in names]
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
