"""The sections "Time-step error control" and "Time-step error control: 3D Berkovich half model" of
docs/performance.md (issue 10), written from their results store docs/results/step_control.json by
bench/step_control_bench.py and checked against it by tools/doc_numbers.py.

The store: {"parts": {part: {...}}}, part "axi" (the first section) and "3d" (the second), each {"provenance":
{"command", "date", "machine", ...}, "scenes": [...], "table": {...} or null, and the figures the section's
hand-written text quotes from earlier runs, each with its own "note" saying where it was taken from ("quiet" in "axi";
"sector_tol" and "issue10_before" in "3d")}. A scene {"name", "reference": {output: value}, "uncertainty":
{output: relative}, "provenance" (only in a scene not run by the part's command: its own note),
"before_mesh_differs" (true where the 'before' scene's mesh is not today's; absent in scenes taken over), "rows":
[{"variant" ("before" or "shipped"), "steps", "newton", "calls" (UMAT calls), "wall_s" (median of the repeats),
"cpu_s" (median, user + system of the driver processes), "errors": {output: relative error against the
reference}}]}. The table (nanoindentation, axisymmetric: each error measure at three tolerances, then
Newton's stopping rule): {"reference", "uncertainty", "rows": [{"measure", "tol", "newton_rule" (null for the
measure rows), "steps", "newton", "wall_s", "cpu_s", "errors"}], "provenance" (only when not run by the part's
command)}. Values at full digits.
"""

from camclay9 import results_store

STORE = "step_control"
TITLE = "## Time-step error control"
TITLE_3D = "## Time-step error control: 3D Berkovich half model"
TITLES = {"axi": TITLE, "3d": TITLE_3D}
SCENE_KEYS = ("name", "reference", "uncertainty", "rows")
ROW_KEYS = ("variant", "steps", "newton", "calls", "wall_s", "cpu_s", "errors")
LOAD_PER_STAGE = "output, the load relative to the stage"   # the table's rows with relative_to: stage on the load stage
TABLE_KEYS = ("measure", "tol", "newton_rule", "steps", "newton", "wall_s", "cpu_s", "errors")
TABLE_OUTPUTS = ("load at end of loading", "creep depth", "residual depth")
QUIET_KEYS = ("note", "date", "nano_axi_wall_s", "nano_axi_cpu_s", "micro_axi_wall_s", "rate_wall_s", "bedding_wall_s",
              "nano_3d_wall_s", "nano_3d_steps", "targets_s")
SECTOR_KEYS = ("note", "P", "creep", "h_res_below")
BEFORE_KEYS = ("note", "steps", "wall_s")




def checked(store, part):
    """The store's part with the keys its section needs; a clear message naming the missing ones otherwise."""
    results_store.require(STORE, "the store", store, ("parts",))
    results_store.require(STORE, "parts", store["parts"], (part,))
    p = store["parts"][part]
    results_store.require(STORE, f"parts.{part}", p, ("provenance", "scenes", "table"))
    results_store.require(STORE, f"parts.{part}.provenance", p["provenance"], ("command", "date", "machine"))
    for i, s in enumerate(p["scenes"]):
        results_store.require(STORE, f"parts.{part}.scenes[{i}]", s, SCENE_KEYS)
        for j, r in enumerate(s["rows"]):
            results_store.require(STORE, f"parts.{part}.scenes[{i}] ({s['name']}).rows[{j}]", r, ROW_KEYS)
    if p["table"] is not None:
        results_store.require(STORE, f"parts.{part}.table", p["table"], ("reference", "uncertainty", "rows"))
        for j, r in enumerate(p["table"]["rows"]):
            results_store.require(STORE, f"parts.{part}.table.rows[{j}]", r, TABLE_KEYS)
            results_store.require(STORE, f"parts.{part}.table.rows[{j}].errors", r["errors"], TABLE_OUTPUTS)
    extra = {"axi": {"quiet": QUIET_KEYS}, "3d": {"sector_tol": SECTOR_KEYS, "issue10_before": BEFORE_KEYS}}[part]
    for key, keys in extra.items():
        results_store.require(STORE, f"parts.{part}", p, (key,))
        results_store.require(STORE, f"parts.{part}.{key}", p[key], keys)
    return p


def fmt_err(e, d=2):
    return ", ".join(f"{k} {v:+.{d}%}" for k, v in e.items())


def scene_lines(s):
    """Part 1's lines for one scene: its runs, then its reference's uncertainty."""
    lines = [f"| {s['name']} | {r['variant']} | {r['steps']} | {r['newton']} | {r['calls']:,} | {r['wall_s']:.1f} | "
             f"{r['cpu_s']:.1f} | {fmt_err(r['errors'])} |" for r in s["rows"]]
    return lines + [f"| {s['name']} | reference (uncertainty) | | | | | | {max(s['uncertainty'].values()):.2e} |"]


def table_lines(t):
    """Part 2: each measure at its tolerances, then Newton's stopping rule (errors to four digits)."""
    lines = ["| measure | tol | steps | Newton its | wall [s] | CPU [s] | load at end of loading | creep depth | "
             "residual depth |",
             "|---|---|---|---|---|---|---|---|---|"]
    for r in t["rows"]:
        rule, d = r["newton_rule"], 4 if r["newton_rule"] else 2
        head = f"{r['measure']}, {rule} | 1.5e-2" if rule else f"{r['measure']} | {r['tol']:g}"
        lines.append(f"| {head} | {r['steps']} | {r['newton']} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | "
                     + " | ".join(f"{r['errors'][k]:+.{d}%}" for k in TABLE_OUTPUTS) + " |")
    return lines


