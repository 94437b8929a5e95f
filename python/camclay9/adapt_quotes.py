"""The reading of the adapted meshes (bench/adapt_conclusions.md, which docs/performance.md's section "Adapted meshes"
carries): the helpers its quotes use, on bench/adapt_bench.py's store (docs/results/adapt_bench.json), and its lines
that hold numbers (LINES), checked and written by tools/doc_numbers.py like every other quote (camclay9.doc_quotes).

The store keeps, beside the cases run with the indicator as it is, the same cases as they were run with the indicator
before its contact-surface term ("before_contact_term"), so that the reading compares the two from runs."""
from . import results_store

BAND = (0.5, 2.0)      # the effectivities the issue asks for
MEASURABLE = 2e-3      # a level's true error must be at least the references' own uncertainty (0.2 %)


def effectivities(cases):
    """(case, level, output, effectivity) of every level with a stated error whose true error is measurable."""
    out = []
    for case, r in cases.items():
        ref = r.get("reference") or {}
        for lv in r["levels"]:
            for q, v in lv["q"].items():
                e, rv = lv["e"].get(q), ref.get(q)
                if q == "h_max" or rv is None or e is None or e != e or abs(v / rv - 1) < MEASURABLE:
                    continue
                out.append((case, lv["level"], q, e / abs(v - rv)))
    return out


def helpers(store_dir=None):
    """The quotes' names: lvq, lve, lvc (a level's value, its error against the case's reference, its change against
    another level; before=True: the level as run before the contact term), effs (the measurable effectivities, now or
    before) and in_band (how many lie in BAND)."""
    store = results_store.load("adapt_bench", store_dir)
    now, before = store.get("cases", {}), store.get("before_contact_term", {}).get("cases", {})

    def level(case, k, before_term):
        return (before if before_term else now)[case]["levels"][k]

    def lvq(case, k, q, before_term=False):
        return level(case, k, before_term)["q"][q]

    def lvu(case, k, before_term=False):
        return level(case, k, before_term)["unknowns"]

    def lve(case, k, q, before_term=False):
        return lvq(case, k, q, before_term) / (before if before_term else now)[case]["reference"][q] - 1

    def lvc(case, a, b, q, before_term=False):
        return abs(lvq(case, a, q, before_term) / lvq(case, b, q, before_term) - 1)

    def effs(which="now", case=None):
        """The measurable effectivities of every case (or of `case`), now or "before" the contact term."""
        return [x[3] for x in effectivities(now if which == "now" else before) if case in (None, x[0])]

    def in_band(values):
        return sum(BAND[0] <= v <= BAND[1] for v in values)

    return dict(lvq=lvq, lvu=lvu, lve=lve, lvc=lvc, effs=effs, in_band=in_band, range=range)


