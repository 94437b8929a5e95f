"""Engineering constants <-> (lambda, muT, muL, a, b) of a transversely isotropic elastic frame.

The stiffness is eq. 21 of Yin, Liu & Borja (2021) (theory.md section 4.2). In bedding axes (normal n = e3),
Voigt order 11, 22, 33, 12, 13, 23, engineering shear strains (the DDSDDE layout):

    C11 = C22 = lam + 2 muT     C12 = lam     C13 = C23 = lam + a
    C33 = lam + 2 muT + 2 a + b + 4 (muL - muT)     C44(12) = muT     C55(13) = C66(23) = muL

Engineering constants (theory.md section 4.3), subscript p = in the bedding plane, n = normal to it,
nu_ij = -eps_j / eps_i under a uniaxial stress along i:

    S11 = 1/Ep   S12 = -nu_pp/Ep   S13 = -nu_pn/Ep = -nu_np/En   S33 = 1/En   S55 = 1/Gnp
    S44(12) = 2 (1 + nu_pp)/Ep

nu_pn is the ratio for stress in the bedding plane and strain normal to it. This is the reading under
which Table 1 of the paper is consistent (its 0.19 behaves as nu_pn, theory.md section 4.3 and A5).
If your data give nu_np (stress normal to the bedding, strain in it), pass nu_pn = nu_np * Ep / En.

The conversion is homogeneous of degree one in the moduli: any consistent stress unit works; the
UMAT expects MPa. Only numpy is needed. tools/ti_constants.py is its command line (main below). The functions at
module level are the importable API; each raises InputError (a ValueError) naming the command-line option, its value and the allowed range.
"""

import argparse
import json
import math
import sys

import numpy as np

__all__ = [
    "InputError",
    "engineering_to_lame",
    "lame_to_engineering",
    "isotropic_to_lame",
    "stiffness_bedding_axes",
    "mandel_eigenvalues",
]

_SQ2 = math.sqrt(2.0)


class InputError(ValueError):
    """An input outside its admissible range.

    Attributes: option (the command-line option, e.g. '--nu-pp'), value, allowed (text of the range).
    """

    def __init__(self, option, value, allowed):
        self.option = option
        self.value = value
        self.allowed = allowed
        super().__init__(f"{option} = {value:.10g} is not allowed: need {allowed}")


def _finite(option, value):
    value = float(value)
    if not math.isfinite(value):
        raise InputError(option, value, "a finite number")
    return value


def _positive(option, value):
    value = _finite(option, value)
    if not value > 0.0:
        raise InputError(option, value, f"{option[2:]} > 0")
    return value


def stiffness_bedding_axes(lam, muT, muL, a, b):
    """6x6 stiffness in bedding axes (n = e3), Voigt 11,22,33,12,13,23, engineering shear (DDSDDE layout)."""
    c11 = lam + 2.0 * muT
    c13 = lam + a
    c33 = lam + 2.0 * muT + 2.0 * a + b + 4.0 * (muL - muT)
    C = np.zeros((6, 6))
    C[:3, :3] = [[c11, lam, c13], [lam, c11, c13], [c13, c13, c33]]
    C[3, 3] = muT
    C[4, 4] = C[5, 5] = muL
    return C


def mandel_eigenvalues(C):
    """Eigenvalues (ascending) of a 6x6 Voigt stiffness with engineering shear, via its Mandel form.

    Mandel form: D = W C W with W = diag(1, 1, 1, sqrt2, sqrt2, sqrt2) (theory.md 1.1, DDSDDE = W^-1 D W^-1).
    C is positive definite iff all these eigenvalues are > 0.
    """
    w = np.array([1.0, 1.0, 1.0, _SQ2, _SQ2, _SQ2])
    Cm = np.asarray(C, dtype=float) * np.outer(w, w)
    return np.linalg.eigvalsh(0.5 * (Cm + Cm.T))


def engineering_to_lame(Ep, En, nu_pp, nu_pn, Gnp):
    """(Ep, En, nu_pp, nu_pn, Gnp) -> dict with lam, muT, muL, a, b and the stiffness entries.

    Reading S13 = -nu_pn/Ep (theory.md 4.3). Positive definiteness: Ep, En, Gnp > 0, |nu_pp| < 1,
    1 - nu_pp - 2 nu_pn^2 En/Ep > 0.
    """
    Ep = _positive("--Ep", Ep)
    En = _positive("--En", En)
    Gnp = _positive("--Gnp", Gnp)
    nu_pp = _finite("--nu-pp", nu_pp)
    if not -1.0 < nu_pp < 1.0:
        raise InputError("--nu-pp", nu_pp, "-1 < nu-pp < 1")
    nu_pn = _finite("--nu-pn", nu_pn)
    bound = math.sqrt((1.0 - nu_pp) * Ep / (2.0 * En))
    if not 1.0 - nu_pp - 2.0 * nu_pn * nu_pn * En / Ep > 0.0:
        raise InputError(
            "--nu-pn", nu_pn,
            f"|nu-pn| < sqrt((1 - nu-pp) Ep / (2 En)) = {bound:.6g} for the other values given")

    nu_np = nu_pn * En / Ep
    delta = (1.0 + nu_pp) * (1.0 - nu_pp - 2.0 * nu_pn * nu_np)
    c11 = Ep * (1.0 - nu_pn * nu_np) / delta
    c12 = Ep * (nu_pp + nu_pn * nu_np) / delta
    c13 = En * nu_pn * (1.0 + nu_pp) / delta
    c33 = En * (1.0 - nu_pp * nu_pp) / delta
    c44 = Ep / (2.0 * (1.0 + nu_pp))          # = (c11 - c12)/2, shear in the bedding plane
    c55 = Gnp
    lam, muT, muL = c12, c44, c55
    a = c13 - c12
    b = c11 + c33 - 2.0 * c13 - 4.0 * c55     # difference of large numbers: ill-conditioned
    return {
        "lam": lam, "muT": muT, "muL": muL, "a": a, "b": b,
        "nu_np": nu_np,
        "C11": c11, "C12": c12, "C13": c13, "C33": c33, "C44": c44, "C55": c55,
    }


