#!/usr/bin/env python3
"""Independent high-accuracy reference integration of the Cam-Clay IX two-frame Perzyna model.

Derived only from docs/theory.md (sections 1-4) and docs/umat-interface.md (PROPS layout), not from the
Fortran UMAT, so that the two can be compared.  numpy + scipy only.

Conventions (theory.md §1.1): tension positive; Voigt order 11, 22, 33, 12, 13, 23; strains in
engineering Voigt (shear doubled) on output; stresses in plain Voigt.  Internally: 3x3 tensors for the
constitutive functions, Mandel 6-vectors (shear * sqrt 2) for the linear algebra of the mixture.

Run it to see the self-checks against the worked numbers of theory.md §5 (CTest reference.self_check):
    python3 -m camclay9.reference
"""
import numpy as np
from scipy.integrate import solve_ivp

VOIGT = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]   # Abaqus order 11, 22, 33, 12, 13, 23
SQ2 = np.sqrt(2.0)
W = np.array([1, 1, 1, SQ2, SQ2, SQ2])                      # Mandel weights (§1.1)
I3 = np.eye(3)


# ---------------------------------------------------------------- conversions (§1.1)
def t2mandel(T):
    return np.array([T[i, j] for i, j in VOIGT]) * W


def mandel2t(v):
    T = np.empty((3, 3))
    for A, (i, j) in enumerate(VOIGT):
        T[i, j] = T[j, i] = v[A] / W[A]
    return T


def mandel2voigt_strain(v):          # engineering shear: gamma_ij = 2 eps_ij = sqrt2 * Mandel
    return v * W


def mandel2voigt_stress(v):
    return v / W


def voigt_stress2t(s):
    return mandel2t(np.asarray(s, float) * W)


def c4_to_mandel(C4):
    return np.array([[C4[i, j, k, l] for (k, l) in VOIGT] for (i, j) in VOIGT]) * np.outer(W, W)


def unit(n):
    n = np.asarray(n, float)
    return n / np.linalg.norm(n)


# ---------------------------------------------------------------- elasticity (§4.2)
def stiffness_tensor(lam, muT, muL, a, b, n):
    """C_ijkl of theory.md §4.2 (Y21 eq. 21) for the unit bedding normal n."""
    n = unit(n)
    d = I3
    C = (lam * np.einsum('ij,kl->ijkl', d, d)
         + muT * (np.einsum('ik,jl->ijkl', d, d) + np.einsum('il,jk->ijkl', d, d))
         + a * (np.einsum('ij,k,l->ijkl', d, n, n) + np.einsum('i,j,kl->ijkl', n, n, d))
         + b * np.einsum('i,j,k,l->ijkl', n, n, n, n)
         + (muL - muT) * (np.einsum('jl,i,k->ijkl', d, n, n) + np.einsum('ik,j,l->ijkl', d, n, n)
                          + np.einsum('il,j,k->ijkl', d, n, n) + np.einsum('jk,i,l->ijkl', d, n, n)))
    return C


def stiffness_voigt(lam, muT, muL, a, b, n):
    """6x6 DDSDDE in engineering-shear Voigt order: DDSDDE(A,B) = C_ijkl, no factors (§4.2)."""
    C = stiffness_tensor(lam, muT, muL, a, b, n)
    return np.array([[C[i, j, k, l] for (k, l) in VOIGT] for (i, j) in VOIGT])


def stiffness_mandel(lam, muT, muL, a, b, n):
    return c4_to_mandel(stiffness_tensor(lam, muT, muL, a, b, n))


# ---------------------------------------------------------------- projection (§1.2)
def project(c1, c2, c3, n, sig):
    """sigma' = P:sigma = c1 sig + c2 (n.sig.n) m + (c3/2)[n (x) sig n + sig n (x) n]  (§1.2)."""
    n = unit(n)
    sn = sig @ n
    return c1 * sig + c2 * (n @ sn) * np.outer(n, n) + 0.5 * c3 * (np.outer(n, sn) + np.outer(sn, n))


def projection(c1, c2, c3, n):
    """P_ijkl (3x3x3x3), obtained by applying the closed form to the symmetric basis tensors."""
    P = np.zeros((3, 3, 3, 3))
    for k in range(3):
        for l in range(3):
            E = 0.5 * (np.outer(I3[k], I3[l]) + np.outer(I3[l], I3[k]))
            P[:, :, k, l] = project(c1, c2, c3, n, E)
    return P