def head(title, pv):
    return [title, "",
            f"Command: `{pv['command']}` ({pv['date']}; {pv['machine']}). Before: the scene as shipped until",
            "issue 10 (the UMAT's worst-point control, PROPS tol). Shipped: the scene now (`steps.error`, docs/driver.md). The",
            "reference: the same mesh with the output measure at tol 5e-3 and 2.5e-3, extrapolated (first order); its",
            "uncertainty is the relative difference of the finer run from it. Fields off; one rank (triaxial: 2). Wall:",
            "median of the repeats for shipped rows; CPU: user + system of the driver processes.", "",
            "| scene | variant | steps | Newton its | UMAT calls | wall [s] | CPU [s] | errors against the reference |",
            "|---|---|---|---|---|---|---|---|"]


def note_lines(p):
    """What of the part was not run by its command (its provenance's 'note', each kept scene's), under its table."""
    notes = [p["provenance"]["note"]] if p["provenance"].get("note") else []
    notes += [f"{s['name']}: not rerun; {s['provenance']['note']}." for s in p["scenes"] if "provenance" in s]
    notes += [f"{s['name']}: its 'before' run is on the mesh shipped before issue 10, not on today's (the reference's): "
              "its errors include the difference of the meshes." for s in p["scenes"] if s.get("before_mesh_differs")]
    if p["table"] and "provenance" in p["table"]:
        notes.append(f"The table of measures below: not rerun; {p['table']['provenance']['note']}.")
    return [line for n in notes for line in ("", n)]


def quiet_lines(q):
    """The hand-written paragraph on a quiet machine, its figures from the store (taken over: q['note'])."""
    return ["", f"**On a quiet machine** (load average below 0.8, {q['date']}, the shipped scenes with fields off, one",
            "rank, main after this session's merges; nano axi: median of 3): nanoindent_kerogen_axi "
            f"{q['nano_axi_wall_s']:.2f} s wall "
            f"({q['nano_axi_cpu_s']:.2f} s CPU),",
            f"microindent_BN_axi {q['micro_axi_wall_s']:.2f} s, loading_rate_a1 {q['rate_wall_s']:.2f} s, bedding_theta45 "
            f"{q['bedding_wall_s']:.2f} s, nanoindent_kerogen (3D half model)",
            f"{q['nano_3d_wall_s']:.2f} s ({q['nano_3d_steps']} steps: the Berkovich's normal on its edges changed since "
            "the 3D rows below were measured). The issue's",
            f"targets: {', '.join(f'{t:g} s' for t in q['targets_s'][:-1])} and {q['targets_s'][-1]:g} s."]


def section_axi(p):
    lines = head(TITLE, p["provenance"])
    for s in p["scenes"]:
        lines += scene_lines(s)
    lines += note_lines(p) + quiet_lines(p["quiet"])
    if p["table"] is not None:
        lines += ["", "Nanoindentation (axisymmetric), each measure at three tolerances (unload stage: output 0.1 for "
                  "the relative", "measures), same reference:", ""] + table_lines(p["table"])
        if any(r["measure"] == LOAD_PER_STAGE for r in p["table"]["rows"]):
            lines += ["", f"'{LOAD_PER_STAGE}': the load stage's error relative to the stage "
                      "(`relative_to: stage`, docs/driver.md,", "Error measures), the hold's and the unload's relative "
                      "to the step, as in the rows 'output'."]
        lines += ["", "![error against CPU time](step_control.png)"]
    return "\n".join(lines) + "\n"


def section_3d(p):
    s, b = p["sector_tol"], p["issue10_before"]
    lines = ["*Measured on the half models before the mesh study (\"3D indentation: mesh convergence and the cheapest "
             "model\":", f"P1, h_tip 0.05 µm). On the shipped P2 sector, tol 5e-3 instead of 1.5e-2 moves P by {s['P']:g} %, "
             "the creep depth by", f"{s['creep']:g} % and the residual depth by < {s['h_res_below']:g} % (that section's "
             "\"tol 0.005\" rows).*", ""]
    lines = [TITLE_3D, ""] + lines + head(TITLE_3D, p["provenance"])[2:]
    for sc in p["scenes"]:
        lines += scene_lines(sc)
    lines += note_lines(p)
    n = len(b["steps"])
    lines += ["", "The 'before' runs (the UMAT's worst-point control at PROPS tol 1e-5, as shipped until issue 10) take "
              "about ten", "minutes each and were not rerun (`--no-before`); issue 10 measured them as "
              + ", ".join(f"{x:,}".replace(",", " ") for x in b["steps"][:n - 1]) + f" and {b['steps'][-1]:,}".replace(",", " ")
              + " steps and", ", ".join(f"{x:g}" for x in b["wall_s"][:n - 1]) + f" and {b['wall_s'][-1]:g} s wall. "
              "The 3D rows' wall times are inflated by the load of the shared machine (load average",
              "6 to 10); on one rank the CPU time is what a quiet machine's wall time would be. These errors are of "
              "the time", "stepping only, on each scene's own mesh: the mesh error of the 3D models is far larger "
              "(section \"3D indentation:", "mesh convergence and the cheapest model\")."]
    return "\n".join(lines) + "\n"


def sections(store):
    """{title: text} for the parts the store holds (tools/doc_numbers.py's call for a store behind several sections)."""
    writers = {"axi": section_axi, "3d": section_3d}
    return {TITLES[part]: writers[part](checked(store, part)) for part in store.get("parts", {})}


def section(store, root=None, part="axi"):
    """One part's section text (tests and the bench)."""
    return sections({"parts": {part: checked(store, part)}})[TITLES[part]]