AD = "docs/adapt.md"
ADAPT_MD = [  # docs/adapt.md, "Which field" (the levels before the contact term) and "The contact surface"
    "before the contact term below) the kerogen sector's level 2 («th(lvu('sector', 2, True))» unknowns) is within 1 % of its converged answer",
    "in all three outputs (creep depth «pc(lve('sector', 2, 'creep', True), 2)», against −1.45 % on the stress alone at 8 872 unknowns), but",
    "loading_rate_a1's level 2 did not move (creep depth «f(lvq('lr1', 2, 'creep', True), 2)» against 35.19 nm on the stress alone).",
    "«pu(lvc('bn', 2, -1, 'h_res'))» from its last level's «f(lvq('bn', -1, 'h_res') / 1e3, 3)» µm, where before the term level 2 was «pu(lvc('bn', 2, -1, 'h_res', True))» from",
    "«f(lvq('bn', -1, 'h_res', True) / 1e3, 3)» µm. The kerogen sector's level 1 gains in creep depth («pc(lve('sector', 1, 'creep'))» against «pc(lve('sector', 1, 'creep', True))» before),",
    "and its level 2 stays within 1 % (creep depth «pc(lve('sector', 2, 'creep'), 2)», residual depth «pc(lve('sector', 2, 'h_res'), 2)»; before «pc(lve('sector', 2, 'creep', True), 2)» and",
    "«pc(lve('sector', 2, 'h_res', True), 2)»). On the 2D loading-rate scene the level-2 answer moves within the meshes' noise (creep depth «pc(lve('lr1', 2, 'creep'), 2)»",
    "against «pc(lve('lr1', 2, 'creep', True), 2)» before). The levels' stated errors lie in [0.5, 2] of their true errors in «in_band(effs())» of",
    "the «len(effs())» measurable cases, against «in_band(effs('before'))» of «len(effs('before'))» before.",
]
CONCLUSIONS = "bench/adapt_conclusions.md"
LINES = [  # the reading's lines that hold numbers (bench/adapt_conclusions.md)
    "- **Where adaptation pays: the 3D nanoindentation.** The kerogen sector's level 2 («th(ad('sector', 2).unknowns)» unknowns, «f(ad('sector', 2).umat_calls / 1e6, 1)» M UMAT",
    "  calls) is within «pu(max(abs(lve('sector', 2, q)) for q in ('P', 'creep', 'h_res')))» of the converged 3D answer in all three outputs. On hand-picked uniform zones the first",
    "  mesh within 1 % in all three has «th(kr('sector2_0.05').unknowns)» unknowns (h_tip 0.05 µm; the 3D mesh study above), and the shipped scene's («th(kr('sector2_0.12').unknowns)» unknowns)",
    "  is «pc(err3('sector2_0.12').P)», «pc(err3('sector2_0.12').creep)» and «pc(err3('sector2_0.12').h_res)» off. `input/nanoindent_kerogen_sector_adapt.yaml` runs these levels, and a second",
    "  run into the same directory runs only the last one («f(ad('sector', 2).cpu, 0)» s CPU here). The issue's 15 s for an answer within 1 % is not",
    "  reached: level 1 («th(ad('sector', 1).unknowns)» unknowns, «f(ad('sector', 1).cpu, 0)» s) is «pc(lve('sector', 1, 'creep'))» in creep depth («pc(lve('sector', 1, 'creep', True))» before the contact term).",
    "  converges far more slowly: its level 4 («th(ad('sector_p1', 4).unknowns)» unknowns, «f(ad('sector_p1', 4).umat_calls / 1e6, 1)» M UMAT calls) is still «pc(lve('sector_p1', 4, 'P'))» in the load,",
    "  «pc(lve('sector_p1', 4, 'creep'))» in the creep depth and «pc(lve('sector_p1', 4, 'h_res'))» in the residual depth. Linear tetrahedra are too stiff for the tip's",
    "- **Where it does not: the 2D loading-rate scene.** From a coarse start («th(ad('lr1', 0).unknowns)» unknowns) the levels reach the",
    "  shipped mesh's accuracy at about its size (level 2: «th(ad('lr1', 2).unknowns)» unknowns; creep depth «pc(lve('lr1', 2, 'creep'), 2)», residual depth «pc(lve('lr1', 2, 'h_res'), 2)», depth",
    "  at the end of loading «pc(lve('lr1', 2, 'h_max'), 2)»; the shipped mesh has «th(isp('loading_rate_a1').unknowns)» unknowns), not the issue's 60 s. Its error sits where the",
    "  the term level 2 was «pc(lve('lr1', 2, 'creep', True), 2)» in creep depth and «pc(lve('lr1', 2, 'h_res', True), 2)» in residual depth. The shipped loading-rate scenes keep",
    "- **BN and BP: the residual depth.** On BN's uniform P2 zones it rises «pu(min(b / a - 1 for a, b in zip(bn.p2.h_res[:-1], bn.p2.h_res[1:])))»–«pu(max(b / a - 1 for a, b in zip(bn.p2.h_res[:-1], bn.p2.h_res[1:])))» per refinement (the 3D mesh study above), so",
    "  the shipped meshes' values are lower bounds. On the adapted levels BN's rises «', '.join(f(lvq('bn', k, 'h_res') / 1e3, 3) for k in range(5))» µm: level 2",
    "  («th(ad('bn', 2).unknowns)» unknowns) is «pu(lvc('bn', 2, 4, 'h_res'))» from level 4, where before the contact term level 2 was «pu(lvc('bn', 2, 4, 'h_res', True))» from its level 4",
    "  («', '.join(f(lvq('bn', k, 'h_res', True) / 1e3, 3) for k in range(5))» µm). The last two levels («th(ad('bn', 3).unknowns)» and «th(ad('bn', 4).unknowns)» unknowns) agree within «pu(lvc('bn', 3, 4, 'h_res'), 2)», «pu(lvq('bn', 4, 'h_res') / 1e3 / bn.twin_h_res - 1)» above the",
    "  axisymmetric twin's «f(bn.twin_h_res, 3)» µm and «pu(lvq('bn', 4, 'h_res') / 1e3 / bn.p2.ship.h_res - 1, 0)» above the shipped uniform mesh's «f(bn.p2.ship.h_res, 3)» µm. BP's rises «', '.join(f(lvq('bp', k, 'h_res') / 1e3, 3) for k in range(4))» µm",
    "  (the last two within «pu(lvc('bp', 2, 3, 'h_res'), 2)», «th(ad('bp', 2).unknowns)» and «th(ad('bp', 3).unknowns)» unknowns), «pu(lvq('bp', 3, 'h_res') / 1e3 / bp.p2.ship.h_res - 1, 0)» above the shipped mesh's «f(bp.p2.ship.h_res, 3)» µm. The loads (BN",
    "  «th(min(lvq('bn', k, 'P') for k in range(5)) / 1e3, 0)»–«th(max(lvq('bn', k, 'P') for k in range(5)) / 1e3, 0)» mN, BP «th(min(lvq('bp', k, 'P') for k in range(4)) / 1e3, 0)»–«th(max(lvq('bp', k, 'P') for k in range(4)) / 1e3, 0)» mN) and creep depths from level 1 on (BN «f(min(lvq('bn', k, 'creep') for k in range(1, 5)), 0)»–«f(max(lvq('bn', k, 'creep') for k in range(1, 5)), 0)» nm;",
    "  BP «f(min(lvq('bp', k, 'creep') for k in range(1, 4)), 0)»–«f(max(lvq('bp', k, 'creep') for k in range(1, 4)), 0)» nm) agree with the uniform ladders. `input/microindent_BN_sector_adapt.yaml` (three reruns) and",
    "  100 nm. P1 from the twin's mesh (**sphere**): from level 1 on («th(ad('sphere', 1).unknowns)» unknowns) the load, creep and residual depths are",
    "  within «pu(max(abs(lve('sphere', k, q)) for k in (1, 2, 3) for q in ('P', 'creep', 'h_res')), 2)» of a P2 run on its own adapted meshes, errors within the reference's own uncertainty, so no",
    "  effectivity can be measured there. The axisymmetric kerogen twin (**axi**): from level 1 on within «pu(max(abs(lve('axi', k, q)) for k in (1, 2, 3) for q in ('P', 'creep', 'h_res')), 2)» of its reference.",
    "  From a coarse first mesh (**sphere_coarse**, h_tip 0.1 µm, «th(ad('sphere_coarse', 0).unknowns)» unknowns) the levels' errors are measurable: «in_band(effs('now', 'sphere_coarse'))» of its",
    "  «len(effs('now', 'sphere_coarse'))» effectivities lie in [0.5, 2] («in_band(effs('before', 'sphere_coarse'))» of «len(effs('before', 'sphere_coarse'))» before the contact term). The elastic sphere of Hertz's contact, whose load is",
    "  least 0.2 %) it lies in [0.5, 2] in «in_band(effs())» of «len(effs())» cases, «sum(e < 0.5 for e in effs())» below and «sum(e > 2 for e in effs())» above (before the contact term: «in_band(effs('before'))» of «len(effs('before'))», «sum(e < 0.5 for e in effs('before'))» below,",
    "  «sum(e > 2 for e in effs('before'))» above). The ones above are where a level's answer lies closer than its levels' changes say, which no",
]
QUOTES = [(AD, line) for line in ADAPT_MD] + [(CONCLUSIONS, line) for line in LINES]
