"""The numbers that hand-written text quotes from the results store (docs/results/*.json): README.md and the readings
of docs/performance.md. Each quote is (document, text), the text with «expression» where a number stands; the
expression is evaluated on the stores (namespace() below) and formatted by the helpers pc (signed per cent, "−4.7 %"),
pu (unsigned per cent), f (fixed decimals) and g (any format spec). tools/doc_numbers.py checks that each quote, its
numbers computed from the store, stands in its document, and --write puts the store's numbers into it.

Coverage: every number of README's main-job paragraph and of its table rows for the 3D kerogen, BN and BP scenes,
the axisymmetric twin, the 2D loading-rate and bedding scenes and the triaxial scenes, and the quick-look paragraph
below the table (the shipped scenes' CPU times from bench/indent_speed_bench.py, indent_speed.json; the adapted
scenes' errors and CPU from bench/adapt_bench.py, adapt_bench.json), except costs quoted from other benches' prose (the
kerogen sector's idle-machine figures, kept in indent3d.json); docs/parallel.md's solver choice and memory budget
(bench/scaling_bench.py, fe_scaling.json);
the numbers of docs/contact.md's reading "The field split" (bench/contact_solver_bench.py, contact_solver.json; the
quotes in camclay9.contact_quotes);
those of docs/calibrate.md's 300 s drift hold (bench/calibrate_coverage.py, calibrate_coverage.json); the
effectivities and the kerogen sector's shares of docs/adapt.md's "The time-step error" (bench/time_error_bench.py,
time_error.json; not its rounded bounds for the triaxial stage, "17–200 times", "below 0.03 %"); and those of
the 3D section's reading (bench/indent_convergence_conclusions.md, which docs/performance.md carries): the numbers of
camclay9.indent3d_study.numbers(), from the 3D ladders' store (indent_convergence.json), the adapted levels
(adapt_bench.json) and the few figures carried over in indent3d.json.
"""
import re
import statistics

from camclay9 import (adapt_quotes, contact_quotes, contact_solver_study, coverage_study, half_model_study, indent3d_study,
                      indent_models_study, loading_steps_study, paper_doc_tri, results_store)
from camclay9.adapt_study import effectivity
from camclay9.indent2d_study import key


MINUS = "\u2212"


def pc(x, d=1):
    return f"{x * 100:+.{d}f} %".replace("-", MINUS)


def pu(x, d=1):
    return f"{abs(x) * 100:.{d}f} %"


def f(x, d=1):
    return f"{x:.{d}f}".replace("-", MINUS)


def g(x, spec):
    return format(x, spec)


def th(x, d=0):
    """Fixed decimals, thousands apart by a space ("1 057.0")."""
    return f"{x:,.{d}f}".replace(",", " ")


class A(dict):
    """A dict whose keys read as attributes too (k.reference.P)."""

    def __getattr__(self, name):
        try:
            v = self[name]
        except KeyError:
            raise AttributeError(name) from None
        return A(v) if isinstance(v, dict) else v


S3, S2 = ("sector0.12", "sector0.0707", "sector0.05", "sector0.0425", "sector0.034"), ("axi1", "axi2")  # bench/contact_solver_bench.py's 3D and 2D cases
BIG, MIL = "sector0.018", "sector0.019"  # its cases at 1.21 M and 1.03 M unknowns (field split alone)
G, LU = "fieldsplit, GAMG on P2", "fieldsplit, LU on u"  # its field split with GAMG on the P2 block; with the block solved exactly
FT = contact_solver_study.FORCING  # ... with GMRES' tolerance by the inexact Newton forcing term (-indent_ksp_ew)
SP, R2 = "fieldsplit, simple partition", "ranks0.0425"  # its field split on the simple partition; its 2-rank partition case
DN, BO, CF = "drift_noise, drift: fit", "both, drift: fit", "clean, drift: fit"  # bench/calibrate_coverage.py's cases
CN, IG = "clean, drift: none", "ignored, drift: none"


def _fe_scaling(store_dir=None):
    """The quotes' helpers on bench/scaling_bench.py's store (docs/results/fe_scaling.json)."""
    fsr = results_store.load("fe_scaling", store_dir).get("rows", [])

    def fs(solver, ranks, n=None):
        """A row of bench/scaling_bench.py (docs/results/fe_scaling.json): the solver's on `ranks` ranks nearest n
        unknowns, or (n None) its largest."""
        sel = [A(r) for r in fsr if r["solver"] == solver and r["ranks"] == ranks]
        return max(sel, key=lambda r: r.unknowns) if n is None else min(sel, key=lambda r: abs(r.unknowns - n))

    def fkb(r):
        """An FE scaling row's resident set summed over its ranks per unknown [kB]."""
        return 1024 * r.rss_all / r.unknowns

    def fkpn(solver, ranks=1):
        """The FE scaling rows' Krylov iterations per Newton iteration of a solver: [smallest, largest]."""
        its = [r["krylov"] / r["newton"] for r in fsr if r["solver"] == solver and r["ranks"] == ranks]
        return [min(its), max(its)]

    return dict(fs=fs, fkb=fkb, fkpn=fkpn)


def _adapted(store_dir=None):
    """The quotes' helpers on bench/adapt_bench.py's store (docs/results/adapt_bench.json); before=True: a case as run
    before the indicator's contact term (the store's before_contact_term)."""
    store = results_store.load("adapt_bench", store_dir)
    cases = {False: store.get("cases", {}), True: store.get("before_contact_term", {}).get("cases", {})}

    def ad(case, level, before=False):
        """A level of bench/adapt_bench.py's case (docs/results/adapt_bench.json): cells, unknowns, cpu, q, e."""
        return A(cases[before][case]["levels"][level])

    def ade(case, level, q, before=False):
        """A level's error in output q relative to its case's reference."""
        return cases[before][case]["levels"][level]["q"][q] / cases[before][case]["reference"][q] - 1

    def adch(case, a, b, q, before=False):
        """The size of the change in output q from level b to level a, relative to level b."""
        lv = cases[before][case]["levels"]
        return abs(lv[a]["q"][q] / lv[b]["q"][q] - 1)

    def adf(case, level, q):
        """A level's stated mesh error over its difference from its case's reference in output q: the effectivity's rule
        (adapt_study.effectivity), here also against a reference that is not a converged answer."""
        lv = cases[False][case]["levels"][level]
        return effectivity(dict(cases[False][case]["reference"], converged=True), q, lv["q"][q], lv["e"][q])

    def adr(case):
        """A case's reference: its outputs and where they come from."""
        return A(cases[False][case]["reference"])

    def adc(case, levels):
        """The CPU seconds of a case's first `levels` levels: an adapted scene that runs them."""
        return sum(lv["cpu"] for lv in cases[False][case]["levels"][:levels])

    return dict(ad=ad, ade=ade, adch=adch, adf=adf, adc=adc, adr=adr, **adapt_quotes.helpers(store))


def _indent_speed(store_dir=None):
    """The quotes' helper on bench/indent_speed_bench.py's store (docs/results/indent_speed.json)."""
    isr = {(r["scene"], r["driver"]): r for r in results_store.load("indent_speed", store_dir).get("rows", [])}

    def isp(scene, driver="this tree"):
        """A scene's row of bench/indent_speed_bench.py (docs/results/indent_speed.json): cpu, steps, log_view, ..."""
        return A(isr[(scene, driver)])

    return dict(isp=isp)