# ---------------------------------------------------------------- yield function and flow (§1.3)
def yield_f(sig, pc, M, c, n):
    """f = q'^2/M^2 + p'(p' - pc), p', q' of sigma' = P:sigma (tension positive sigma, §1.3)."""
    sp = project(*c, n, sig)
    p = -np.trace(sp) / 3.0
    s = sp + p * I3
    q2 = 1.5 * np.sum(s * s)
    return q2 / M**2 + p * (p - pc)


def flow_N(sig, pc, M, c, n):
    """N = df/dsigma = P:n',  n' = -(2p'-pc)/3 1 + (3/M^2) s'  (§1.3; P symmetric)."""
    sp = project(*c, n, sig)
    p = -np.trace(sp) / 3.0
    s = sp + p * I3
    nprime = -(2.0 * p - pc) / 3.0 * I3 + 3.0 / M**2 * s
    return project(*c, n, nprime)


# ---------------------------------------------------------------- frames from PROPS (umat-interface.md)
def frames(props):
    """(hard, soft) dicts from the 19-slot PROPS list; soft frame isotropic: muT = muL, a = b = 0."""
    p = [float(x) for x in props]
    hard = dict(lam=p[1], muT=p[2], muL=p[3], a=p[4], b=p[5], M=p[6], lamp=p[7],
                c=(p[8], p[9], p[10]), pc0=p[11], eta=p[12])
    soft = dict(lam=p[13], muT=p[14], muL=p[14], a=0.0, b=0.0, M=p[15], lamp=p[16],
                c=(1.0, 0.0, 0.0), pc0=p[17], eta=p[18])
    return p[0], hard, soft


def _Chat(fr, n):
    return stiffness_mandel(fr['lam'], fr['muT'], fr['muL'], fr['a'], fr['b'], n)


def pc_of(fr, evp_mandel):
    """§1.4 closed form: pc = pc0 exp(-tr evp / lamp) (tr from the real vp strain of the frame)."""
    return fr['pc0'] * np.exp(-np.sum(evp_mandel[:3]) / fr['lamp'])


def vp_rate(fr, n, sig_t, pc):
    """Perzyna (§3.1, Y21 eq. 27): d evp/dt = <f>/eta N, returned as a Mandel vector."""
    f = yield_f(sig_t, pc, fr['M'], fr['c'], n)
    if f <= 0.0:
        return np.zeros(6)
    return f / fr['eta'] * t2mandel(flow_N(sig_t, pc, fr['M'], fr['c'], n))


