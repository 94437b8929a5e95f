"""The quotes of docs/contact.md's reading "The field split" (bench/contact_solver_bench.py's store,
docs/results/contact_solver.json): the lines that hold numbers, each with «expression» where a number stands, in
camclay9.doc_quotes' namespace (its contact-solver helpers cs, csr, kpn, kps, kbu, ku, fband and the case names S3, BIG, MIL,
R2, G, LU, FT); doc_quotes checks and writes them like every other quote."""

CONTACT_MD = [
    # the field split against the direct path (docs/contact.md, "The field split"; bench/contact_solver_bench.py)
    ("at «ku(S3[1])» k unknowns the p-multigrid took «f(kpn(S3[1]), 0)» Krylov iterations per Newton iteration where GAMG on the P2 block took\n"
         "  «f(kpn(S3[1], G), 0)», in «f(csr(S3[1], 'cpu', 'fieldsplit', G), 2)»× its CPU; at «ku(S3[3])» k, «f(kpn(S3[3]), 0)» against "
         "«f(kpn(S3[3], G), 0)» in «f(csr(S3[3], 'cpu', 'fieldsplit', G), 2)»×; at «f(cs(BIG, G, 'unknowns') / 1e6, 2)» M, «f(kpn(BIG), 0)» against "
         "«f(kpn(BIG, G), 0)» in «f(csr(BIG, 'cpu', 'fieldsplit', G), 2)»×"),
    ("The field split's peak memory is «f(kbu(S3[3]), 0)» kB per\n  unknown at «ku(S3[3])» k unknowns against the direct path's "
         "«f(kbu(S3[3], 'direct'), 0)», and «f(kbu(S3[4]), 0)» against «f(kbu(S3[4], 'direct'), 0)» at «ku(S3[4])» k; at "
         "«f(cs(BIG, 'fieldsplit', 'unknowns') / 1e6, 2)» M unknowns, beyond the direct\n  path's reach in 23 GB, «f(kbu(BIG), 1)» kB "
         "(«f(cs(BIG, 'fieldsplit', 'mem') / 1000, 1)» GB)"),
    ("The field split takes «f(csr(S3[0], 'cpu'), 2)»× the\n  direct path's CPU at «ku(S3[0])» k unknowns and «f(csr(S3[1], 'cpu'), 2)»× "
         "at «ku(S3[1])» k, then «f(csr(S3[2], 'cpu'), 2)»× at «ku(S3[2])» k, «f(csr(S3[3], 'cpu'), 2)»× at «ku(S3[3])» k and "
         "«f(csr(S3[4], 'cpu'), 2)»× at «ku(S3[4])» k"),
    ("the field split takes «f(csr('whole0.0707', 'cpu'), 2)»× the\n  direct path's CPU at «ku('whole0.0707')» k unknowns and "
         "«f(csr('whole0.05', 'cpu'), 2)»× at «ku('whole0.05')» k"),
    ("the direct path ran the same sector at «f(kr('sector2_0.03536').unknowns / 1e3, 0)» k\n  unknowns through its whole "
         "history in «f(kr('sector2_0.03536').rss_mb / 1e3, 1)» GB"),
    ("its factors, about «f(kbu(S3[4], 'direct'), 0)» kB per unknown at «ku(S3[4])» k and growing"),
    ("the field split takes «f(csr('lr1', 'cpu'), 1)»× its CPU on loading_rate_a1 (P2,\n  «ku('lr1')» k unknowns) and "
         "«f(min(csr(c, 'cpu') for c in S2), 1)»–«f(max(csr(c, 'cpu') for c in S2), 1)»× on the kerogen twin"),
    ("«f(kpn(S3[0]), 0)» at «ku(S3[0])» k unknowns, «f(kpn(S3[3]), 0)» at «ku(S3[3])» k and «f(kpn(BIG), 0)» at "
         "«f(cs(BIG, 'fieldsplit', 'unknowns') / 1e6, 2)» M with\n  the p-multigrid, «f(100 * (kpn(BIG) / kpn(S3[3]) - 1), 0)» % more from "
         "«ku(S3[3])» k to «f(cs(BIG, 'fieldsplit', 'unknowns') / 1e6, 2)» M; with GAMG on the P2 block «f(kpn(S3[0], G), 0)», "
         "«f(kpn(S3[3], G), 0)» and «f(kpn(BIG, G), 0)» («f(100 * (kpn(BIG, G) / kpn(S3[3], G) - 1), 0)» % more)"),
    # from 1e5 to 1e6 unknowns (the measure): bench case sector0.019
    ("  From 1e5 to 1e6 unknowns: «f(kpn(S3[3]), 1)» at «ku(S3[3])» k and «f(kpn(MIL), 1)» at «f(cs(MIL, 'fieldsplit', 'unknowns') / 1e6, 2)» M («f(100 * (kpn(MIL) / kpn(S3[3]) - 1), 0)» % more,\n"
         "  «f(kbu(MIL), 1)» kB per unknown). That is within 50 % at 1.03 M but not at 1.21 M: the growth goes on at about the\n"
         "  sixth root of the unknowns (the two meshes are «f(cs(MIL, 'fieldsplit', 'unknowns') / cs(S3[3], 'fieldsplit', 'unknowns'), 1)» and «f(cs(BIG, 'fieldsplit', 'unknowns') / cs(S3[3], 'fieldsplit', 'unknowns'), 1)» times the 101 k one), which is what an estimate of the Schur\n"
         "  complement by diag(K)⁻¹ gives, whose condition grows as 1/h (next item)"),
    # the fixed-step ladder's whole runs at Newton 1e-6 (bench cases fix...)
    ("  Under the whole contact the field split took «f(kpn('fix0.12'), 0)», «f(kpn('fix0.0707'), 0)», «f(kpn('fix0.0425'), 0)» and «f(kpn('fix0.034'), 0)» Krylov iterations per Newton\n"
         "  iteration at «ku('fix0.12')» k, «ku('fix0.0707')» k, «ku('fix0.0425')» k and «ku('fix0.034')» k unknowns, in «f(kbu('fix0.034', q='mem_all'), 1)» kB per unknown over both ranks at «ku('fix0.034')» k"),
    # the ladder's Krylov iterations per solve by stage (the bench's stage split)
    ("By stage, the Krylov iterations per solve at «ku('fix0.0425')» k and\n  «ku('fix0.034')» k unknowns: «f(kps('fix0.0425', 'load'), 0)» and «f(kps('fix0.034', 'load'), 0)» in the load,\n  «f(kps('fix0.0425', 'hold'), 0)» and «f(kps('fix0.034', 'hold'), 0)» in the hold, «f(kps('fix0.0425', 'unload'), 0)» and\n  «f(kps('fix0.034', 'unload'), 0)» in the unload"),
    # the 1.03 M rung's whole run with the forcing term (bench case fix0.019)
    ("The 1.03 M rung then ran its whole\n  load, hold and unload on these steps with the forcing term (bench row fix0.019, 'fieldsplit, forcing term', 2 ranks):\n  «cs('fix0.019', FT, 'steps')» steps, «cs('fix0.019', FT, 'newton')» Newton iterations, «f(kpn('fix0.019', FT), 1)» Krylov iterations per Newton iteration against «f(kpn('fix0.0425', FT), 1)» at «ku('fix0.0425')» k\n  unknowns («f(100 * (kpn('fix0.019', FT) / kpn('fix0.0425', FT) - 1), 0)» % more), in «f(kbu('fix0.019', FT, q='mem_all'), 1)» kB per unknown over both ranks and «f(cs('fix0.019', FT, 'cpu') / 3600, 1)» h of CPU. By stage, per\n  solve, against the 101 k rung's with the forcing term: «f(kps('fix0.019', 'load', FT), 0)» against «f(kps('fix0.0425', 'load', FT), 0)» in the load, «f(kps('fix0.019', 'hold', FT), 0)» against «f(kps('fix0.0425', 'hold', FT), 0)» in the hold,\n  «f(kps('fix0.019', 'unload', FT), 0)» against «f(kps('fix0.0425', 'unload', FT), 0)» in the unload"),
    # ... and its outputs against the 190 k rung's
    ("Its outputs differ from the «ku('fix0.034')» k rung's by «f(100 * (cs('fix0.019', FT, 'outputs')['P'] / cs('fix0.034', 'fieldsplit', 'outputs')['P'] - 1), 2)» % in the load at the end of loading,\n  «f(100 * (cs('fix0.019', FT, 'outputs')['creep'] / cs('fix0.034', 'fieldsplit', 'outputs')['creep'] - 1), 2)» % in the creep depth and «f(100 * (cs('fix0.019', FT, 'outputs')['h_res'] / cs('fix0.034', 'fieldsplit', 'outputs')['h_res'] - 1), 2)» % in the residual depth: on equal steps, the mesh's share alone"),
    # the inexact Newton forcing term against the tight solves on the ladder (bench solver 'fieldsplit, forcing term')
    ("ladder's fixed steps the forcing term took «f(csr('fix0.12', 'cpu', FT, 'fieldsplit'), 2)»×, «f(csr('fix0.0707', 'cpu', FT, 'fieldsplit'), 2)»×, «f(csr('fix0.0425', 'cpu', FT, 'fieldsplit'), 2)»× and «f(csr('fix0.034', 'cpu', FT, 'fieldsplit'), 2)»× the\n  tight solves' CPU at «ku('fix0.12')» k, «ku('fix0.0707')» k, «ku('fix0.0425')» k and «ku('fix0.034')» k unknowns, with «f(kpn('fix0.0425', FT), 0)» Krylov iterations per Newton iteration instead of\n"
         "  «f(kpn('fix0.0425'), 0)» and «f(cs('fix0.0425', FT, 'newton'), 0)» Newton iterations instead of «f(cs('fix0.0425', 'fieldsplit', 'newton'), 0)» at «ku('fix0.0425')» k."),
    # BN's sector on the same fixed steps (bench cases bnfix...): the residual depth on the uniform rungs
    ("  BN's sector on the same fixed steps (bench cases bnfix…: the same meshes at 25 times the size) took «f(kpn('bnfix3'), 0)», «f(kpn('bnfix1.768'), 0)»,\n"
         "  «f(kpn('bnfix1.062'), 0)» and «f(kpn('bnfix0.85'), 0)» Krylov iterations per Newton iteration at «ku('bnfix3')» k, «ku('bnfix1.768')» k, «ku('bnfix1.062')» k and «ku('bnfix0.85')» k unknowns. Its residual\n"
         "  depth still rises with each uniform rung: «f(cs('bnfix3', 'fieldsplit', 'outputs')['h_res'], 0)», «f(cs('bnfix1.768', 'fieldsplit', 'outputs')['h_res'], 0)», «f(cs('bnfix1.062', 'fieldsplit', 'outputs')['h_res'], 0)» and «f(cs('bnfix0.85', 'fieldsplit', 'outputs')['h_res'], 0)» nm, "
         "«f(100 * (cs('bnfix0.85', 'fieldsplit', 'outputs')['h_res'] / cs('bnfix1.062', 'fieldsplit', 'outputs')['h_res'] - 1), 1)» % from\n"
         "  «ku('bnfix1.062')» k to «ku('bnfix0.85')» k"),
    # BN's 1.03 M rung (bench row bnfix0.475) against the 101 k rung with the same solver
    ("  bnfix0.475, 2 ranks): «cs('bnfix0.475', FT, 'steps')» steps, «f(kpn('bnfix0.475', FT), 1)» Krylov iterations per Newton iteration against «f(kpn('bnfix1.062', FT), 1)» at «ku('bnfix1.062')» k unknowns with\n"
         "  the same solver («f(100 * (kpn('bnfix0.475', FT) / kpn('bnfix1.062', FT) - 1), 0)» % more), in «f(kbu('bnfix0.475', FT, q='mem_all'), 1)» kB per unknown over both ranks. Its residual depth, «f(cs('bnfix0.475', FT, 'outputs')['h_res'], 0)» nm, is «f(100 * (cs('bnfix0.475', FT, 'outputs')['h_res'] / cs('bnfix0.85', 'fieldsplit', 'outputs')['h_res'] - 1), 2)» %\n"
         "  above the «ku('bnfix0.85')» k rung's"),
    # the uniform rungs beside the adapted meshes on the same fixed steps (bench/adapt_bench.py, sector_fixed and bn_fixed)
    ("  their meshes alone). The kerogen sector's adapted level 3 («th(ad('sector_fixed', 3).unknowns)» unknowns) is within «pu(max(abs(ade('sector_fixed', 3, q)) for q in ('P', 'creep', 'h_res')), 2)» of the 1.03 M rung in all\n"
         "  three outputs, where the uniform «ku('fix0.034')» k rung is «pu(cs('fix0.034', 'fieldsplit', 'outputs')['creep'] / cs('fix0.019', FT, 'outputs')['creep'] - 1, 2)» off in the creep depth. BN's adapted residual depth settles at\n"
         "  «f(min(ad('bn_fixed', k).q['h_res'] for k in range(2, 6)) / 1e3, 3)» to «f(max(ad('bn_fixed', k).q['h_res'] for k in range(2, 6)) / 1e3, 3)» µm from level 2 («th(ad('bn_fixed', 2).unknowns)» unknowns) on, and the uniform rungs climb toward it: the limit of the last\n"
         "  two («ku('bnfix0.85')» k and 1.03 M) is «f(fband(('bnfix0.85', 'fieldsplit'), ('bnfix0.475', FT), 'h_res')[0] / 1e3, 3)» to «f(fband(('bnfix0.85', 'fieldsplit'), ('bnfix0.475', FT), 'h_res')[1] / 1e3, 3)» µm if their error falls as h_tip to h_tip²"),
    ("«f(kpn(S3[1], LU), 1)» per Newton iteration at «ku(S3[1])» k unknowns and «f(kpn(S3[3], LU), 1)» at «ku(S3[3])» k"),
    ("active: with the p-multigrid «f(kpn('lhu0.12'), 0)» Krylov iterations per Newton iteration at «ku('lhu0.12')» k unknowns, "
         "«f(kpn('lhu0.0707'), 0)» at «ku('lhu0.0707')» k and «f(kpn('lhu0.0425'), 0)» at «ku('lhu0.0425')» k; with\n  the displacement "
         "block solved exactly, «f(kpn('lhu0.12', LU), 1)» and «f(kpn('lhu0.0707', LU), 1)» («f(kpn(S3[1], LU), 1)» in the first 8 steps at «ku(S3[1])» k). The field "
         "split then takes «f(csr('lhu0.12', 'cpu'), 2)»×,\n  «f(csr('lhu0.0707', 'cpu'), 2)»× and «f(csr('lhu0.0425', 'cpu'), 2)»× the "
         "direct path's CPU"),
    # where the field split's time goes on 2 ranks (bench case ranks0.0425, -log_view)
    ("- **Where the field split's time goes** (-log_view, bench case ranks0.0425: «ku(R2)» k unknowns, 2 ranks, the first 4\n"
         "  steps; docs/performance.md): of «f(cs(R2, 'fieldsplit', 'events')['CC9 contact solve'], 1)» s in the contact solve, «f(cs(R2, 'fieldsplit', 'events')['KSPSolve_FS_0'], 1)» s are the displacement block's multigrid\n"
         "  cycles and «f(cs(R2, 'fieldsplit', 'events')['KSPSolve_FS_Schu'], 1)» s the Schur complement's solves; the set-ups of the hierarchy take «f(cs(R2, 'fieldsplit', 'events')['PCSetUp'], 1)» s, the residual with\n"
         "  its UMAT calls «f(cs(R2, 'fieldsplit', 'events')['CC9 residual+UMAT'], 1)» s. At this size the run is its contact solve, and that is its displacement block"),
    ("GAMG on the P2 block took «f(min(csr(c, 'cpu', 'fieldsplit, before', G) for c in S3[:2]), 1)»–"
         "«f(max(csr(c, 'cpu', 'fieldsplit, before', G) for c in S3[:2]), 1)»× the CPU of its kept form in 3D"),
]