def _half_model(store_dir=None):
    """The quotes' helper on bench/half_model_bench.py's store (docs/results/half_model.json)."""
    rows = {(r["scene"], r["model"]): r for r in results_store.load(half_model_study.STORE, store_dir).get("rows", [])}

    def hm(scene, model="half"):
        """A scene's row, model 'half' or 'whole'; cpu: its median CPU."""
        r = rows[(scene, model)]
        return A(r | {"cpu": half_model_study.cpu(r)})

    steps = results_store.load(loading_steps_study.STORE, store_dir)

    def lst(scene, variant="shipped"):
        """A scene's row of bench/loading_steps_bench.py's store (docs/results/loading_steps.json); cpu: its median."""
        r = loading_steps_study.rows_of(steps, scene)[variant]
        return A(r | {"cpu": loading_steps_study.cpu(r)})

    return dict(hm=hm, lst=lst)


def namespace(store_dir=None):
    paper = results_store.load("paper", store_dir)
    n = paper.get("numbers", {})
    tri = results_store.int_keys(n.get("triaxial", {}))
    i3, i2 = indent3d_study.numbers(store_dir), results_store.load("indent2d_convergence", store_dir)
    fe = results_store.load("fe_triaxial", store_dir)

    def rung2(sk, h_tip, r_fine, order=2):
        """A 2D study rung's errors against its scene's converged answer."""
        r = i2["rungs"][key(sk, order, h_tip, r_fine)]
        return A({k: r["o"][k] / i2["reference"][sk][k]["value"] - 1 for k in r["o"]} | {"cpu": r["cpu"], "unknowns": r["unknowns"]})

    def kr(key):
        """A kerogen rung of the 3D mesh study by its key ('sector2_0.12'): P, creep, h_res, unknowns, cpu, ..."""
        return A(i3["kerogen"]["rungs"][key])

    def err3(key):
        """A kerogen rung's errors against the converged 3D answer."""
        r, ref = i3["kerogen"]["rungs"][key], i3["kerogen"]["reference"]
        return A({k: r[k] / ref[k] - 1 for k in ("P", "creep", "h_res")})

    fe_row = {(r["size"], r["tol"], r["ranks"]): A(r) for r in fe.get("rows", [])}
    cs_rows = {(r["case"], r["solver"]): r for r in results_store.load("contact_solver", store_dir).get("rows", [])}

    def cs(case, solver, q):
        """A number of bench/contact_solver_bench.py's row (case, solver)."""
        return cs_rows[(case, solver)][q]

    cbs = results_store.load("calibrate_bench", store_dir)

    def cb(name):
        """An example of bench/calibrate_bench.py (docs/results/calibrate_bench.json) by its name."""
        return A(next(r for r in cbs["examples"] if r.get("name") == name))

    def cbe(name, p):
        """The relative error of an example's quoted parameter p against the truth the examples were made with."""
        return cb(name).quote[p]["value"] / cbs["true"][p] - 1

    holds = results_store.load("calibrate_coverage", store_dir).get("holds", {})
    cov, cov6 = holds.get("300", {}), holds.get("60", {})

    def cc(name, entry=cov):
        """A case of bench/calibrate_coverage.py --cases ("drift_noise, drift: fit", ...), the 300 s drift hold's or
        another entry's."""
        return A(next(r for r in entry["cases"] if r.get("name") == name))

    def cc6(name):
        """A case with the shipped protocol's 60 s drift hold."""
        return cc(name, cov6)

    def rmsz(rows):
        """The rms of a fault's errors in units of their reported standard errors (1 when those are right)."""
        return (sum(r["z"] ** 2 for r in rows) / len(rows)) ** 0.5

    def kbu(case, solver="fieldsplit", q="mem"):
        """A contact-solver row's peak memory per unknown [kB]: the largest rank's (mem) or all ranks' (mem_all)."""
        return 1000 * cs(case, solver, q) / cs(case, solver, "unknowns")

    def kpn(case, solver="fieldsplit"):
        """A contact-solver row's Krylov iterations per Newton iteration."""
        return cs(case, solver, "krylov") / cs(case, solver, "newton")

    def kps(case, stage, solver="fieldsplit"):
        """A fixed-step contact-solver row's Krylov iterations per solve in one stage (the bench's stage split)."""
        d = cs(case, solver, "stages")[stage]
        return d["krylov"] / d["solves"]

    def fband(coarse, fine, q):
        """The limits of output q that two rungs of the fixed-step ladder, (case, solver) each (h_tip from the case's
        name), give if its error falls as h_tip and as h_tip² (indent3d_study.bracket): (low, high)."""
        rungs = (coarse, fine)
        return indent3d_study.bracket([float(re.sub(r"^[a-z]+", "", c)) for c, _ in rungs],
                                      [cs(c, s, "outputs")[q] for c, s in rungs])

    def pcopies(case, solver="fieldsplit"):
        """A 2-rank row's vertices also held by the rank that does not own them [%] (the driver's 'partition:' line)."""
        return 100 * cs(case, solver, "partition")["copies"] / cs(case, solver, "partition")["vertices"]

    ims = {r["model"]: r for r in results_store.load("indent_models", store_dir).get("rows", [])}

    def im(model):
        """A row of bench/indent_models_bench.py (docs/results/indent_models.json) by its model's key."""
        return ims[model]

    def imd(model, q):
        """|a model's output q relative to the sector's, minus 1| (bench/indent_models_bench.py)."""
        return abs(ims[model][q] / ims["sector"][q] - 1)

    def ku(case):
        """A contact-solver case's unknowns in thousands as the readings print them ("5.9", "24", "190")."""
        n = next(r["unknowns"] for (c, _), r in cs_rows.items() if c == case) / 1000
        return f(n, 1 if n < 10 else 0)

    def csr(case, q, solver="fieldsplit", base="direct"):
        """The ratio of a field-split row's q to the direct path's (or base's) on the same case."""
        return cs(case, solver, q) / cs(case, base, q)
    te = results_store.load("time_error", store_dir).get("cases", {})

    def tef(case):
        """The effectivities (stated / true time-step error) of bench/time_error_bench.py's case, where measured."""
        return [r["effectivity"] for r in te[case]["rows"] if r["effectivity"] is not None]

    def tet(case, i=0, q="true"):
        """A time-step bench row's true (or stated) error relative to its case's reference; row 0: the shipped control."""
        return te[case]["rows"][i][q] / abs(te[case]["reference"])
    sc_rows = {(s["name"], r["variant"]): r["errors"] for part in results_store.load("step_control", store_dir).get("parts", {}).values()
               for s in part["scenes"] for r in s["rows"]}

    def stc(scene, q, variant="shipped"):
        """A scene's error in q against its fine-step reference (bench/step_control_bench.py, step_control.json)."""
        return sc_rows[(scene, variant)][q]
    ns = dict(meta=A(paper.get("meta", {})), pc=pc, pu=pu, f=f, g=g, min=min, max=max, abs=abs, float=float, zip=zip, tri=tri, ind=A(n.get("indent", {})),
              walls=A(paper.get("meta", {}).get("walls", {})), k=A(i3.get("kerogen", {})), bn=A(i3.get("BN", {})),
              bp=A(i3.get("BP", {})), i2=A(i2), rung2=rung2, err3=err3, kr=kr, half_over_sector=indent_models_study.half_over_sector(results_store.load(indent_models_study.STORE, store_dir)), fe=fe_row, cs=cs, csr=csr, kbu=kbu, kpn=kpn, kps=kps, fband=fband, ku=ku, S3=S3, S2=S2, BIG=BIG, MIL=MIL, G=G, LU=LU, FT=FT,
              pcopies=pcopies, SP=SP, R2=R2, im=im, imd=imd,
              tef=tef, tet=tet, stc=stc, cb=cb, cbe=cbe,
              cc=cc, cd=cov.get("draws", {}), cc6=cc6, cd6=cov6.get("draws", {}), covered=coverage_study.covered, rmsz=rmsz, sum=sum, len=len, median=statistics.median, DN=DN, BO=BO, CF=CF, CN=CN, IG=IG, th=th)
    ns.update(_fe_scaling(store_dir), **_adapted(store_dir), **_indent_speed(store_dir), **_half_model(store_dir))
    if 0 in tri and 90 in tri:
        ns.update(rd=A(paper_doc_tri.fig17_readings(tri)), f18=A(paper_doc_tri.fig18(tri)))
    return ns


