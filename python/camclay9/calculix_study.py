"""The section "CalculiX on the same mesh (issue 13)" of docs/performance.md, written from its results store
docs/results/calculix.json by bench/calculix_compare.py and checked against it by tools/doc_numbers.py.

The store (values at full digits; times in s, displacements in mm):
  {"provenance": {"command", "date" and "finished" (UTC, "YYYY-MM-DD HH:MM UTC"), "rev" (the driver's commit),
                  "calculix" (the version CalculiX prints), "cores" (the machine's), "load" ({"start", "end"}: the
                  1, 5 and 15-minute load averages), "note" (optional: what the run left out)},
   "method": {"plans": {name: {"increments", "hold", "ramp", "creep" (each phase's period)}} (the plans the meshes
              use), "tol_fixed" (PROPS(20) of the fixed-increment runs), "trace_max" (the largest tets x increments
              traced), "target": {"ratio", "from_tets"} (issue 13's requirement on the driver's default against
              CalculiX on 1 thread, per increment: at most "ratio" from "from_tets" tets on; not a measurement)},
   "meshes": [one per mesh, in the bench's order: {"size" (gmsh element size, mm), "ntet", "nnode", "plan",
              "incs", "repeats", "agree" ({} when not traced, else the worst relative differences of
              camclay9.calculix_mesh.compare: "time", "mean strain", "mean stress", "mean evp33 hard", "mean evp33
              soft", "cell stress", "cell pc_hard", "cell pc_soft", "cell evp"), "printed" (the worst relative
              difference of the mean top u_z over the repeats, at CalculiX's printed digits), "printed_digits" (the
              significant digits of CalculiX's .dat), "runs": [one per configuration, in the bench's order:
              {"code": "driver" with "options" (its PETSc options, "" = the defaults), or "calculix" with
              "threads"; "steps", "its" (increments and Newton iterations of the first repeat), "wall", "cpu"
              (medians of the repeats), "walls", "cpus" (each repeat's)}]}],
   "adaptive": null or {"size", "ntet", "tol" (PROPS(20)), "runs": {"fixed" | "adaptive": {"driver" |
              "calculix": {"steps", "cutbacks", "its", "wall", "cpu", "u_end" (mean top u_z at the end),
              "u_load" (at the end of the ramp)}}}}}
The section's tables and its reading are computed from these values alone.
"""
from camclay9 import results_store

STORE = "calculix"
TITLE = "## CalculiX on the same mesh (issue 13)"
# the driver's set-up before issue 13's solver work, as the bench's documented command gives it
OLD = "-ksp_type preonly -fe_coo false -pc_factor_mat_solver_type mumps"
AGREE_KEYS = ("mean strain", "mean stress", "mean evp33 hard", "mean evp33 soft", "cell stress", "cell pc_hard",
              "cell pc_soft", "cell evp")
RUN_KEYS = ("code", "steps", "its", "wall", "cpu", "walls", "cpus")
AD_KEYS = ("steps", "cutbacks", "its", "wall", "cpu", "u_end", "u_load")


def checked(store):
    """The store's meshes, each part checked: a ValueError naming the file and the missing key otherwise."""
    req = results_store.require
    req(STORE, "the store", store, ("provenance", "method", "meshes", "adaptive"))
    req(STORE, "provenance", store["provenance"], ("command", "date", "finished", "rev", "calculix", "cores", "load"))
    req(STORE, "provenance.load", store["provenance"]["load"], ("start", "end"))
    m = store["method"]
    req(STORE, "method", m, ("plans", "tol_fixed", "trace_max", "target"))
    req(STORE, "method.target", m["target"], ("ratio", "from_tets"))
    for name, p in m["plans"].items():
        req(STORE, f"method.plans.{name}", p, ("increments", "hold", "ramp", "creep"))
    for i, r in enumerate(store["meshes"]):
        req(STORE, f"meshes[{i}]", r, ("size", "ntet", "nnode", "plan", "incs", "repeats", "agree", "printed",
                                       "printed_digits", "runs"))
        if r["agree"]:
            req(STORE, f"meshes[{i}].agree", r["agree"], AGREE_KEYS)
        for j, run in enumerate(r["runs"]):
            req(STORE, f"meshes[{i}].runs[{j}]", run, RUN_KEYS + (("options",) if run.get("code") == "driver" else ("threads",)))
        if reference(r) is None:
            raise ValueError(f"docs/results/{STORE}.json: meshes[{i}] has no CalculiX run on 1 thread (the reference)")
    ad = store["adaptive"]
    if ad is not None:
        req(STORE, "adaptive", ad, ("size", "ntet", "tol", "runs"))
        req(STORE, "adaptive.runs", ad["runs"], ("fixed", "adaptive"))
        for label in ("fixed", "adaptive"):
            req(STORE, f"adaptive.runs.{label}", ad["runs"][label], ("driver", "calculix"))
            for code in ("driver", "calculix"):
                req(STORE, f"adaptive.runs.{label}.{code}", ad["runs"][label][code], AD_KEYS)
    return store["meshes"]