def _check_lame(lam, muT, muL, a, b):
    """Positive definiteness of the 6x6 stiffness of eq. 21, one condition per option."""
    lam = _finite("--lam", lam)
    a = _finite("--a", a)
    b = _finite("--b", b)
    muT = _positive("--muT", muT)
    muL = _positive("--muL", muL)
    # Eigenvalues in bedding axes: muT (12), muL (13, 23; twice), 2 muT (11-22 difference) and the
    # 2x2 block [[2(lam+muT), sqrt2 C13], [sqrt2 C13, C33]].
    if not lam + muT > 0.0:
        raise InputError("--lam", lam, f"lam > -muT = {-muT:.6g}")
    b_min = (lam + a) ** 2 / (lam + muT) - (lam - 2.0 * muT + 2.0 * a + 4.0 * muL)
    if not b > b_min:
        raise InputError(
            "--b", b,
            f"b > (lam + a)^2/(lam + muT) - (lam - 2 muT + 2 a + 4 muL) = {b_min:.6g} for the other values given")
    return lam, muT, muL, a, b


def lame_to_engineering(lam, muT, muL, a, b):
    """(lam, muT, muL, a, b) -> dict with Ep, En, nu_pp, nu_pn, nu_np, Gnp, Gpp, S11, S12, S13, S33.

    Raises InputError unless the 6x6 stiffness is positive definite.
    """
    lam, muT, muL, a, b = _check_lame(lam, muT, muL, a, b)
    C = stiffness_bedding_axes(lam, muT, muL, a, b)
    eig = mandel_eigenvalues(C)
    if not eig[0] > 0.0:   # cannot happen after _check_lame except at round-off level
        raise InputError("--b", b, "a positive definite stiffness (smallest Mandel eigenvalue "
                         f"{eig[0]:.6g} <= 0)")
    c11, c12, c13, c33 = C[0, 0], C[0, 1], C[0, 2], C[2, 2]
    det = c33 * (c11 + c12) - 2.0 * c13 * c13      # > 0 by the checks above
    s_sum = c33 / det                               # S11 + S12
    s_dif = 1.0 / (c11 - c12)                       # S11 - S12 = 1/(2 muT)
    s11 = 0.5 * (s_sum + s_dif)
    s12 = 0.5 * (s_sum - s_dif)
    s13 = -c13 / det
    s33 = (c11 + c12) / det
    Ep, En = 1.0 / s11, 1.0 / s33
    return {
        "Ep": Ep, "En": En,
        "nu_pp": -s12 * Ep, "nu_pn": -s13 * Ep, "nu_np": -s13 * En,
        "Gnp": muL, "Gpp": muT,
        "S11": s11, "S12": s12, "S13": s13, "S33": s33,
        "mandel_eigenvalues": [float(x) for x in eig],
    }


def isotropic_to_lame(E, nu):
    """(E, nu) -> dict with lam, mu (soft frame, PROPS 14-15)."""
    E = _positive("--E", E)
    nu = _finite("--nu", nu)
    if not -1.0 < nu < 0.5:
        raise InputError("--nu", nu, "-1 < nu < 0.5")
    return {"lam": E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), "mu": E / (2.0 * (1.0 + nu))}


# ------------------------------------------------------------------------------------------- CLI

def _props_line(values):
    return ", ".join(f"{v:.8g}" for v in values)


def _cmd_to_lame(args):
    r = engineering_to_lame(args.Ep, args.En, args.nu_pp, args.nu_pn, args.Gnp)
    props = [r["lam"], r["muT"], r["muL"], r["a"], r["b"]]
    if args.json:
        out = {"input": {"Ep": args.Ep, "En": args.En, "nu_pp": args.nu_pp, "nu_pn": args.nu_pn,
                         "Gnp": args.Gnp},
               "reading": "S13 = -nu_pn/Ep", **r, "props_2_6": props}
        return json.dumps(out, indent=2)
    lines = [
        "# reading S13 = -nu_pn/Ep; moduli in the input's stress unit (MPa for the UMAT)",
        f"lam  = {r['lam']:.8g}",
        f"muT  = {r['muT']:<12.8g}(shear in the bedding plane)",
        f"muL  = {r['muL']:<12.8g}(shear in planes containing the normal)",
        f"a    = {r['a']:.8g}",
        f"b    = {r['b']:.8g}",
        f"nu_np = nu_pn*En/Ep = {r['nu_np']:.6g}",
        f"PROPS 2-6: {_props_line(props)}",
    ]
    return "\n".join(lines)


