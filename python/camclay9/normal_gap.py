"""The normal gap against Sneddon (issue 26, item 5; docs/contact.md, "The normal gap against γ"): the explanation
P_normal / P_Sneddon = 1 + A kappa c - (B_C - C_2 kappa^2) c^2 + O(c^3), c = cot psi, kappa = (1-2nu)/(2(1-nu)), its
constants (A and A_R from Catalan's constant, B_C by quadrature: b_cerruti(), C_2 fitted by bench/normal_gap_bench.py),
Hay, Bolshakov & Pharr's gamma, and the cone scene the bench and tests/driver/test_normal_gap.py run (MESH: the
bench's block, QUICK: the test's).
"""
import math

import numpy as np
from camclay9.launch import repo_root

E = 1000.0
CATALAN = 0.915965594177219
A_R = 1 + 2 / math.pi * (CATALAN - 1.5)          # the radial displacement of Sneddon's surface (Hay et al.'s term)
A_SHEAR = 2 - 4 / math.pi * (CATALAN + 0.5)      # the vertical (Cerruti) displacement of the face-normal shear
A = A_R + A_SHEAR                                # = 3 - (2/pi)(G + 5/2)
B_C = 0.3655                                     # b_cerruti(): the radial displacement of that shear, any nu
MESH = dict(W=4000, H=2000, h_tip=0.025, h_far=200, r_fine=1.5, r_contact=2.0, order=2)
QUICK = dict(W=400, H=200, h_tip=0.05, h_far=20, r_fine=1.5, r_contact=2.0, order=1)


def kappa(nu):
    return (1 - 2 * nu) / (2 * (1 - nu))


def theory(psi, nu, c2=None, order=2):
    """P_normal / P_Sneddon to first order (order=1) or second (order=2; C_2 from the fit, or given)."""
    c, k = 1 / math.tan(math.radians(psi)), kappa(nu)
    first = 1 + A * k * c
    return first if order == 1 else first - (B_C - (C2_SHIPPED if c2 is None else c2) * k * k) * c * c


C2_SHIPPED = 0.33   # fit_c2() of this benchmark's runs (psi >= 65 deg: 0.331)


def gamma_hay(psi, nu):
    """Hay, Bolshakov & Pharr (1999): the simple form 1 + (1-2nu)/(4(1-nu) tan psi) and the full one."""
    e = kappa(nu) / 2 / math.tan(math.radians(psi))
    return 1 + e, math.pi * (math.pi / 4 + 0.15483073 * e) / (math.pi / 2 - 0.83119312 * e) ** 2


def b_cerruti(nu=0.3):
    """B_C: the load lost, at second order in cot psi, because the shear traction c p of a face-normal pressure p
    moves the contact surface outward (Cerruti's tangential point load, integrated over rings of Sneddon's cone
    pressure p ~ arccosh(a/r)), where the cone is higher. Independent of nu (checked at 0 and 0.3)."""
    from scipy.integrate import quad
    from scipy.interpolate import CubicSpline

    def u_r(r):  # radial displacement at r, shear modulus 1, traction arccosh(1/t) on t < 1
        def ring(t):
            def f(th):
                rx, ry = r - t * np.cos(th), -t * np.sin(th)
                rho2 = rx * rx + ry * ry
                return (2 * (1 - nu) * np.cos(th) + 2 * nu * rx * (r * np.cos(th) - t) / rho2) / (4 * np.pi * np.sqrt(rho2))
            return 2 * quad(f, 0, np.pi, limit=400)[0] * t
        return quad(lambda t: np.arccosh(1 / t) * ring(t), 0, 1, points=[r] if 0 < r < 1 else None, limit=400)[0]
    rs = np.linspace(0, 1, 41)
    g = CubicSpline(rs, [u_r(max(r, 1e-9)) / (1 - nu) for r in rs])   # the profile change / c^3 (E*/(2G) = 1/(1-nu))
    d = g.derivative()
    ih = quad(lambda x: d(np.sin(x)), 0, np.pi / 2, limit=200)[0]
    ip = quad(lambda x: np.sin(x) ** 2 * d(np.sin(x)), 0, np.pi / 2, limit=200)[0]
    return -(4 / math.pi * (-g(0) - ih) + 4 / math.pi * ip)


def scene(psi, nu, gap, m, root=None):
    """The axisymmetric elastic block under a rigid cone of half-angle psi pushed to (pi/2) cot psi, Sneddon's
    contact radius 1, `gap` vertical or normal, on the mesh parameters m (MESH, QUICK); the block's .geo that of the
    repository `root` (default: camclay9.repo_root())."""
    h = math.pi / 2 / math.tan(math.radians(psi))
    return f"""scene: fe
mesh:
  geometry: {repo_root(root)}/meshes/indent_block2d.geo
  parameters: {{W: {m['W']}, H: {m['H']}, half: 1, h_tip: {m['h_tip']}, h_far: {m['h_far']}, r_fine: {m['r_fine']}, r_contact: {m['r_contact']}}}
  kinematics: axisymmetric
  order: {m['order']}
material: {{umat: elastic, props: [{E}, {nu}], nstatv: 0}}
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {{shape: cone, half_angle: {psi}, contact: contact{', gap: vertical' if gap == 'vertical' else ''}}}
stages:
  - {{name: push, duration: 1, indenter: {{depth: {h:.10g}}}, steps: {{count: 8}}}}
output: {{fields_every: 0}}
"""