PART = re.compile(r"«(.*?)»")
NUMBER = r"(?:[−+-]?(?:\d[\d., ]*\d|\d|X)(?: %)?)"   # what a «» place holds: a number, a list of them, or X


class QuoteError(Exception):
    """A quote whose expression the stores cannot compute (a reading written for other numbers)."""


def render(text, ns):
    """The quote's text with each «expression» replaced by its value; QuoteError where one cannot be computed."""
    def value(m):
        try:
            return str(eval(m.group(1), {"__builtins__": {}, **ns}))
        except (ArithmeticError, LookupError, TypeError, ValueError, AttributeError) as e:
            raise QuoteError(f"the quote '{text[:100]}' cannot be computed from the store ({type(e).__name__}: {e})") from e
    return PART.sub(value, text)


def pattern(text):
    """The quote's text with any numbers in its «» places, as a regular expression."""
    return "".join(re.escape(p) if i % 2 == 0 else NUMBER for i, p in enumerate(PART.split(text)))


def find(text, doc):
    """The place in doc where the quote's text stands with any numbers in its «» places, or None."""
    m = re.search(pattern(text), doc)
    return m.group(0) if m else None


R = "README.md"
C2, C3 = "bench/indent2d_convergence_conclusions.md", "bench/indent_convergence_conclusions.md"
CT = "docs/contact.md"
CA = "docs/calibrate.md"
AD = "docs/adapt.md"
PL = "docs/parallel.md"
PF = "docs/performance.md"
CAD = "bench/adapt_conclusions.md"
BNP3 = [  # the reading's lines that hold numbers (bench/indent_convergence_conclusions.md)
    "  Its load converges: on P2 «', '.join(th(x, 1) for x in bn.p2.P)» mN,",
    "  the shipped rung «pc(bn.p2.ship.P / bn.p2.P[-1] - 1, 2)» from the finest, and P1 approaches from above («', '.join(th(x, 1) for x in bn.p1.P)» mN).",
    "  Its creep depth settles within a few per cent on both (P2 «', '.join(f(x, 1) for x in bn.p2.creep)» nm; P1",
    "  «', '.join(f(x, 1) for x in bn.p1.creep)» nm).",
    "- **BN's residual depth is not converged on any uniform 3D mesh run**: P2 «', '.join(f(x, 3) for x in bn.p2.h_res)» µm, P1",
    "  «', '.join(f(x, 3) for x in bn.p1.h_res)» µm, rising by «pu(min(b / a - 1 for a, b in zip(bn.p2.h_res[:-2], bn.p2.h_res[1:-1])))» to «pu(max(b / a - 1 for a, b in zip(bn.p2.h_res[:-2], bn.p2.h_res[1:-1])))» per P2 refinement down to 1.25 µm,",
    '  then by «pu(bn.p2.h_res[-1] / bn.p2.h_res[-2] - 1)» to the finest rung («f(bn.p2.unknowns[-1] / 1e3, 0)» k unknowns).',
    "  «', '.join(f(x, 4) for x in bn.twin.h_res)» µm, within 0.1 % of its finest from h_tip «f(bn.twin_from_h_tip, 2)» µm on.",
    "  For kerogen the 3D and axisymmetric residual depths agree within «pu(err3('axi2_0.01').h_res)»",
    "  of unknowns. Meshes adapted to BN's answer converge it in 3D: «f(bn.adapted.h_res[0], 3)» and «f(bn.adapted.h_res[1], 3)» µm on levels of",
    '  «f(bn.adapted.unknowns[0] / 1e3, 1)» k and «f(bn.adapted.unknowns[1] / 1e3, 1)» k unknowns, «pu(bn.adapted.h_res[1] / bn.twin_h_res - 1)» above the twin\'s «f(bn.twin_h_res, 3)» µm (section "Adapted meshes"). Against them the',
    '  shipped mesh is «pc(bn.p2.ship.h_res / bn.adapted.h_res[-1] - 1)» and the finest uniform P2 rung «pc(bn.p2.h_res[-1] / bn.adapted.h_res[-1] - 1)»; the runs of Figs. 4–5 use the',
    "  «', '.join(g(x, '.4g') for x in bp.p2.h_tip)» µm (the rung at 3.54 µm stops under load control at a limit point of that coarse model,",
    "  listed above): load «', '.join(th(x, 1) for x in bp.p2.P)» mN, creep depth «', '.join(f(x, 1) for x in bp.p2.creep)» nm, residual depth",
    "  «', '.join(f(x, 3) for x in bp.p2.h_res)» µm. As BN's, its residual depth rises with refinement; the adapted meshes converge it at",
    '  «f(bp.adapted.h_res[0], 3)» and «f(bp.adapted.h_res[1], 3)» µm («f(bp.adapted.unknowns[0] / 1e3, 1)» k and «f(bp.adapted.unknowns[1] / 1e3, 1)» k unknowns), against which the shipped mesh is «pc(bp.p2.ship.h_res / bp.adapted.h_res[-1] - 1)».',
]


