"""docs/performance.md's "Measured curves: calibration coverage" sections, one per drift-hold length, written from the
results store docs/results/calibrate_coverage.json (bench/calibrate_coverage.py builds it; tools/doc_numbers.py checks
the sections against it). A hold's entry: its provenance (the command's draws, faults, hold and whether the issue's
cases ran), each fault's draws and the cases, each row with the numbers the tables print."""
import numpy as np

from camclay9.instrument_record import SHIPPED_DRIFT_HOLD

STORE = "calibrate_coverage"
TITLE = "## Measured curves: calibration coverage"
# the numbers a draw's or a case's row keeps (fractions, not per cent; the CPU in seconds)
DRAW_KEYS = ("error", "se_rel", "white_rel", "se_load_rel", "z", "cpu", "warned")
CASE_KEYS = ("name", "value", "error", "se_rel", "white_rel", "se_load_rel", "z", "runs", "cpu", "drift", "load")


def lengthened(hold):
    """Whether a drift hold of `hold` seconds is not the shipped protocol's (then it has its own section)."""
    return float(hold) != SHIPPED_DRIFT_HOLD


def title(hold):
    """The section's title for a drift hold of `hold` seconds."""
    return f"{TITLE}, a {float(hold):g} s drift hold" if lengthened(hold) else TITLE


def covered(rows):
    """How many of the rows (draws or cases) have the truth within 2 reported standard errors (|z| <= 2)."""
    return sum(abs(r["z"]) <= 2 for r in rows)


def keep(row, keys):
    """A bench row as the store keeps it: a failed row keeps its message."""
    if "failed" in row:
        return {k: row[k] for k in ("name", "failed") if k in row}
    return {k: row[k] for k in keys}


def command(p):
    hold = f" --drift-hold {float(p['hold']):g}" if lengthened(p["hold"]) else ""
    faults = f" --faults {','.join(p['faults'])}" if p["draws"] else ""
    return f"bench/calibrate_coverage.py --draws {p['draws']}{' --cases' if p['cases'] else ''}{hold}{faults}"


def intro(p):
    hold = float(p["hold"])
    return (f"Command: `{command(p)}` ({p['date']}; docs/calibrate.md, \"Measured curves\"). Synthetic instrument records "
            "made by the project's own model, so that the model is exact and only the data's faults remain: the paper's "
            f"nano protocol with a {hold:g} s hold at 10 % of the peak load on unloading (protocols/paper_drift_hold.yaml"
            f"{', its drift hold lengthened' if lengthened(hold) else ''}), 10 rows a second, the depths those of the forward "
            "scene the fit runs (nano_fast driven by the record's loads) at the truth. Each draw: a truth eta_soft "
            "log-uniform in [6e9, 3e10], a start 3x above it, `weighting: noise`; faults: depth noise 1 nm; drift 0.05 "
            "nm/s over the whole record (`drift: fit`); both, with load noise 0.5 % of the peak (the fitted load "
            "history); ignored: noise and drift fitted without a drift option. Covered: the truth within 2 reported "
            "standard errors (fit.yaml's quote: the data's part by Newey-West, and with a fitted load history its share, "
            "from -calibrate_load_draws forward runs, docs/calibrate.md \"A noisy load\"). CPU: the driver and its forward "
            "processes.\n")


def load_part(values):
    """The load history's share of the s.e. (relative) as the tables print it: the median of those measured, or a dash."""
    v = [x for x in values if x is not None]
    return f"{100 * np.median(v):.2f} %" if v else "—"


def draws_table(draws):
    lines = ["| fault | draws | covered (within 2 s.e.) | median abs. error | median s.e. | its load history's part "
             "| median s.e. if white | largest abs. z | hold trend warned | median CPU [s] |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for fault, rs in draws.items():
        ok = [r for r in rs if "failed" not in r]
        cov = covered(ok)
        lines.append(f"| {fault} | {len(rs)} ({len(rs) - len(ok)} failed) | {cov} of {len(rs)} ({100 * cov / len(rs):.0f} %) | "
                     f"{100 * np.median([abs(r['error']) for r in ok]):.2f} % | "
                     f"{100 * np.median([r['se_rel'] for r in ok]):.2f} % | "
                     f"{load_part([r.get('se_load_rel') for r in ok])} | "
                     f"{100 * np.median([r['white_rel'] for r in ok]):.2f} % | "
                     f"{max(abs(r['z']) for r in ok):.2f} | {sum(r['warned'] for r in ok)} of {len(ok)} | "
                     f"{np.median([r['cpu'] for r in ok]):.1f} |")
    return lines


def cases_table(cases):
    named = {r["name"]: r for r in cases if "failed" not in r}
    base, plain = named.get("clean, drift: fit"), named.get("clean, drift: none")
    lines = ["\nThe issue's cases at one truth (eta_soft = 1.83e10, seed fixed), each from 3x above:\n",
             "| record, drift option | eta_soft | error | s.e. (white) | its load history's part | truth in s.e. | forward runs | "
             "CPU [s] | CPU / clean (same option) | drift fitted [nm/s] | load history |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in cases:
        if "failed" in r:
            lines.append(f"| {r.get('name', '?')} | failed: {r['failed']} |")
            continue
        ref = base if "fit" in r["name"] else plain
        lines.append(f"| {r['name']} | {r['value']:.5g} | {100 * r['error']:+.2f} % | {100 * r['se_rel']:.2f} % "
                     f"({100 * r['white_rel']:.2f} %) | {load_part([r.get('se_load_rel')])} | {r['z']:+.2f} | {r['runs']} | {r['cpu']:.1f} | "
                     f"{r['cpu'] / ref['cpu']:.2f} | {r['drift'] if r['drift'] is not None else '—'} | {r['load']} |")
    return lines


def section(entry, hold):
    """The section for one hold's entry of the store."""
    p = entry["provenance"]
    lines = [f"{title(hold)}\n", intro(p)]
    if entry.get("draws"):
        lines += draws_table(entry["draws"])
    if entry.get("cases"):
        lines += cases_table(entry["cases"])
    return "\n".join(lines) + "\n"


def sections(store):
    """{title: section text} for every hold the store keeps in the bench's own form (a provenance with its draws)."""
    return {title(h): section(e, h) for h, e in store.get("holds", {}).items() if "draws" in e.get("provenance", {})}