def _cmd_to_engineering(args):
    r = lame_to_engineering(args.lam, args.muT, args.muL, args.a, args.b)
    if args.json:
        out = {"input": {"lam": args.lam, "muT": args.muT, "muL": args.muL, "a": args.a, "b": args.b},
               "reading": "S13 = -nu_pn/Ep", **r}
        return json.dumps(out, indent=2)
    eig = ", ".join(f"{x:.6g}" for x in r["mandel_eigenvalues"])
    lines = [
        "# nu_ij = -eps_j/eps_i under uniaxial stress along i; p = in bedding, n = normal",
        f"Ep     = {r['Ep']:.8g}",
        f"En     = {r['En']:.8g}",
        f"nu_pp  = {r['nu_pp']:.6g}",
        f"nu_pn  = {r['nu_pn']:<10.6g}(stress in the bedding plane, strain normal to it; S13 = -nu_pn/Ep)",
        f"nu_np  = {r['nu_np']:<10.6g}(stress normal to the bedding, strain in it; S13 = -nu_np/En)",
        f"Gnp    = {r['Gnp']:.8g}",
        f"Gpp    = {r['Gpp']:.8g}",
        f"S13    = {r['S13']:.6e}",
        f"Mandel eigenvalues: {eig}",
    ]
    return "\n".join(lines)


def _cmd_isotropic(args):
    r = isotropic_to_lame(args.E, args.nu)
    if args.json:
        out = {"input": {"E": args.E, "nu": args.nu}, **r, "props_14_15": [r["lam"], r["mu"]]}
        return json.dumps(out, indent=2)
    return "\n".join([
        f"lam = {r['lam']:.8g}",
        f"mu  = {r['mu']:.8g}",
        f"PROPS 14-15: {_props_line([r['lam'], r['mu']])}",
    ])


def build_parser():
    parser = argparse.ArgumentParser(
        prog="ti_constants.py",
        description="Convert between engineering constants of a transversely isotropic elastic frame and "
                    "the (lambda, muT, muL, a, b) of Yin et al. (2021) eq. 21 (PROPS 2-6 of the Cam-Clay IX "
                    "UMAT), reading S13 = -nu_pn/Ep. Exit code 2 on invalid input.")
    parser.add_argument("--json", action="store_true", default=False, help="machine-readable output")
    common = argparse.ArgumentParser(add_help=False)
    common.add_argument("--json", action="store_true", default=argparse.SUPPRESS,
                        help="machine-readable output")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("to-lame", parents=[common],
                       help="engineering constants -> lam, muT, muL, a, b (PROPS 2-6)")
    p.add_argument("--Ep", type=float, required=True, help="Young's modulus in the bedding plane")
    p.add_argument("--En", type=float, required=True, help="Young's modulus normal to the bedding")
    p.add_argument("--nu-pp", type=float, required=True,
                   help="Poisson's ratio, stress and strain in the bedding plane")
    p.add_argument("--nu-pn", type=float, required=True,
                   help="Poisson's ratio, stress in the bedding plane, strain normal to it (S13 = -nu_pn/Ep)")
    p.add_argument("--Gnp", type=float, required=True,
                   help="shear modulus in planes containing the bedding normal")
    p.set_defaults(func=_cmd_to_lame)

    p = sub.add_parser("to-engineering", parents=[common],
                       help="lam, muT, muL, a, b -> Ep, En, nu_pp, nu_pn, nu_np, Gnp, Gpp, S13")
    p.add_argument("--lam", type=float, required=True, help="lambda (PROPS 2)")
    p.add_argument("--muT", type=float, required=True, help="muT, shear in the bedding plane (PROPS 3)")
    p.add_argument("--muL", type=float, required=True, help="muL, shear normal to the bedding (PROPS 4)")
    p.add_argument("--a", type=float, required=True, help="a (PROPS 5)")
    p.add_argument("--b", type=float, required=True, help="b (PROPS 6)")
    p.set_defaults(func=_cmd_to_engineering)

    p = sub.add_parser("isotropic", parents=[common],
                       help="E, nu -> lam, mu of the isotropic soft frame (PROPS 14-15)")
    p.add_argument("--E", type=float, required=True, help="Young's modulus")
    p.add_argument("--nu", type=float, required=True, help="Poisson's ratio")
    p.set_defaults(func=_cmd_isotropic)
    return parser


def main(argv=None):
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        print(args.func(args))
    except InputError as err:
        print(f"{parser.prog} {args.command}: error: {err}", file=sys.stderr)
        return 2
    return 0