def num(x):
    """A setting as the text gives it: 1e6, 36000, 0.25, 1e-6."""
    return f"{x:g}".replace("e+0", "e").replace("e-0", "e-").replace("e+", "e")


def reference(mesh):
    """The CalculiX run on 1 thread of a mesh (the reference of the last column), or None."""
    return next((r for r in mesh["runs"] if r["code"] == "calculix" and r["threads"] == 1), None)


def default_run(mesh):
    """The driver's run with its default options, or None."""
    return next((r for r in mesh["runs"] if r["code"] == "driver" and not r["options"].strip()), None)


def per_increment(run, ref):
    """(wall, CPU) per increment of `run` relative to those of `ref`."""
    return (run["wall"] / run["steps"] / (ref["wall"] / ref["steps"]), run["cpu"] / run["steps"] / (ref["cpu"] / ref["steps"]))


def name(run):
    if run["code"] == "driver":
        return f"driver {run['options']}" if run["options"].strip() else "driver (default solver)"
    return f"CalculiX SPOOLES, {run['threads']} thread{'s' if run['threads'] > 1 else ''}"


def agreement_table(meshes):
    digits = {r["printed_digits"] for r in meshes}
    lines = ["| tets | increments | mean strain | mean stress | mean evp33 hard / soft | cell stress | cell pc hard / soft "
             f"| cell evp | top u_z ({'/'.join(map(str, sorted(digits)))} printed digits) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in meshes:
        g = r["agree"]
        full = (f"{g['mean strain']:.1e} | {g['mean stress']:.1e} | {g['mean evp33 hard']:.1e} / {g['mean evp33 soft']:.1e} | "
                f"{g['cell stress']:.1e} | {g['cell pc_hard']:.1e} / {g['cell pc_soft']:.1e} | {g['cell evp']:.1e}") if g \
            else "(no trace: too large) | | | | | "
        lines.append(f"| {r['ntet']} | {r['incs']} | {full} | {r['printed']:.1e} |")
    return "\n".join(lines)


def time_table(meshes):
    lines = ["| tets (nodes) | increments | code, options | Newton its | wall s | CPU s | wall ms / increment | "
             "wall ms / Newton it. | CPU ms / increment | per increment vs CalculiX 1 thread: wall, CPU |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in meshes:
        ref = reference(r)
        for x in r["runs"]:
            wall, cpu, steps, its = x["wall"], x["cpu"], x["steps"], x["its"]
            ratio = "{:.2f}, {:.2f}".format(*per_increment(x, ref))
            lines.append(f"| {r['ntet']} ({r['nnode']}) | {steps} ({r['plan']}) | {name(x)} | {its} | {wall:.2f} | {cpu:.2f} | "
                         f"{1e3 * wall / steps:.1f} | {1e3 * wall / max(its, 1):.1f} | {1e3 * cpu / steps:.1f} | {ratio} |")
    return "\n".join(lines)


def adaptive_table(ad):
    lines = ["| run | code | increments | cutbacks | Newton its | wall s | CPU s | creep [mm] | creep vs fixed |",
             "|---|---|---|---|---|---|---|---|---|"]
    for label in ("fixed", "adaptive"):
        for code in ("driver", "calculix"):
            x = ad["runs"][label][code]
            lines.append(f"| {label} | {'driver' if code == 'driver' else 'CalculiX, 1 thread'} | {x['steps']} | {x['cutbacks']} | "
                         f"{x['its']} | {x['wall']:.2f} | {x['cpu']:.2f} | {creep(ad, label, code):.5e} | "
                         f"{creep(ad, label, code) / creep(ad, 'fixed', code) - 1:+.1e} |")
    return "\n".join(lines)


def creep(ad, label, code):
    """Top u_z at the end of the creep minus at the end of the ramp [mm]."""
    x = ad["runs"][label][code]
    return x["u_end"] - x["u_load"]


def head(store):
    pv, m = store["provenance"], store["method"]
    plans = m["plans"]
    full, short = plans.get("full"), plans.get("short")
    inc = (f'"full" is the {full["increments"]} increments of input/abaqus (hold {num(full["hold"])} s, ramp the top '
           f'pressure to its creep value in {num(full["ramp"])} s, creep {num(full["creep"])} s)' if full else "")
    inc += (", " if full and short else "") + (f'"short" the first increments of each phase ({short["increments"]})'
                                                 if short else "")
    note = f" {pv['note']}" if pv.get("note") else ""
    end = pv["finished"][11:] if pv["finished"][:10] == pv["date"][:10] else pv["finished"]
    return [TITLE, "", f"Command: `{pv['command']}`. Run {pv['date']} to {end}, the driver at {pv['rev']}, "
            f"CalculiX {pv['calculix']}; load average {pv['load']['start'][0]:.1f} at the start and {pv['load']['end'][0]:.1f} "
            f"at the end ({pv['cores']} cores shared with other jobs: take the times as rough, compare CPU beside wall).{note}",
            "", f"One gmsh mesh per row (meshes/cylinder.geo), run by the driver (P1 tetrahedra, one point) and by CalculiX "
            f"{pv['calculix']} (C3D4, one point), with the same UMAT, PROPS (tol = {num(m['tol_fixed'])}), per-element phi "
            "(the driver's draw of input/triaxial.yaml, written into CalculiX as one material per element), supports, "
            f"pressures and fixed increments: {inc}. How: python/camclay9/calculix_mesh.py, docs/calculix.md. "
            "**Agreement**, worst relative difference over all increments (per element: over the field outputs at the "
            "end of each phase); the full-precision columns need the traced CalculiX and are left out where tets x "
            f"increments exceed {m['trace_max']}:", ""]


def time_text(store):
    t, meshes = store["method"]["target"], store["meshes"]
    old = any(x["code"] == "driver" and x["options"] == OLD for r in meshes for x in r["runs"])
    return ("**Time.** Process wall and CPU time (user + system), medians of the repeats, runs interleaved (each "
            "configuration once per round). The driver on one rank; CalculiX with SPOOLES, its `*CONTROLS` residual "
            "and correction ratios as tight as the driver's Newton (docs/calculix.md, \"Precision\"; it symmetrises "
            "DDSDDE, so its Newton converges linearly and takes more iterations). Both times include start-up and input "
            "(CalculiX reads one material per element). The driver's default solver (docs/driver.md, \"Solvers\"): "
            "MUMPS inside GMRES, its factorisation kept across Newton iterations and steps while the Krylov iterations "
            "stay few, the Jacobian assembled by COO"
            + (f"; the option `{OLD}` is the set-up before issue 13's solver work (a fresh MUMPS factorisation at every "
               "Newton iteration, MatSetValues)" if old else "")
            + f". Issue 13 asks for the default to be at least {num(1 / t['ratio'])}x faster per increment than CalculiX "
            f"from {num(t['from_tets'])} tets on: the last column at most {num(t['ratio'])}.")


def adaptive_text(ad, store):
    full = store["method"]["plans"].get("full", {})
    return (f"**Adaptive** ({ad['ntet']} tets, one run each). Each code's own incrementation with PROPS(20) = tol = "
            f"{num(ad['tol'])} as input/triaxial.yaml: the driver's worst-point control (PNEWDT), CalculiX's automatic "
            "incrementation (first, minimum and maximum increments of input/abaqus' cylinder; it grows by its iteration "
            "counts and cuts where the UMAT's PNEWDT asks). Creep = top u_z at the end of the creep minus at the end of "
            "the ramp, against the same code's fixed"
            + (f" {full['increments']}" if "increments" in full else "") + " increments.")


def span(values, fmt):
    lo, hi = min(values), max(values)
    return fmt.format(lo) if fmt.format(lo) == fmt.format(hi) else f"{fmt.format(lo)}–{fmt.format(hi)}"


def loaded(pv):
    """A caution when the machine had more work than cores during the run, else ""."""
    top = max(pv["load"]["start"][0], pv["load"]["end"][0])
    return (f"; measured at a load average of {pv['load']['start'][0]:.1f} to {pv['load']['end'][0]:.1f} on {pv['cores']} "
            "cores, so the ratios are rough" if top > pv["cores"] else "")


def reading(store):
    """The reading's bullets, every number computed from the store."""
    meshes, t = store["meshes"], store["method"]["target"]
    out = []
    traced = [r for r in meshes if r["agree"]]
    if traced:
        worst = max(((r["agree"][k], k, r["ntet"]) for r in traced for k in AGREE_KEYS))
        out.append(f"- **Agreement.** On the traced meshes ({', '.join(str(r['ntet']) for r in traced)} tets) the two codes "
                   f"agree to {worst[0]:.1e} or better in every compared quantity (the worst: {worst[1]} on {worst[2]} "
                   "tets).")
    p = max(meshes, key=lambda r: r["printed"])
    bound = 0.5 * 10.0 ** (1 - p["printed_digits"])
    out.append(f"- **Printed top u_z.** On every mesh the mean top u_z agrees to {p['printed']:.1e} or better "
               f"({p['ntet']} tets the worst), {'within' if p['printed'] <= bound else 'beyond'} half a unit of CalculiX's "
               f"last printed digit ({bound:.0e} relative at most).")
    big = [(r, per_increment(default_run(r), reference(r))) for r in meshes if r["ntet"] >= t["from_tets"] and default_run(r)]
    if big:
        met = all(w <= t["ratio"] and c <= t["ratio"] for _, (w, c) in big)
        out.append(f"- **Issue 13's target {'is met' if met else 'is not met'}.** Per increment the default takes "
                   + ", ".join(f"{w:.2f} of CalculiX's wall and {c:.2f} of its CPU on {r['ntet']} tets" for r, (w, c) in big)
                   + f" (at most {num(t['ratio'])} asked){loaded(store['provenance'])}.")
    olds = [(x["cpu"] / x["steps"]) / (default_run(r)["cpu"] / default_run(r)["steps"])
            for r in meshes if default_run(r) for x in r["runs"] if x["code"] == "driver" and x["options"] == OLD]
    if olds:
        out.append(f"- **The set-up before issue 13** takes {span(olds, '{:.2f}')}× the default's CPU per increment.")
    its = [reference(r)["its"] / default_run(r)["its"] for r in meshes if default_run(r)]
    if its:
        out.append(f"- **Newton.** On the same increments CalculiX takes {span(its, '{:.1f}')}× the driver's Newton "
                   "iterations.")
    ad = store["adaptive"]
    if ad:
        dd, dc = (creep(ad, "adaptive", c) / creep(ad, "fixed", c) - 1 for c in ("driver", "calculix"))
        apart = abs(creep(ad, "adaptive", "calculix") / creep(ad, "adaptive", "driver") - 1)
        d, c = ad["runs"]["adaptive"]["driver"], ad["runs"]["adaptive"]["calculix"]
        out.append(f"- **Adaptive.** The adaptive creep differs from the fixed increments' by {dd:+.1e} (driver) and "
                   f"{dc:+.1e} (CalculiX), the two adaptive runs by {apart:.0e} from each other. CalculiX rejected "
                   f"{c['cutbacks']} of its {c['steps'] + c['cutbacks']} attempts and took {c['its']} Newton iterations "
                   f"against the driver's {d['its']} ({c['cpu'] / d['cpu']:.1f}× its CPU).")
    return out


def section(store, root=None):
    """The section's text from the store: command and machine, the method, the agreement and time tables, the
    adaptive study, the reading. `root` is unused (the uniform call of tools/doc_numbers.py)."""
    meshes = checked(store)
    lines = head(store) + [agreement_table(meshes), "", time_text(store), "", time_table(meshes)]
    if store["adaptive"]:
        lines += ["", adaptive_text(store["adaptive"], store), "", adaptive_table(store["adaptive"])]
    lines += ["", "**Reading** (computed from docs/results/calculix.json):", ""] + reading(store)
    return "\n".join(lines) + "\n"