K3 = [  # the reading's lines that hold numbers (bench/indent_convergence_conclusions.md)
    "- **The converged 3D answer (kerogen)** is the sector's P2 ladder, down to h_tip 0.0354 µm («th(kr('sector2_0.03536').unknowns)» unknowns,",
    "  «f(kr('sector2_0.03536').cpu, 0)» s CPU, «f(kr('sector2_0.03536').rss_mb / 1e3, 1)» GB). Over its last three rungs the load falls monotonically («', '.join(f(x, 2) for x in k.p2.P[-3:])» µN) at order «f(k.p2.P_order, 2)»,",
    '  slowly, so the reference takes the middle of the finest rung and the Richardson limit («f(k.p2.P_limit, 2)» µN):',
    '  **P = «f(k.reference.P, 1)» µN ± «pu(k.reference.hw.P)»**. The creep and residual depths have no trend left over the same rungs',
    "  («', '.join(f(x, 2) for x in k.p2.creep[-3:])» nm; «', '.join(f(x, 2) for x in k.p2.h_res[-3:])» nm), so the reference is the finest rung, ± its change",
    '  from the rung before: **creep depth «f(k.reference.creep, 2)» nm ± «pu(k.reference.hw.creep)», residual depth «f(k.reference.h_res, 1)» nm ± «pu(k.reference.hw.h_res)»**.',
    '  («pc(tet(\'kerogen_sector\'), 2)» on the shipped mesh) is measured in "Stated time-step error" below.',
    "- **Checked on adapted meshes** (\"Adapted meshes\" below): the sector adapted to levels 4 and 5 («th(ad('sector', 4).unknowns)» and «th(ad('sector', 5).unknowns)» unknowns,",
    "  the same step control) agree within «pu(max(adch('sector', 4, 5, q) for q in ('P', 'creep', 'h_res')), 2)» in all three outputs and are «pc(adr('sector').P / k.reference.P - 1, 2)» in load, «pc(adr('sector').creep / k.reference.creep - 1, 2)» in creep depth",
    "  and «pc(adr('sector').h_res / k.reference.h_res - 1, 2)» in residual depth from this answer. The creep depth lies outside its ± «pu(k.reference.hw.creep)», the residual depth just outside",
    "  its ± «pu(k.reference.hw.h_res)»: a last change small by chance understates the ladder's uncertainty. The tables of this section keep this answer; the adapted meshes' are against level 5.",
    "- **P1 converges too slowly to check it.** The sector on P1 down to h_tip 0.025 µm («th(kr('sector1_0.025').unknowns)» unknowns,",
    "  «f(kr('sector1_0.025').cpu, 0)» s) is still «pc(err3('sector1_0.025').P)» in load, «pc(err3('sector1_0.025').creep)» in creep depth and «pc(err3('sector1_0.025').h_res)» in residual depth, and",
    '  its load converges at order «f(k.p1.P_order, 2)» over its last three rungs.',
    "  lay in coarse elements, and the creep depth jumped from rung to rung («f(kr('old1_0.1').creep, 2)», «f(kr('old1_0.07071').creep, 2)», «f(kr('old1_0.05').creep, 2)» nm on P1). At the scenes'",
    "  h_tip 0.05 µm it was «pc(err3('old1_0.05').creep, 0)» against the converged answer. With r_fine 0.9 µm the P1 creep depth rises monotonically",
    "  («', '.join(f(x, 2) for x in k.p1.creep)» nm).",
    "  h_far 4 and 8 h_tip, and the half model, an independent mesh) are «pc(err3('sector2_0.12').creep)», «pc(err3('sector2f8_0.12').creep)» and «pc(err3('half2_0.12').creep)» in creep",
    "  depth and «pc(err3('sector2_0.12').h_res)», «pc(err3('sector2f8_0.12').h_res)» and «pc(err3('half2_0.12').h_res)» in residual depth. At h_tip 0.1 µm the sector with h_far 4 and 8 h_tip",
    "  and the nested mesh (the 0.2 µm mesh split) are «pc(err3('sector2_0.1').creep)», «pc(err3('sector2f8_0.1').creep)» and «pc(err3('sector2n_0.1').creep)» in creep depth. So down to",
    "- **The shipped mesh** (the sector, P2, h_tip 0.12 µm, h_far 0.48 µm) is the cheapest within 2 %: «pc(err3('sector2_0.12').P)» in load, «pc(err3('sector2_0.12').creep)»",
    "  in creep depth and «pc(err3('sector2_0.12').h_res)» in residual depth, in «f(kr('sector2_0.12').cpu, 0)» s here. On an idle machine it took «k.shipped_cost.cpu_median» s (median of «k.shipped_cost.runs» runs;",
    "  «k.shipped_cost.umat_calls_M» M UMAT calls). Within 1 % in all three, the first uniform mesh is h_tip 0.05 µm («th(kr('sector2_0.05').unknowns)» unknowns, «f(kr('sector2_0.05').cpu, 0)» s). Adapted",
    "- **The axisymmetric twin** (the cone of equal area) converges fast: on P2 at h_tip 0.01 µm it gives «f(kr('axi2_0.01').P, 1)» µN, «f(kr('axi2_0.01').creep, 2)» nm",
    "  and «f(kr('axi2_0.01').h_res, 1)» nm. Against the 3D answer it is «pc(err3('axi2_0.01').P)» in load, «pc(err3('axi2_0.01').creep)» in creep depth and «pc(err3('axi2_0.01').h_res)» in residual depth: the tip's",
    "  shape. The 3D to axisymmetric load ratio is «f(k.reference.P / kr('axi2_0.01').P, 3)», below the elastic Berkovich/cone ratio «k.berkovich_cone_elastic» (docs/contact.md).",
    "  The shipped twin (P1, h_tip 0.02 µm) is «pc(err3('axi1_0.02').P)» in load, «pc(err3('axi1_0.02').creep)» in creep depth and «pc(err3('axi1_0.02').h_res)» in residual depth",
]


