"""The driver's log: the summary line each run ends with, the FE mesh line, and the partition and memory lines.

The summary line (one per run, on stdout; fe/fe_stepper.c, stepping/indent_stepper.c, app/main.c):

  fe scene NAME: S steps, N Newton iterations, C cutbacks (E by the error measure), U UMAT calls, assembly A s,
      wall W s -> OUT/history.csv
  indentation NAME: S steps, N Newton iterations (predictor on), C cutbacks (E by the error measure, U asked by the
      UMAT, T stalled, D not converged), K active-set cycles, U UMAT calls, assembly A s, linear solves L s (direct,
      I Krylov iterations, F factorisations), wall W s -> OUT/history.csv
  point scene NAME: S steps, C cutbacks, worst control residual R (relative), W s[, FAILED] -> OUT/history.csv

`summary_line` reads it with one regular expression into a dict (the fields a kind does not print are absent).
The mesh line of an FE or indentation run ("fe scene NAME: 1234 cells, P1, 4 quadrature points per cell, 567
unknowns, ...") is read by `mesh_line`. On more than one rank an FE or indentation run prints how its mesh was cut
("partition: R ranks (TYPE), N vertices, C copies on ranks that do not own them (P %)", fe/fe_mesh.c), read by
`partition_line`; an indentation ends with "memory: max RSS X MB per rank, Y MB in all" (stepping/indent_stepper.c),
read by `memory_line`.
"""
import re

SUMMARY = re.compile(
    r"^(?P<kind>fe scene|indentation|point scene) (?P<scene>\S+): (?P<steps>\d+) steps"
    r"(?:, (?P<newton_iterations>\d+) Newton iterations(?: \(predictor (?P<predictor>on|off)\))?)?"
    r", (?P<cutbacks>\d+) cutbacks(?: \((?P<cutbacks_by_error>\d+) by the error measure(?:, (?P<cutbacks_by_umat>\d+) "
    r"asked by the UMAT, (?P<cutbacks_stalled>\d+) stalled, (?P<cutbacks_not_converged>\d+) not converged)?\))?"
    r"(?:, (?P<active_set_cycles>\d+) active-set cycles)?"
    r"(?:, worst control residual (?P<worst_control_residual>\S+) \(relative\))?"
    r"(?:, (?P<umat_calls>\d+) UMAT calls)?"
    r"(?:, assembly (?P<assembly_s>\S+) s)?"
    r"(?:, linear solves (?P<linear_solves_s>\S+) s \((?P<linear_solver>\w+), (?P<krylov_iterations>\d+) Krylov "
    r"iterations, (?P<factorisations>\d+) factorisations\))?"
    r", (?:wall )?(?P<wall_s>\S+) s(?P<failed>, FAILED)? -> (?P<output_dir>.*)/history\.csv$", re.M)
MESH = re.compile(r"^fe scene (?P<scene>\S+): (?P<cells>\d+) cells, P(?P<order>\d), (?P<quadrature_points>\d+) "
                  r"quadrature points per cell, (?P<unknowns>\d+) unknowns", re.M)
PARTITION = re.compile(r"^partition: (?P<ranks>\d+) ranks \((?P<type>\w+)\), (?P<vertices>\d+) vertices, (?P<copies>\d+) copies",
                       re.M)
MEMORY = re.compile(r"^memory: max RSS (?P<rank_mb>[0-9.]+) MB per rank, (?P<all_mb>[0-9.]+) MB in all", re.M)
TEXT = frozenset({"kind", "scene", "predictor", "linear_solver", "output_dir", "type"})
FLOAT = frozenset({"worst_control_residual", "assembly_s", "linear_solves_s", "wall_s", "rank_mb", "all_mb"})


def _typed(m):
    out = {}
    for k, v in m.groupdict().items():
        if v is None or k == "failed":
            continue
        out[k] = v if k in TEXT else float(v) if k in FLOAT else int(v)
    return out


def summary_line(log, index=-1):
    """The last summary line in a run's stdout (index: which one, 0 the first: a run that adapts its mesh prints one
    per level, the last the answer) as a dict: kind ('fe scene', 'indentation', 'point scene'), scene,
    steps, cutbacks, wall_s, output_dir, and what the kind prints besides (newton_iterations, umat_calls,
    assembly_s, linear_solves_s, ...; failed True for a point run that failed). ValueError when there is none."""
    found = list(SUMMARY.finditer(log))
    if not found:
        tail = log[-500:] if log else "(empty)"
        raise ValueError(f"no summary line ('<kind> NAME: N steps, ... -> OUT/history.csv') in the driver's output; "
                         f"its end:\n{tail}")
    out = _typed(found[index])
    out["failed"] = found[index].group("failed") is not None
    return out


def mesh_line(log):
    """The first FE mesh line as a dict: scene, cells, order, quadrature_points, unknowns. ValueError when none."""
    m = MESH.search(log)
    if not m:
        raise ValueError("no mesh line ('fe scene NAME: N cells, P1, ..., N unknowns') in the driver's output")
    return _typed(m)


def partition_line(log):
    """The partition line of a run on more than one rank as a dict: ranks, type, vertices, copies; None when the run
    printed none (one rank)."""
    m = PARTITION.search(log)
    return _typed(m) if m else None


def memory_line(log):
    """An indentation's memory line as a dict: rank_mb (the largest rank's peak), all_mb (the ranks' peaks summed);
    None when the run printed none."""
    m = MEMORY.search(log)
    return _typed(m) if m else None
