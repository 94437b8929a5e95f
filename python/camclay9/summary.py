"""summary.json of a run, every kind (driver/src/app/run_summary.c, driver/src/calibrate/calibrate_report.c;
docs/driver.md, "summary.json").

Every summary has "scene", "kind", "completed", "counters" and "cost"; then the kind's own (KIND_KEYS): an FE or
indentation run "mesh", "mesh_error", "stages": [{"name", "end", "change", "mesh_error"?, "time_error"}] and
"levels"; a point run "stages" and "point"; a calibration "parameters" and "misfit". FE, indentation and point
summaries also have "failure" (null, or where the run failed: docs/driver.md), not checked, so that summaries of
earlier builds still read. A run that failed before its first step was done writes summary.json.part (beside its
history.csv.part), which `read_summary` reads when given that file. `read_summary` checks those keys and returns the dict; `stage` picks a stage by name and `reported` one of its quantities. Errors are
ValueError (FileNotFoundError for a missing file) naming the file and the key.
"""
import json
from pathlib import Path

KEYS = ("scene", "kind", "completed", "counters", "cost")
KIND_KEYS = {"fe": ("mesh", "stages", "levels"), "indentation": ("mesh", "stages", "levels"),
             "point": ("stages", "point"), "calibrate": ("parameters", "misfit")}
STAGE_KEYS = ("name", "end", "change")


class Summary(dict):
    """summary.json's object as a dict, and the file it came from as `.path` (for messages)."""

    path = "summary.json"


def summary_path(run):
    """RUN/summary.json for a run directory, or the file itself (summary.json or summary.json.part)."""
    run = Path(run)
    return run if run.suffix == ".json" or run.name.endswith(".json.part") else run / "summary.json"


def read_summary(run):
    """The summary of RUN (a run directory or its summary.json), its keys checked."""
    path = summary_path(run)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such file (the driver writes it at the end of every run but a sweep or "
                                "replay; a run that failed before its first step was done writes summary.json.part)")
    try:
        s = json.loads(path.read_text())
    except json.JSONDecodeError as err:
        raise ValueError(f"{path}: not JSON: {err}") from None
    if not isinstance(s, dict):
        raise ValueError(f"{path}: expected an object of {', '.join(KEYS)}, got {type(s).__name__}")
    if s.get("kind") not in KIND_KEYS:
        raise ValueError(f"{path}: key 'kind' is {s.get('kind')!r}, expected one of {', '.join(KIND_KEYS)}")
    keys = KEYS + KIND_KEYS[s["kind"]]
    missing = [k for k in keys if k not in s]
    if missing:
        raise ValueError(f"{path}: no key {', '.join(repr(k) for k in missing)} (expected {', '.join(keys)})")
    for i, st in enumerate(s.get("stages", [])):
        lost = [k for k in STAGE_KEYS if k not in st]
        if lost:
            raise ValueError(f"{path}: stages[{i}] has no key {', '.join(repr(k) for k in lost)}")
    s = Summary(s)
    s.path = str(path)
    return s


def stage(summary, name):
    """The entry of stage `name` ('start' for the initial state); KeyError naming the file and the stages."""
    for st in summary.get("stages", []):
        if st["name"] == name:
            return st
    raise KeyError(f"{getattr(summary, 'path', 'summary.json')}: no stage '{name}' (stages: "
                   f"{', '.join(st['name'] for st in summary.get('stages', [])) or 'none'})")


def reported(summary, stage_name, quantity, what="end"):
    """A reported quantity (e.g. 'depth') of a stage: its value at the stage's end (what='end') or its change over
    the stage (what='change')."""
    st = stage(summary, stage_name)
    if what not in ("end", "change"):
        raise ValueError(f"what = '{what}': expected 'end' or 'change'")
    if quantity not in st[what]:
        raise KeyError(f"{getattr(summary, 'path', 'summary.json')}: stage '{stage_name}' reports no '{quantity}' "
                       f"(it reports {', '.join(st[what]) or 'nothing'})")
    return st[what][quantity]
