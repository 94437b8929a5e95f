"""Lomnitz (logarithmic) creep law  eps(t) = B ln(1 + t/tau)  and its least-squares fit.

Yin, Liu & Borja (2021) fit their creep curves with this law (theory.md §5.4: B = 9.97e-5, tau = 385 s
for theta = 0). t is the time since the creep load was applied, eps the creep strain (a magnitude,
so B > 0), ln the natural logarithm.
"""
import numpy as np
from scipy.optimize import curve_fit


def lomnitz(t, B, tau):
    """B ln(1 + t/tau), natural log."""
    return B * np.log1p(np.asarray(t, float) / tau)


def _best_B(g, y):
    """Linear least-squares B for y ~ B g (tau fixed), kept positive."""
    return max(float(g @ y) / float(g @ g), 1e-300)


def _initial_guess(t, y):
    """(B, tau) from a log-spaced scan of tau; for each tau the best B is a linear least-squares
    solution. The scan spans three decades beyond the sampled times on each side, so it cannot miss
    the basin of the minimum; curve_fit then only polishes."""
    tpos = t[t > 0]
    best = None
    for tau in np.geomspace(tpos.min() * 1e-3, tpos.max() * 1e3, 241):
        g = np.log1p(t / tau)
        B = _best_B(g, y)
        r = float(np.sum((B * g - y) ** 2))
        if best is None or r < best[0]:
            best = (r, B, tau)
    return best[1], best[2]


def lomnitz_fit(t, eps):
    """Fit eps = B ln(1 + t/tau) to samples (t, eps); returns (B, tau) with B > 0, tau > 0.

    Points with non-finite values or t < 0 are ignored. Raises ValueError when there is nothing to
    fit (fewer than two points with t > 0, or no positive strain) and RuntimeError when the
    least-squares iteration does not converge.
    """
    t = np.asarray(t, float).ravel()
    eps = np.asarray(eps, float).ravel()
    if t.shape != eps.shape:
        raise ValueError(f"lomnitz_fit: t and eps differ in length ({t.size} vs {eps.size})")
    keep = np.isfinite(t) & np.isfinite(eps) & (t >= 0)
    t, eps = t[keep], eps[keep]
    if np.count_nonzero(t > 0) < 2:
        raise ValueError("lomnitz_fit: need at least two points with t > 0")
    scale = np.max(np.abs(eps))
    if not np.max(eps) > 0:
        raise ValueError("lomnitz_fit: no positive creep strain to fit (pass the magnitude)")
    y = eps / scale                                   # fit an O(1) curve; B is rescaled at the end
    B0, tau0 = _initial_guess(t, y)
    (B, tau), _ = curve_fit(lomnitz, t, y, p0=(B0, tau0), bounds=([0.0, 0.0], [np.inf, np.inf]),
                            x_scale=(B0, tau0), ftol=1e-14, xtol=1e-14, gtol=1e-14, max_nfev=2000)
    return float(B * scale), float(tau)