# ---------------------------------------------------------------- the mixture under stress control (§2)
def creep_mixture(props, normal, sigma0, sigma, times, rtol=1e-10, atol=1e-14,
                  evp0_hard=None, evp0_soft=None, method='Radau'):
    """Both frames at sigma0 with zero strain at t = 0; overall stress jumps to sigma at 0+ and is held.

    State y = (evp_hard, evp_soft) in Mandel form; pc per frame from the closed form of §1.4; the total
    strain follows from the overall equilibrium sigma = phi sigma_M + (1-phi) sigma_m (§2):
        eps = Cbar^-1 : (sigma - sigma0 + phi C_M:evp_M + (1-phi) C_m:evp_m)
    evp0_hard / evp0_soft (engineering Voigt) optionally restart from a non-zero viscoplastic state
    (strains then measured from the same sigma0 reference, e.g. after a hold at sigma0).
    times must be sorted ascending and >= 0; row k of every array is the state at times[k] (0 means 0+).
    """
    phi, hard, soft = frames(props)
    n = unit(normal)
    CM, Cm = _Chat(hard, n), _Chat(soft, n)
    Cbar = phi * CM + (1.0 - phi) * Cm                          # §2
    s0, s1 = t2mandel(np.asarray(sigma0, float)), t2mandel(np.asarray(sigma, float))
    times = np.asarray(times, float)

    def state(y):
        eM, em = y[:6], y[6:]
        eps = np.linalg.solve(Cbar, s1 - s0 + phi * CM @ eM + (1.0 - phi) * Cm @ em)
        sM = s0 + CM @ (eps - eM)                                # frame stresses (§2)
        sm = s0 + Cm @ (eps - em)
        return eps, sM, sm, pc_of(hard, eM), pc_of(soft, em)

    def rhs(t, y):
        _, sM, sm, pM, pm = state(y)
        return np.concatenate([vp_rate(hard, n, mandel2t(sM), pM), vp_rate(soft, n, mandel2t(sm), pm)])

    y0 = np.zeros(12)
    if evp0_hard is not None:
        y0[:6] = np.asarray(evp0_hard, float) / W
    if evp0_soft is not None:
        y0[6:] = np.asarray(evp0_soft, float) / W
    sol = solve_ivp(rhs, (0.0, max(times.max(), 1e-30)), y0, method=method, t_eval=times,
                    rtol=rtol, atol=atol, dense_output=False)
    if not sol.success:
        raise RuntimeError(sol.message)

    out = {k: [] for k in ('strain', 'evp_hard', 'evp_soft', 'evp', 'pc_hard', 'pc_soft',
                           'stress_hard', 'stress_soft')}
    for y in sol.y.T:
        eps, sM, sm, pM, pm = state(y)
        out['strain'].append(mandel2voigt_strain(eps))
        out['evp_hard'].append(mandel2voigt_strain(y[:6]))
        out['evp_soft'].append(mandel2voigt_strain(y[6:]))
        # overall vp strain, Y21 eq. 3 (output only)
        out['evp'].append(mandel2voigt_strain(np.linalg.solve(Cbar, phi * CM @ y[:6] + (1 - phi) * Cm @ y[6:])))
        out['pc_hard'].append(pM)
        out['pc_soft'].append(pm)
        out['stress_hard'].append(mandel2voigt_stress(sM))
        out['stress_soft'].append(mandel2voigt_stress(sm))
    out = {k: np.array(v) for k, v in out.items()}
    out['time'] = sol.t
    out['strain0'] = mandel2voigt_strain(state(y0)[0])          # elastic jump at 0+
    out['nfev'] = sol.nfev
    return out


# ---------------------------------------------------------------- one frame under constant stress
def single_frame_constant_stress(frame_props, normal, sigma, pc0, t, rtol=1e-12, atol=1e-14):
    """One frame at constant stress sigma (3x3): only pc moves.  frame_props: dict with M, lamp, c, eta
    (as returned by frames()).  One ODE in y = ln pc (§1.4: d ln pc/dt = -tr(evp_dot)/lamp), plus the
    quadrature of evp.  Returns dict with 'pc' and 'evp' (engineering Voigt) at the times t."""
    n = unit(normal)
    sig = np.asarray(sigma, float)
    M, c, eta, lamp = frame_props['M'], frame_props['c'], frame_props['eta'], frame_props['lamp']

    def rhs(_, y):
        pc = np.exp(y[0])
        f = yield_f(sig, pc, M, c, n)
        if f <= 0.0:
            return np.zeros(7)
        rate = f / eta * t2mandel(flow_N(sig, pc, M, c, n))
        return np.concatenate([[-np.sum(rate[:3]) / lamp], rate])

    t = np.asarray(t, float)
    sol = solve_ivp(rhs, (0.0, t.max()), np.r_[np.log(pc0), np.zeros(6)], method='Radau', t_eval=t,
                    rtol=rtol, atol=atol)
    if not sol.success:
        raise RuntimeError(sol.message)
    return {'time': sol.t, 'pc': np.exp(sol.y[0]), 'evp': np.array([mandel2voigt_strain(v) for v in sol.y[1:].T])}


# ---------------------------------------------------------------- self-checks against theory.md §5
WOODFORD = [0.5, 2900, 18000, 13000, 4100, 6900, 1.46, 0.00013, 0.73, -0.20, 0.40, 2.0, 1.3e13,
            4600, 3100, 1.46, 0.0026, 35.0, 1.3e10]


def _close(a, b, tol, what):
    a, b = np.asarray(a, float), np.asarray(b, float)
    assert np.allclose(a, b, rtol=0, atol=tol), f'{what}: {a} vs {b}'


def _elastic(fr):
    return fr['lam'], fr['muT'], fr['muL'], fr['a'], fr['b']


def _normal(deg):
    return np.array([np.sin(np.radians(deg)), 0.0, np.cos(np.radians(deg))])