QUOTES = [
    # the stated time-step error against the true one (docs/adapt.md, "The time-step error"; bench/time_error_bench.py)
    (AD, "effectivity «f(min(tef('kerogen_axi')), 2)»–«f(max(tef('kerogen_axi')), 2)» on the\nkerogen twin (tol 0.03 to "
         "0.0025), «f(min(tef('kerogen_sector')), 2)»–«f(max(tef('kerogen_sector')), 2)» on the 3D kerogen sector and "
         "«f(min(tef('sphere')), 2)»–«f(max(tef('sphere')), 2)» on a sphere"),
    (AD, "time-step error of «pu(tet('kerogen_sector'), 2)» splits into «pu(tet('kerogen_sector_load'), 2)» from the load "
         "stage's steps and about «pu(tet('kerogen_sector') - tet('kerogen_sector_load'), 2)» from the hold's own. The\n"
         "stated «pu(tet('kerogen_sector', q='stated'), 2)» overstates"),
    (AD, "the triaxial cylinder's creep stage is stated «f(min(tef('triaxial')), 0)»–«f(max(tef('triaxial')), 0)»\n"
         "times its true error, which is at most «pu(max(abs(tet('triaxial', 0)), abs(tet('triaxial', 1)), "
         "abs(tet('triaxial', 2))), 3)»."),
    # the shipped protocol's 60 s drift hold (docs/calibrate.md, "Coverage"; bench/calibrate_coverage.py --cases)
    (CA, "the two noisy cases give «pc(cc6(DN).error, 2)» (± «pu(cc6(DN).se_rel, 2)») and «pc(cc6(BO).error, 2)» "
         "(± «pu(cc6(BO).se_rel, 2)»), at «f(cc6(DN).cpu / cc6(CF).cpu, 2)» and «f(cc6(BO).cpu / cc6(CF).cpu, 2)» times the CPU"),
    (CA, "and with the drift ignored «pc(cc6(IG).error, 0)» (the hold's trend warned)"),
    (CA, "noise leaves η_s a standard error of about «pu(cc6(DN).se_rel, 0)» on this record "
         "(«pu(median([r['se_rel'] for r in cd6['noise']]), 1)» with no drift to fit)"),
    (CA, "Over «len(cd6['noise'])» draws the truth lies within 2 reported standard errors in «covered(cd6['noise'])» with 1 nm of"),
    (CA, "depth noise, «covered(cd6['drift'])» with the drift alone"),
    (CA, "covers), «covered(cd6['drift_noise'])» with noise and drift, «covered(cd6['both'])» with load noise as well and "
         "«covered(cd6['ignored'])» with the drift ignored."),
    # is the standard error right (docs/calibrate.md, "Coverage"): the 300 s and 60 s draws
    (CA, "over the 300 s record's «len(cd['drift_noise'])» draws with noise and drift,"),
    (CA, "have an rms of «f(rmsz(cd['drift_noise']), 2)» (1 for a right standard error)"),
    (CA, "2 of them in «covered(cd['drift_noise'])». With 0.5 % load noise"),
    (CA, "With it the rms is «f(rmsz(cd['both']), 2)» and «covered(cd['both'])» of «len(cd['both'])» draws are covered "
         "(«pu(covered(cd['both']) / len(cd['both']), 0)»; the"),
    (CA, "60 s record: «covered(cd6['both'])» of «len(cd6['both'])»), the part a median «pu(median([r['se_load_rel'] for r in "
         "cd['both']]), 2)» of η_s against the whole standard error's «pu(median([r['se_rel'] for r in cd['both']]), 2)»."),
    (CA, "the noisy-load case's fit took «f(cc(BO).cpu / cc(CF).cpu, 2)» times the clean record's CPU (300 s hold; "
         "«f(cc6(BO).cpu / cc6(CF).cpu, 2)»"),
    # the 300 s drift hold (docs/calibrate.md, "Coverage"; bench/calibrate_coverage.py --drift-hold 300)
    (CA, "At the same truth the two cases give «pc(cc(DN).error, 2)»"),
    (CA, "(± «pu(cc(DN).se_rel, 2)») and «pc(cc(BO).error, 2)» (± «pu(cc(BO).se_rel, 2)»), at «f(cc(DN).cpu / cc(CF).cpu, 2)» "
         "and «f(cc(BO).cpu / cc(CF).cpu, 2)» times the CPU of the clean record's fit. Over «len(cd['drift_noise'])» draws"),
    (CA, "every error is within «pu(max(abs(r['error']) for r in cd['drift_noise']))» and the truth lies within 2 standard "
         "errors in «covered(cd['drift_noise'])» («pu(covered(cd['drift_noise']) "
         "/ len(cd['drift_noise']), 0)»)"),
    (CA, "as well, «sum(abs(r['error']) <= 0.02 for r in cd['both'])» of «len(cd['both'])» errors are within 2 % (the largest "
         "«pu(max(abs(r['error']) for r in cd['both']))») and «covered(cd['both'])» are covered "
         "(«pu(covered(cd['both']) / len(cd['both']), 0)»)"),
    (CA, "300 s record stopped at a local minimum («pc(cc(CN).error, 0)»; TAO reported no progress"),
    # BP's 3D calibration (docs/calibrate.md, "The paper's workflow in two steps"; bench/calibrate_bench.py)
    (CA, "η_s held): η_h «f(cb('micro_BP_3d_eta_hard').quote.eta_hard.value / 1e13, 5)»e13 from 3x low, "
         "«pc(cbe('micro_BP_3d_eta_hard', 'eta_hard'), 2)» (s.e. «pu(cb('micro_BP_3d_eta_hard').quote.eta_hard.relative_std_error, 2)»: "
         "the 1 Hz record misses the jump to 1 mN at t = 0"),
    (CA, "which the forward run then follows as straight lines), «cb('micro_BP_3d_eta_hard').forward_runs» forward runs, "
         "«f(cb('micro_BP_3d_eta_hard').cpu_s, 0)» s"),
    (CA, "CPU («f(cb('micro_BP_3d_eta_hard').wall_s / 60, 0)» min wall on a shared machine; measured once)"),
    *[(CT, line) for line in contact_quotes.CONTACT_MD],
    # the sector against its mirrored half and an independent mesh (docs/contact.md; bench/indent_models_bench.py)
    (CT,
         "On the shipped Cam-Clay IX kerogen scene (load, hold, unload; `bench/indent_models_bench.py`, docs/performance.md) the\n"
         "sector and the half model of three mirrored copies of its mesh agree to «f(1e6 * imd('mirrored', 'P'), 0)», «f(1e6 * imd('mirrored', 'creep'), 0)» and «f(1e6 * imd('mirrored', 'h_res'), 0)» parts per million in P, the creep depth and\n"
         "the residual depth, with the same «im('sector')['steps']» steps.\n"
         "\n"
         "Independently meshed with the sector's element sizes, the half of its hexagon differs from the sector by «pu(imd('hexhalf', 'P'))» in P,\n"
         "«pu(imd('hexhalf', 'creep'))» in the creep depth and «pu(imd('hexhalf', 'h_res'))» in the residual depth: the scatter from one mesh of this density to another"),
    # the partition on 2 ranks (docs/parallel.md, "The partition"; bench/contact_solver_bench.py's case ranks0.0425)
    (PL, "On the kerogen sector at «ku(R2)» k unknowns (bench case ranks0.0425, the first 4 steps on 2 ranks; docs/performance.md,\n"
         "\"Contact solve: direct against field split\") «f(pcopies(R2, SP), 0)» % of the vertices were held by both ranks with the\n"
         "simple partitioner and «f(pcopies(R2), 0)» % with PT-Scotch, and the simple cut took «f(csr(R2, 'cpu', SP, 'fieldsplit'), 2)»× the CPU and\n"
         "«f(csr(R2, 'mem', SP, 'fieldsplit'), 2)»× the largest rank's peak memory"),
    (PL, "«f(kbu(S3[1]), 0)» kB at «ku(S3[1])» k unknowns, «f(kbu(S3[3]), 0)» at «ku(S3[3])» k, «f(kbu(BIG), 1)» at "
         "«f(cs(BIG, 'fieldsplit', 'unknowns') / 1e6, 2)» M (the largest run here: «f(cs(BIG, 'fieldsplit', 'mem') / 1000, 1)» GB on one rank)"),
    (PL, "«f(kbu(S3[1], 'direct'), 0)» kB at «ku(S3[1])» k unknowns, «f(kbu(S3[3], 'direct'), 0)» at «ku(S3[3])» k and «f(kbu(S3[4], 'direct'), 0)» "
         "at «ku(S3[4])» k («f(cs(S3[4], 'direct', 'mem') / 1000, 1)» GB)"),
    # the adapted scenes (README's table; bench/adapt_bench.py, adapt_bench.json: the kerogen sector's, BN's and BP's cases)
    (R, "| «f(half_over_sector, 1)» times the sector's CPU (docs/performance.md"),
    (R, "(the kerogen half model: «f(half_over_sector, 1)» times) |"),
    (PF, "loading_rate_a1 and bedding_theta45 took «isp('loading_rate_a1').steps» and "
        "«isp('bedding_theta45').steps» steps,\n  «isp('loading_rate_a1').newton» and «isp('bedding_theta45').newton» Newton "
        "iterations after it, as before it (the store's run at 5ec347a, in git history); «isp('loading_rate_a1').stalled» and «isp('bedding_theta45').stalled» of their "
        "steps stalled"),
    (R, "its time steps «pc(tet('kerogen_sector'), 2)» in creep depth (docs/adapt.md, \"The time-step error\")"),
    (R, "P1 locks under the soft frame's nearly isochoric flow (creep depth «pc(rung2('lr', 0.02, 0.9, order=1).creep, 0)» on P1 at "
        "h_tip 0.02 µm, «pc(rung2('lr', 0.005, 0.4, order=1).creep, 0)» at 0.005 µm and «f(rung2('lr', 0.005, 0.4, order=1).cpu, 0)» s of "
        "CPU, against «pc(rung2('lr', 0.01414, 0.9).creep, 1)» for the uniform P2 zone shipped before on the whole block at «f(rung2('lr', 0.01414, 0.9).cpu, 0)» s)"),

    (R, "last level («f(ad('sector', 3).unknowns / 1000, 1)» k unknowns): load «pc(ade('sector', 3, 'P'), 2)», creep depth "
        "«pc(ade('sector', 3, 'creep'), 2)», residual depth «pc(ade('sector', 3, 'h_res'), 2)» against the sector adapted to level 5 "
        "(«f(ad('sector', 5).unknowns / 1000, 1)» k unknowns), whose creep depth «f(adr('sector').creep, 2)» nm is "
        "«pu(adr('sector').creep / k.reference.creep - 1, 2)» above the uniform ladder's converged answer"),
    (R, "its stated mesh error «pu(ad('sector', 3).e['P'] / ad('sector', 3).q['P'])», «pu(ad('sector', 3).e['creep'] / ad('sector', 3).q['creep'])» "
        "and «pu(ad('sector', 3).e['h_res'] / ad('sector', 3).q['h_res'])» in the three"),
    (R, "«f(adc('sector', 4), 0)» s CPU for the four levels, «f(ad('sector', 3).cpu, 0)» s for the last alone"),
    (R, "«f(adc('bn', 4), 0)» s CPU for its four levels on a loaded machine"),
    (R, "«f(adc('bp', 3), 0)» s CPU for its three levels on a loaded machine"),
    # the FE solvers' speed and memory (docs/parallel.md; bench/scaling_bench.py, fe_scaling.json)
    (PL, "GAMG is already faster at «fs('GAMG', 1, 46e3).unknowns» unknowns («f(fs('GAMG', 1, 46e3).solve_wall)» s against "
         "«f(fs('direct', 1, 46e3).solve_wall)» s of stepping)"),
    (PL, "At «fs('direct', 1).unknowns» unknowns GAMG's stepping took «f(fs('GAMG', 1, fs('direct', 1).unknowns).solve_wall)» s "
         "against the direct solve's «f(fs('direct', 1).solve_wall)» s (one rank, 4 steps), and "
         "«f(fs('GAMG', 1, fs('direct', 1).unknowns).rss / 1024)» GB instead of «f(fs('direct', 1).rss / 1024)» GB"),
    (PL, "GAMG needs «f(fkpn('GAMG')[0], 0)» to «f(fkpn('GAMG')[1], 0)» GMRES iterations per Newton iteration"),
    (PL, "GAMG: about «f(min(fkb(fs('GAMG', 1, n)) for n in (4e4, 1e5, 2.5e5)), 0)» kB per unknown on one rank "
         "(«f(fkb(fs('GAMG', 1)), 1)» kB at «fs('GAMG', 1).unknowns» unknowns, the largest run here: "
         "«f(fs('GAMG', 1).rss / 1024, 1)» GB, «f(fs('GAMG', 1).krylov / fs('GAMG', 1).newton, 0)» GMRES\n    iterations per "
         "Newton iteration), «f(fkb(fs('GAMG', 2)), 0)» kB on two at «fs('GAMG', 2).unknowns» unknowns."),
    (PL, "Direct solve: «f(fkb(fs('direct', 1, 4.6e4)), 0)» kB per unknown at «fs('direct', 1, 4.6e4).unknowns» unknowns, "
         "«f(fkb(fs('direct', 1)), 0)» kB at «fs('direct', 1).unknowns» on one rank"),
    (PL, "stepping of a GAMG run at «fs('GAMG', 2).unknowns» unknowns took «f(fs('GAMG', 2).solve_wall)» s on 2 ranks against "
         "«f(fs('GAMG', 1, fs('GAMG', 2).unknowns).solve_wall)» s on one"),
    # the main job (defects 1, 5): both readings of eq. 28's log, the run times, Fig. 18's window
    (R, "It takes «f(fe[(6, 1e-06, 2)].wall)» s wall on 2 quiet cores at the default mesh («fe[(6, 1e-06, 2)].cells» tets; "
        "docs/performance.md, \"FE: triaxial cylinder\") and «f(walls.triaxial_theta0)» s in docs/paper.md's latest run"),
    (R, "Read with ln, its creep is «f(rd.ln.early[0], 2)»× and «f(rd.ln.early[1], 2)»× the paper's fit at 385 s (θ = 0, 90) "
        "and «f(rd.ln.late[0], 2)»–«f(rd.ln.late[1], 2)»× from 1 to 10 h; read with log10, «f(rd.log10.early[0], 2)»× and "
        "«f(rd.log10.early[1], 2)»× at 385 s and «f(rd.log10.late[0], 2)»–«f(rd.log10.late[1], 2)»× from 1 to 10 h"),
    (R, "> 10× the hard one only until «f(f18.until[0], 0)» s (θ = 0) and «f(f18.until[90], 0)» s (θ = 90) of the 36 000 s"),
    (R, "(size 6 mm: «pu(fe[(6, 1e-06, 2)].err_10h, 2)» from the finest run at 10 h, with another φ draw) | "
        "«f(fe[(6, 1e-06, 2)].wall, 0)» s wall on 2 quiet cores (the main job above) |"),
    (R, "docs/paper.md (about «f(meta.wall_runs / 60, 0)» min on an idle"),
    # the kerogen sector (defect 3)
    (R, "(P2 to h_tip 0.035: P «f(k.reference.P, 1)» µN ± «pu(k.reference.hw.P)», creep depth «f(k.reference.creep, 2)» nm ± "
        "«pu(k.reference.hw.creep)», residual depth «f(k.reference.h_res, 1)» nm ± «pu(k.reference.hw.h_res)»): load at 200 nm "
        "«pc(err3('sector2_0.12').P)», creep depth «pc(err3('sector2_0.12').creep)», residual depth «pc(err3('sector2_0.12').h_res)»"),
    (R, "(against the sector adapted to level 5, whose creep depth is higher: creep depth «pc(kr('sector2_0.12').creep / adr('sector').creep - 1)», "
        "residual depth «pc(kr('sector2_0.12').h_res / adr('sector').h_res - 1)»)"),
    (R, "another mesh of this density is «pc(err3('sector2f8_0.12').h_res)» in residual depth"),
    (R, "«f(isp('nanoindent_kerogen_sector').cpu, 0)» s CPU on a shared machine (docs/performance.md, \"Indentation speed\"); "
        "on an idle machine «f(k.shipped_cost.cpu_median, 0)» s (median of «k.shipped_cost.runs»; «k.shipped_cost.umat_calls_M» M "
        "UMAT calls, «k.shipped_cost.ratio_to_umat»× their benchmark time; the mesh before: «f(k.shipped_cost.cpu_before_repick, 0)» s, "
        "creep «pc(err3('sector2f8_0.1').creep)»)"),
    (R, "an independent mesh of this density (the cube, h_tip 0.12) is «pc(err3('half2_0.12').P)» in load, "
        "«pc(err3('half2_0.12').creep)» in creep depth and «pc(err3('half2_0.12').h_res)» in residual depth"),
    (R, "«f(half_over_sector, 1)» times less CPU than the half model; P2 reaches the 3D answer where P1 at "
        "h_tip 0.05 µm is still «g(100 * min(abs(v) for v in err3('sector1_0.05').values()), '.0f')»–«pu(max(abs(v) for v in "
        "err3('sector1_0.05').values()), 0)» away at «f(kr('sector1_0.05').cpu / kr('sector2_0.12').cpu, 0)» times the CPU"),
    (R, "(a uniform zone within 1 % of that answer needs «f(kr('sector2_0.05').unknowns / 1e3, 0)» k unknowns)"),
    (R, "ladders of the sector on P2 (h_tip «g(bn.p2.h_tip[0], 'g')» to «g(bn.p2.h_tip[-1], '.3g')» µm, «f(bn.p2.unknowns[-1] / 1e3, 0)» k "
        "unknowns) and P1 («g(bn.p1.h_tip[0], 'g')» to «g(bn.p1.h_tip[-1], '.3g')» µm)"),
    (R, "a ladder of h_tip «', '.join(g(x, '.3g') for x in bp.p2.h_tip)» µm (P2, the last «f(bp.p2.cpu[-1], 0)» s CPU)"),
    # the axisymmetric twin (defect 3)
    (R, "«pc(err3('axi1_0.02').P)» in load against the 3D answer (the tip's shape; × «k.berkovich_cone_elastic», the elastic "
        "Berkovich/cone ratio, overshoots by «pu(kr('axi1_0.02').P * k.berkovich_cone_elastic / k.reference.P - 1)»: "
        "with creep the converged 3D and axisymmetric loads are «f(k.reference.P / kr('axi2_0.01').P, 2)»× apart), "
        "«pc(err3('axi1_0.02').creep, 0)» in creep depth, «pc(err3('axi1_0.02').h_res)» in residual depth; within "
        "«pu(kr('axi1_0.02').P / kr('axi2_0.01').P - 1)» (load) and "
        "«pu(kr('axi1_0.02').creep / kr('axi2_0.01').creep - 1)» (creep) of its own converged answer"),
    # BN and BP (defects 3, 6)
    (R, "the creep depth within «pu(max(abs(bn.p2.ship.creep / c - 1) for c in (bn.p2.creep[-1], bn.p1.creep[-1], bn.adapted.creep[-1])))» "
        "of the finest uniform P2 («f(bn.p2.creep[-1], 1)» nm), P1 («f(bn.p1.creep[-1], 1)» nm) and adapted («f(bn.adapted.creep[-1], 1)» nm) meshes"),
    (R, "+«g(100 * min(b / a - 1 for a, b in zip(bn.p2.h_res[1:], bn.p2.h_res[2:])), '.1f')»–«g(100 * max(b / a - 1 for a, b in "
        "zip(bn.p2.h_res[1:], bn.p2.h_res[2:])), '.0f')» % per refinement on P1 and P2 alike (P2: «', '.join(f(x, 2) for x in bn.p2.h_res[1:])» µm), so the shipped mesh's «f(bn.p2.ship.h_res, 3)» µm is "
        "«pc(bn.p2.ship.h_res / bn.adapted.h_res[-1] - 1, 0)» against the converged «f(bn.adapted.h_res[-1], 3)» µm "
        "(adapted meshes, `microindent_BN_sector_adapt.yaml`; the axisymmetric twin: «f(bn.twin_h_res, 3)» µm)"),
    (R, "| «f(isp('microindent_BN_sector').cpu, 0)» s CPU on a shared machine; «isp('microindent_BN_sector').steps» steps, "
        "«isp('microindent_BN_sector').rejected» rejected |"),
    (R, "the load «pc(bp.p2.ship.P / bp.p2.P[-1] - 1, 2)» from the finest rung, the creep depth within «pu(max(abs(c / bp.p2.ship.creep - 1) "
        "for c in bp.p2.creep[bp.p2.h_tip.index(bp.p2.shipped):]))» of the finer rungs', the residual "
        "depth «f(bp.p2.ship.h_res, 3)» µm, «pc(bp.p2.ship.h_res / bp.adapted.h_res[-1] - 1, 0)» against the converged "
        "«f(bp.adapted.h_res[-1], 2)» µm"),
    (R, "| «f(isp('microindent_BP').cpu, 0)» s CPU on a shared machine, «pu(isp('microindent_BP').log_view.factorisation / "
        "isp('microindent_BP').log_view.total, 0)» of its time in the contact solve's factorisations |"),
    # the axisymmetric twin's and the 2D scenes' CPU (bench/indent_speed_bench.py)
    (R, "of its own converged answer | «f(isp('nanoindent_kerogen_axi').cpu, 1)» s |"),
    (R, "in the full reproduction (docs/paper.md) «f(meta.cpus['loading_rate_a1'], 0)» s CPU for α = 1, «f(meta.cpus['loading_rate_a10'], 0)» s for α = 10 "
        "(both levels), «f(meta.cpus['loading_rate_a0.1'], 0)» s for α = 0.1 (three levels); the uniform zone shipped before: «f(lst('loading_rate_a1').cpu, 0)» s "
        "CPU for α = 1 (medians of «len(lst('loading_rate_a1').cpu_s)» runs, docs/performance.md, \"Indentation: the direct solver and the loading steps\") |"),
    (R, "residual depth «f(ad('bn', 1).q['h_res'] / 1e3, 2)» and «f(ad('bn', 2).q['h_res'] / 1e3, 2)» µm on its first two "
        "reruns, «f(ad('bn', 3).q['h_res'] / 1e3, 3)» µm on its last level («f(ad('bn', 3).unknowns / 1e3, 1)» k unknowns) and "
        "«f(ad('bn', 4).q['h_res'] / 1e3, 3)» µm one level further («f(ad('bn', 4).unknowns / 1e3, 1)» k): converged, "
        "«pu(ad('bn', 3).q['h_res'] / 1e3 / bn.twin_h_res - 1)» above the axisymmetric twin's «f(bn.twin_h_res, 3)» µm and "
        "«pu(ad('bn', 3).q['h_res'] / 1e3 / bn.p2.ship.h_res - 1, 0)» above the shipped mesh's «f(bn.p2.ship.h_res, 3)» µm |"),
    (R, "residual depth «f(ad('bp', 0).q['h_res'] / 1e3, 2)» and «f(ad('bp', 1).q['h_res'] / 1e3, 2)» µm on its first two "
        "levels, «f(ad('bp', 2).q['h_res'] / 1e3, 3)» µm on its last («f(ad('bp', 2).unknowns / 1e3, 1)» k unknowns) and "
        "«f(ad('bp', 3).q['h_res'] / 1e3, 3)» µm one level further («f(ad('bp', 3).unknowns / 1e3, 1)» k): converged, "
        "«pu(ad('bp', 2).q['h_res'] / 1e3 / bp.p2.ship.h_res - 1, 0)» above the shipped mesh's «f(bp.p2.ship.h_res, 3)» µm |"),
    (R, "| 2D twin of BN | as the kerogen twin | «f(isp('microindent_BN_axi').cpu, 1)» s |"),
    # the 2D scenes (defects 2, 10)
    (R, "docs/paper.md's runs: α = 1 depth at the end of loading «pc(ind.loading_rate_a1.depth_end_of_load / i2.reference.lr.h_max.value - 1)», creep depth "
        "«pc(ind.loading_rate_a1.creep_depth / i2.reference.lr.creep.value - 1)»; α = 10 «pc(ind.loading_rate_a10.depth_end_of_load / i2.reference.lr10.h_max.value - 1)» "
        "and «pc(ind.loading_rate_a10.creep_depth / i2.reference.lr10.creep.value - 1)»; α = 0.1 «pc(ind['loading_rate_a0.1']['depth_end_of_load'] / i2.reference.lr01.h_max.value - 1)» "
        "and «pc(ind['loading_rate_a0.1']['creep_depth'] / i2.reference.lr01.creep.value - 1)» (its answer an extrapolation, ± «pu(i2.reference.lr01.creep.hw)»); "
        "from the same coarse start with an unload added, α = 1's first rerun is «pc(ade('lr1', 1, 'h_res'), 2)» in residual depth"),
    (R, "The uniform zone shipped before (h_tip 0.0141 µm within 0.9 µm), at α = 1: depth at the end of loading «pc(rung2('lr', 0.01414, 0.9).h_max)», "
        "creep depth «pc(rung2('lr', 0.01414, 0.9).creep)», residual depth «pc(rung2('lr', 0.01414, 0.9).h_res)» (with an unload added), stress under the tip "
        "«pc(rung2('lr', 0.01414, 0.9).sig_hold)» and its change over the hold (Fig. 13's quantity) «pc(rung2('lr', 0.01414, 0.9).dsig)»; "
        "at α = 0.1 «pc(rung2('lr01', 0.01414, 0.9).creep)» in creep depth and at α = 10 «pc(rung2('lr10', 0.01414, 0.9).creep)»; the time steps "
        "«pc(stc('loading_rate_a1', 'creep depth'), 2)» in creep depth"),
    (R, "(at 20 k unknowns: creep «pc(rung2('bed', 0.3536, 10.0).creep)» against "
        "«pc(rung2('bed', 0.1768, 10.0, 1).creep)», residual depth «pc(rung2('bed', 0.3536, 10.0).h_res)» against "
        "«pc(rung2('bed', 0.1768, 10.0, 1).h_res)»)"),
    (R, "docs/paper.md's run at 45° against the converged 2D answer: depth at the end of loading "
        "«pc(ind.bedding_theta45.depth_end_of_load / i2.reference.bed.h_max.value - 1)», creep depth "
        "«pc(ind.bedding_theta45.creep_depth / i2.reference.bed.creep.value - 1)»"),
    (R, "The uniform mesh shipped before (h_tip 0.25 µm), at 45°: depth at the end of loading «pc(rung2('bed', 0.25, 10.0).h_max)», "
        "creep depth «pc(rung2('bed', 0.25, 10.0).creep)», stress under the tip «pc(rung2('bed', 0.25, 10.0).sig_hold)» (the residual "
        "depth, not reported by these scenes, «pc(rung2('bed', 0.25, 10.0).h_res)»); before the 2D study, P1: "
        "«pc(rung2('bed', 0.5, 10.0, 1).creep)» in creep, «pc(rung2('bed', 0.5, 10.0, 1).h_res)» in residual depth"),
    (R, "in the full reproduction (docs/paper.md) «f(min(meta.cpus[f'bedding_theta{t}'] for t in (0, 90)), 0)»–«f(max(meta.cpus[f'bedding_theta{t}'] "
        "for t in (0, 90)), 0)» s on the half model, «f(min(meta.cpus[f'bedding_theta{t}'] for t in (30, 45, 60)), 0)»–"
        "«f(max(meta.cpus[f'bedding_theta{t}'] for t in (30, 45, 60)), 0)» s on the whole block, both runs of each |"),
    # below the table (defect 3)
    (R, "were «f(kr('old1_0.05').cpu, 0)» s for the sector but «pc(err3('old1_0.05').P, 0)» in load and "
        "«pc(err3('old1_0.05').creep, 0)» in creep depth"),
    (R, "with `h_tip: 0.2` (P2, «f(kr('sector2_0.2').cpu, 0)» s CPU) are «pc(err3('sector2_0.2').P)» in load but "
        "«pc(err3('sector2_0.2').creep, 0)» in creep depth and «pc(err3('sector2_0.2').h_res, 0)» in residual depth"),
    # the readings written by hand beside the generated tables (bench/*_conclusions.md, included in docs/performance.md)
    (C2, "creep depth «f(i2.reference.lr.creep.value * 1e3, 2)» nm ± «pu(i2.reference.lr.creep.hw)», residual\n  "
         "depth «f(i2.reference.lr.h_res.value * 1e3, 2)» nm ± «pu(i2.reference.lr.h_res.hw)»; σ̄ at the hold's end "
         "«f(i2.reference.lr.sig_hold.value)» MPa and its change over the hold «f(i2.reference.lr.dsig.value)» MPa"),
    (C2, "depth at the end of loading «pc(rung2('lr', 0.01414, 0.9).h_max)», creep depth «pc(rung2('lr', 0.01414, 0.9).creep)», "
         "residual depth «pc(rung2('lr', 0.01414, 0.9).h_res)», σ̄\n  at the end of the hold «pc(rung2('lr', 0.01414, 0.9).sig_hold)»"),
    (C2, "Fig. 13's quantity Δσ̄ «pc(rung2('lr', 0.01414, 0.9).dsig)»"),
    (C2, "its creep depth, «f(ind.loading_rate_a1.creep_depth * 1e3, 2)» nm, is «pc(ind.loading_rate_a1.creep_depth / "
         "i2.reference.lr.creep.value - 1)»"),
    (C2, "converged creep depth «f(i2.reference.bed.creep.value * 1e3, 1)» nm ± «pu(i2.reference.bed.creep.hw)» (Richardson, "
         "p «f(float(i2.reference.bed.creep.rule.split('= ')[1]), 2)»), residual depth «f(i2.reference.bed.h_res.value * 1e3, 1)» nm ± "
         "«pu(i2.reference.bed.h_res.hw)»"),
    (C2, "(41 k unknowns, 130 s, 2.7 ×): «pc(rung2('bed', 0.25, 10.0).h_max)», «pc(rung2('bed', 0.25, 10.0).creep)», "
         "«pc(rung2('bed', 0.25, 10.0).h_res)», «pc(rung2('bed', 0.25, 10.0).sig_hold)»: within all four limits (✓);\n  Δσ̄ "
         "«pc(rung2('bed', 0.25, 10.0).dsig)». Before (P1, h_tip 0.5; 7 s): «pc(rung2('bed', 0.5, 10.0, 1).h_max)», "
         "«pc(rung2('bed', 0.5, 10.0, 1).creep)», «pc(rung2('bed', 0.5, 10.0, 1).h_res)», «pc(rung2('bed', 0.5, 10.0, 1).sig_hold)»"),
    # the 3D section's reading (bench/indent_convergence_conclusions.md, which its generated section carries), line by
    # line: the kerogen reference and ladders, the shipped mesh, the twin; BN's and BP's ladders, twins and adapted levels
    *[(C3, line) for line in K3],
    *[(C3, line) for line in BNP3],
    # docs/adapt.md's "Which field" and "The contact surface"; the adapted meshes' reading, line by line
    *[(AD, line) for line in adapt_quotes.ADAPT_MD],
    *[(CAD, line) for line in adapt_quotes.LINES],
]
