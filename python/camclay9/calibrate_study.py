"""The section "Calibration" of docs/performance.md (docs/calibrate.md), written from its results store
docs/results/calibrate_bench.json by bench/calibrate_bench.py and checked against it by tools/doc_numbers.py.

The store: {"provenance": {"command", "date", "machine", ...}, "true": {parameter: the value the synthetic data
were made with}, "examples": [...], "not_run": [text, ...]}, the examples in the bench's order, each
{"name", "models": [{"scene" (the forward model's scene, its stem), "drive" ("data" or "scene"), "reference" (the
full model's scene stem, or null)}], "iterations" (TAO's), "forward_runs", "full_model_runs", "cpu_s" (the driver and
its forward processes, user + system [s]), "wall_s" [s], "parameters" ({parameter: {"value", "relative_std_error"}}:
TAO's fit with the forward model), "quote" (the same for fit.yaml's quote), "bias" ({parameter: {"relative" (the
first estimate), "value" (the measured one, the refined fit's value, where refined)}}), "refined" (the quote refined
on the full model)}, all as fit.yaml has them (full digits). An example taken over from elsewhere than this run
carries its own "provenance" (which table, which commit, to what digits), which the section names.
"""

from camclay9 import results_store

STORE = "calibrate_bench"
TITLE = "## Calibration"
KEYS = ("name", "models", "iterations", "forward_runs", "full_model_runs", "cpu_s", "wall_s", "parameters", "quote",
        "bias", "refined")
FIT_KEYS = ("value", "relative_std_error")
HEADER = ("| example | forward model (drive), full model | TAO its | forward runs | full-model runs | CPU [s] | wall [s] "
          "| forward fit (error, s.e.) | quoted (error ± s.e.) | bias: first estimate, measured |")




def checked(store):
    """The store's examples, each with the keys its row needs; a clear message naming the missing ones otherwise."""
    results_store.require(STORE, "the store", store, ("provenance", "true", "examples"))
    results_store.require(STORE, "provenance", store["provenance"], ("command", "date", "machine"))
    for i, ex in enumerate(store["examples"]):
        results_store.require(STORE, f"examples[{i}]", ex, KEYS)
        for part in ("parameters", "quote"):
            for k, p in ex[part].items():
                results_store.require(STORE, f"examples[{i}] ({ex['name']}).{part}.{k}", p, FIT_KEYS)
                if k not in store["true"]:
                    raise ValueError(f"docs/results/{STORE}.json: examples[{i}] ({ex['name']}).{part} names {k}, "
                                     f"which 'true' lacks (it has {', '.join(store['true'])})")
        for k, b in ex["bias"].items():
            results_store.require(STORE, f"examples[{i}] ({ex['name']}).bias.{k}", b, ("relative",))
    return store["examples"]


def pct(x, sign="+"):
    """x as a percentage with two significant digits (0.00041 %, -11 %)."""
    return f"{100 * x:{sign}.2g} %"


def models_text(ex):
    return "; ".join(f"{m['scene']} ({m['drive']})" + (f", ref. {m['reference']}" if m.get("reference") else "")
                     for m in ex["models"])


def row(ex, true):
    """The table's line for one example."""
    fwd, quote, bias = [], [], []
    for k, p in ex["parameters"].items():
        q = ex["quote"][k]
        fwd.append(f"{k} {p['value']:.5g} ({pct(p['value'] / true[k] - 1)}, s.e. {pct(p['relative_std_error'], '')})")
        quote.append(f"{k} {q['value']:.7g} ({pct(q['value'] / true[k] - 1)} ± {pct(q['relative_std_error'], '')})")
        b = ex["bias"].get(k)
        if b:
            measured = f", measured {pct(b['value'] / p['value'])}" if b.get("value") is not None else ""
            bias.append(f"first {pct(b['relative'])}{measured}")
    return (f"| {ex['name']} | {models_text(ex)} | {ex['iterations']} | {ex['forward_runs']} | {ex['full_model_runs']} | "
            f"{ex['cpu_s']:.0f} | {ex['wall_s']:.0f} | {'; '.join(fwd)} | {'; '.join(quote)}"
            f"{' (refined)' if ex['refined'] else ''} | {'; '.join(bias) or '—'} |")


def notes(store):
    """The lines under the table: the examples not run, and those taken over (each with its provenance)."""
    out = []
    if store.get("not_run"):
        out.append(f"Not run: {', '.join(store['not_run'])}.")
    for ex in store["examples"]:
        if "provenance" in ex:
            out.append(f"{ex['name']}: not rerun; {ex['provenance']['note']}.")
    return ["", *out] if out else []


def section(store, root=None):
    """The section's text: the command, its date and machine, what was run, the table. `root` is unused (no
    hand-written reading); it is there for tools/doc_numbers.py's uniform call."""
    examples = checked(store)
    pv = store["provenance"]
    lines = [TITLE, "",
             f"Command: `{pv['command']}` ({pv['date']}; {pv['machine']}; docs/calibrate.md). The examples of "
             "`input/calibrate/`, TAO POUNDERS from a start 3x off, one forward",
             "run at a time; synthetic data made by the driver with eta_soft 1.3e10 and eta_hard 1.3e13 (the noise "
             "example:",
             "1 % noise, so its error is to be read against its standard error). CPU: the driver and its forward "
             "processes",
             "(user + system). One run each on a shared machine (wall times vary by about 2x with its load). The "
             "forward fit is",
             "TAO's with the forward model; the quoted value is fit.yaml's `quote` (refined on the full model when "
             "the forward",
             "model's bias exceeds its standard error); the bias is relative to the forward fit.", "",
             HEADER, "|---|---|---|---|---|---|---|---|---|---|"]
    lines += [row(ex, store["true"]) for ex in examples]
    return "\n".join(lines + notes(store)) + "\n"