def _check_stiffness(hard):
    """§5.1 stiffness matrices (theta = 0, 45, 90, the soft frame, the mixture), §4.3 eigenvalues."""
    C0 = stiffness_voigt(*_elastic(hard), _normal(0))
    ref0 = np.array([[38900, 2900, 7000, 0, 0, 0], [2900, 38900, 7000, 0, 0, 0], [7000, 7000, 34000, 0, 0, 0],
                     [0, 0, 0, 18000, 0, 0], [0, 0, 0, 0, 13000, 0], [0, 0, 0, 0, 0, 13000]], float)
    _close(C0, ref0, 1e-9, '§5.1 theta=0')
    C90 = stiffness_voigt(*_elastic(hard), _normal(90))
    ref90 = np.diag([34000, 38900, 38900, 13000, 13000, 18000.])
    ref90[0, 1] = ref90[1, 0] = ref90[0, 2] = ref90[2, 0] = 7000
    ref90[1, 2] = ref90[2, 1] = 2900
    _close(C90, ref90, 1e-9, '§5.1 theta=90')
    C45 = stiffness_voigt(*_elastic(hard), _normal(45))
    chk = {(0, 0): 34725, (2, 2): 34725, (1, 1): 38900, (0, 1): 4950, (1, 2): 4950, (0, 2): 8725,
           (0, 4): -1225, (2, 4): -1225, (1, 4): 2050, (3, 3): 15500, (5, 5): 15500, (3, 5): -2500,
           (4, 4): 14725, (0, 3): 0, (0, 5): 0, (3, 4): 0, (4, 5): 0}
    for (A, B), v in chk.items():
        _close(C45[A, B], v, 1e-8, f'§5.1 theta=45 C[{A+1},{B+1}]')
        _close(C45[B, A], v, 1e-8, f'§5.1 theta=45 C[{B+1},{A+1}]')
    ev = np.linalg.eigvalsh(stiffness_mandel(*_elastic(hard), _normal(0)))
    _close(ev, [26000, 26000, 27260, 36000, 36000, 48540], 2.0, '§4.3 Mandel eigenvalues')
    E, nu = 8000.0, 0.3                                   # soft frame and mixture use unrounded 4615.4/3076.9
    ls, ms = E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))
    Cs = stiffness_voigt(ls, ms, ms, 0, 0, _normal(0))
    _close([Cs[0, 0], Cs[0, 1], Cs[3, 3]], [10769.2, 4615.4, 3076.9], 0.06, '§5.1 soft')
    Cmix = 0.5 * C0 + 0.5 * Cs
    _close([Cmix[0, 0], Cmix[0, 1], Cmix[0, 2], Cmix[2, 2], Cmix[3, 3], Cmix[4, 4], Cmix[5, 5]],
           [24834.6, 3757.7, 5807.7, 22384.6, 10538.5, 8038.5, 8038.5], 0.06, '§5.1 mixture')
    print('§5.1 stiffness (theta = 0, 45, 90, soft, mixture): OK')


def _check_projection(c):
    """§5.2 projection tensor, §4.4 its Voigt form; returns the random symmetric S and normal used again."""
    Pm0 = c4_to_mandel(projection(*c, _normal(0)))
    _close(Pm0, np.diag([0.73, 0.73, 0.93, 0.73, 0.93, 0.93]), 1e-14, '§5.2 theta=0')
    _close(c4_to_mandel(projection(*c, _normal(90))), np.diag([0.93, 0.73, 0.73, 0.93, 0.93, 0.73]), 1e-14,
           '§5.2 theta=90')
    P45 = projection(*c, _normal(45))
    Pm45 = c4_to_mandel(P45)
    for (A, B), v in {(0, 0): 0.88, (2, 2): 0.88, (0, 2): -0.05, (0, 4): 0.0707, (2, 4): 0.0707, (1, 1): 0.73,
                      (3, 3): 0.83, (4, 4): 0.83, (5, 5): 0.83, (3, 5): 0.10}.items():
        _close([Pm45[A, B], Pm45[B, A]], [v, v], 5e-5, f'§5.2 theta=45 P[{A+1},{B+1}]')
    Pv = np.array([[P45[i, j, k, l] * (2 if k != l else 1) for (k, l) in VOIGT] for (i, j) in VOIGT])
    _close([Pv[0, 4], Pv[4, 0]], [0.10, 0.05], 1e-14, '§4.4 P_v(11,13), P_v(13,11)')
    rng = np.random.default_rng(1)
    S = rng.normal(size=(3, 3)); S = S + S.T
    nr = unit(rng.normal(size=3))
    _close(np.einsum('ijkl,kl->ij', projection(*c, nr), S), project(*c, nr, S), 1e-13, 'P:sigma vs closed form')
    Pr = projection(*c, nr)
    _close(Pr, np.einsum('klij->ijkl', Pr), 1e-15, 'P major symmetry')
    print('§5.2 / §4.4 projection tensor: OK')
    return S, nr


def _check_yield_and_flow(hard, soft, S, nr):
    """§5.3 f, tr N, N at sigma = -35 I; §1.3 tr N and N = df/dsigma by central differences."""
    c = hard['c']
    sig = -35.0 * I3
    for deg in (0, 90):
        f = yield_f(sig, hard['pc0'], hard['M'], c, _normal(deg))
        _close(f, 744.70, 0.006, f'§5.3 f_hard theta={deg}')
    _close(np.diag(project(*c, _normal(0), sig)), [-25.55, -25.55, -32.55], 1e-12, '§5.3 sigma\'')
    N = flow_N(sig, hard['pc0'], hard['M'], c, _normal(0))
    _close(np.trace(N), -44.15, 0.006, '§5.3 tr N')
    _close(t2mandel(N) / W, [-10.686, -10.686, -22.776, 0, 0, 0], 6e-4, '§5.3 N')
    _close(yield_f(sig, soft['pc0'], soft['M'], soft['c'], _normal(0)), 0.0, 1e-10, '§5.3 f_soft')
    _close(np.trace(flow_N(sig, soft['pc0'], soft['M'], soft['c'], _normal(0))), -35.0, 1e-12, '§5.3 tr N soft')
    rate = f / hard['eta'] * t2mandel(N) / W
    _close(f / hard['eta'], 5.73e-11, 5e-14, '§5.3 f/eta')
    _close(rate[:3] / 1e-10, [-6.1, -6.1, -13.0], 0.06, '§5.3 initial vp rate')
    _close(np.sum(rate[:3]), -2.53e-9, 5e-12, '§5.3 vol rate')
    # §1.3 formula for tr N (non-trivial theta) and N = df/dsigma by central differences
    s_r = -30 * I3 + 5 * S
    N_r = flow_N(s_r, 20.0, hard['M'], c, nr)
    sp = project(*c, nr, s_r); p = -np.trace(sp) / 3; dev = sp + p * I3
    trN = -(2 * p - 20.0) * (c[0] + (c[1] + c[2]) / 3) + 3 / hard['M']**2 * (c[1] + c[2]) * (nr @ dev @ nr)
    _close(np.trace(N_r), trN, 1e-10, '§1.3 tr N formula')
    h = 1e-4
    for k in range(3):
        for l in range(k, 3):
            E = 0.5 * h * (np.outer(I3[k], I3[l]) + np.outer(I3[l], I3[k]))
            df = (yield_f(s_r + E, 20.0, hard['M'], c, nr) - yield_f(s_r - E, 20.0, hard['M'], c, nr)) / (2 * h)
            _close(df, N_r[k, l], 1e-7, f'N=df/dsigma ({k}{l})')
    print(f'§5.3 f_hard = {yield_f(sig, 2.0, 1.46, c, _normal(0)):.3f}, tr N = {np.trace(N):.3f}, '
          f'N = {np.diag(N)}, f/eta = {f / hard["eta"]:.4e}: OK')


def _check_single_frames(hard, soft):
    """A single frame against the mixture with phi = 1 / phi = 0 and no stress jump (each frame then at constant
    stress)."""
    tt = np.array([0.0, 360.0, 3600.0, 36000.0])
    sig_c = np.diag([-35.0, -35.0, -75.0])
    for phi_t, name, fr in ((1.0, 'hard', hard), (0.0, 'soft', soft)):
        pr = list(WOODFORD); pr[0] = phi_t
        mix = creep_mixture(pr, _normal(30), sig_c, sig_c, tt, rtol=1e-11)
        one = single_frame_constant_stress(fr, _normal(30), sig_c, fr['pc0'], tt)
        _close(mix['stress_' + name], np.tile(mandel2voigt_stress(t2mandel(sig_c)), (len(tt), 1)), 1e-9,
               f'phi={phi_t}: constant frame stress')
        d = np.max(np.abs(mix['evp_' + name] - one['evp'])) / np.max(np.abs(one['evp']))
        dp = np.max(np.abs(mix['pc_' + name] / one['pc'] - 1))
        assert d < 1e-8 and dp < 1e-9, (d, dp)
        print(f'phi = {phi_t:g}: mixture vs single_frame_constant_stress ({name}): rel. diff evp {d:.1e}, '
              f'pc {dp:.1e}; pc(36000 s) = {one["pc"][-1]:.4f}')


def _check_scenario():
    """The brief's scenario: both frames at -35 I, the overall stress jumps to diag(-35,-35,-75) at 0+ (no hold)."""
    sig_c = np.diag([-35.0, -35.0, -75.0])
    n30 = _normal(30)
    sig0 = -35.0 * I3
    times = np.array([0.0, 360.0, 3600.0])
    r10 = creep_mixture(WOODFORD, n30, sig0, sig_c, times, rtol=1e-10)
    r12 = creep_mixture(WOODFORD, n30, sig0, sig_c, times, rtol=1e-12, atol=1e-16)
    dop = creep_mixture(WOODFORD, n30, sig0, sig_c, times, rtol=1e-12, atol=1e-16, method='DOP853')
    cr10 = r10['strain'][:, 2] - r10['strain0'][2]
    cr12 = r12['strain'][:, 2] - r12['strain0'][2]
    crd = dop['strain'][:, 2] - dop['strain0'][2]
    print('\nScenario theta = 30 deg, sigma0 = -35 I, sigma = diag(-35,-35,-75), no hold:')
    print(f'  eps33(0+) = {r10["strain0"][2]:.10e}')
    for k, t in enumerate(times[1:], 1):
        print(f'  t = {t:6.0f} s: creep eps33 - eps33(0+) = {cr10[k]:.10e}  (rtol 1e-12: {cr12[k]:.10e}, '
              f'rel diff {abs(cr10[k] / cr12[k] - 1):.1e}; DOP853 rtol 1e-12: rel diff {abs(crd[k] / cr12[k] - 1):.1e})')
        print(f'           pc_hard = {r10["pc_hard"][k]:.6f}, pc_soft = {r10["pc_soft"][k]:.6f}, '
              f'evp33 hard/soft = {r10["evp_hard"][k, 2]:.4e} / {r10["evp_soft"][k, 2]:.4e}')
    rel = np.max(np.abs(r10['strain'] - r12['strain'])) / np.max(np.abs(r12['strain']))
    print(f'  max |strain(rtol 1e-10) - strain(rtol 1e-12)| / max|strain| = {rel:.1e}')
    assert rel < 1e-8


def _check_paper_creep():
    """theory.md §5.4: hold at -35 I until steady, then +40 MPa axial (theta = 0 and 90)."""
    sig0, sig_c = -35.0 * I3, np.diag([-35.0, -35.0, -75.0])
    print('\n§5.4 check: hold at -35 I for T_hold, then diag(-35,-35,-75); creep eps33 at 385/3600/36000 s')
    tc = np.array([0.0, 385.0, 3600.0, 36000.0])
    for deg, paper in ((0, (6.1e-5, 1.3e-4, 2.8e-4)), (90, (4.5e-5, 7.8e-5, 1.6e-4))):
        for thold in (1e6, 1e7):
            hold = creep_mixture(WOODFORD, _normal(deg), sig0, sig0, [thold])
            r = creep_mixture(WOODFORD, _normal(deg), sig0, sig_c, tc, evp0_hard=hold['evp_hard'][-1],
                              evp0_soft=hold['evp_soft'][-1])
            cr = -(r['strain'][1:, 2] - r['strain0'][2])
            print(f'  theta = {deg:2d}, T_hold = {thold:.0e} s: pc_hard after hold = {hold["pc_hard"][-1]:.3f}; '
                  f'compressive creep = {cr[0]:.2e}, {cr[1]:.2e}, {cr[2]:.2e}   (theory.md: {paper})')


def _self_check():
    np.set_printoptions(precision=5, suppress=True, linewidth=130)
    phi, hard, soft = frames(WOODFORD)
    _check_stiffness(hard)
    S, nr = _check_projection(hard['c'])
    _check_yield_and_flow(hard, soft, S, nr)
    _check_single_frames(hard, soft)
    _check_scenario()
    _check_paper_creep()

if __name__ == '__main__':
    _self_check()
