#!/usr/bin/env python3
"""Standard errors for correlated residuals (issue 37; docs/calibrate.md, "Standard errors"): which estimate covers
the truth when the depth noise wanders along the record? The record is calibrate_coverage.py's (the nano drift-hold
protocol, 10 rows a second, the depths of the forward scene the fit runs at eta_soft = 1.7e10); its Jacobian in
ln(eta_soft) by central differences (forward runs at 1.7e10 x 0.99 and 1.01), the residuals weighted by the noise
(weighting: noise), a block per stage, the holds less their means. Each draw adds AR(1) depth noise of lag-1 rho to
the exact depths and takes the linearised fit, d = G r (G = -(J^T J)^-1 J^T); the estimates of its standard error,
written here as calibrate_stats.c computes them:

  white        s^2 sum g_i^2, independent residuals of one size (the fit's before issue 37)
  scores       Newey-West on the scores g_i r_i, Bartlett kernel, Andrews' AR(1) bandwidth (their own form)
  errors       the same kernel on the residuals' autocovariance, weighted by g_i g_j
  prewhitened  the residuals prewhitened by an AR(1) (|rho| <= 0.99, Prais-Winsten's first row), the kernel on the
               innovations (calibrate_stats.c)

and counts the draws whose truth lies within 2 of them.

  bench/calibrate_se_study.py [--draws 40] [--rho 0,0.9,0.98]
"""
import argparse
import os
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import driver_path, read_history, run_driver

import calibrate_coverage as cov

TRUTH = 1.7e10


def lag1(x, sizes, cap):
    num = den = 0.0
    for b in np.split(x, np.cumsum(sizes)[:-1]):
        num += b[1:] @ b[:-1]
        den += b[:-1] @ b[:-1]
    return float(np.clip(num / den, -cap, cap)) if den > 0 else 0.0


def kernel(e, h, sizes, a):
    """sum over blocks of k(l/S) c(l) sum_i h_i h_i+l (both orders), c the block's autocovariance of e."""
    alpha = 4 * a * a / ((1 - a) ** 2 * (1 + a) ** 2)
    v = 0.0
    for eb, hb in zip(np.split(e, np.cumsum(sizes)[:-1]), np.split(h, np.cumsum(sizes)[:-1])):
        t = len(eb)
        s = 1.1447 * (alpha * t) ** (1 / 3)
        for lag in range(0, max(min(int(np.ceil(s)) - 1, t - 1), 0) + 1):
            c = (eb[:t - lag] @ eb[lag:]) / t * (1 - lag / s if lag else 1)
            v += c * (hb @ hb if lag == 0 else 2 * (hb[:t - lag] @ hb[lag:]))
    return v


def estimates(r, g, sizes):
    m = len(r)
    white = (r @ r) / (m - 1) * (g @ g)
    s = g * r
    scores = 0.0
    a = lag1(s, sizes, 0.97)
    scores = kernel(s, np.ones(m), sizes, a)
    errors = kernel(r, g, sizes, lag1(r, sizes, 0.97))
    rho = lag1(r, sizes, 0.99)
    eta, h = [], []
    for rb, gb in zip(np.split(r, np.cumsum(sizes)[:-1]), np.split(g, np.cumsum(sizes)[:-1])):
        e = rb.copy()
        e[1:] = rb[1:] - rho * rb[:-1]
        e[0] *= np.sqrt(1 - rho * rho)
        hb, acc = np.zeros(len(gb)), 0.0
        for j in range(len(gb) - 1, -1, -1):
            acc = gb[j] + rho * acc
            hb[j] = acc
        hb[0] /= np.sqrt(1 - rho * rho)
        eta.append(e), h.append(hb)
    eta, h = np.concatenate(eta), np.concatenate(h)
    pre = kernel(eta, h, sizes, lag1(eta, sizes, 0.97))
    return {k: float(np.sqrt(v)) for k, v in (("white", white), ("scores", scores), ("errors", errors), ("prewhitened", pre))}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--draws", type=int, default=40)
    ap.add_argument("--rho", default="0,0.9,0.98")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        head, rec = cov.exact_record(TRUTH, work, print)
        t = rec[:, head.index("time_s")] - rec[0, head.index("time_s")]
        seg = rec[:, head.index("segment")].astype(int)
        depth = {}
        for f in (0.99, 1.0, 1.01):
            out = work / f"run_{f}"
            run_driver(work / "dry" / "protocol" / "nano" / "scene.yaml", out,
                       ["-material_set", f"eta_soft={TRUTH * f:.17g}", "-progress_every", "1000000"], root=cov.ROOT,
                       timeout=900)
            h = read_history(out, need=("time", "depth"))
            depth[f] = 1e3 * np.interp(t, h["time"], h["depth"])
    stages = sorted(set(seg))
    blocks = [np.nonzero(seg == s)[0] for s in stages]
    holds = [abs(rec[b[-1], head.index("load_mN")] - rec[b[0], head.index("load_mN")]) < 0.05 * rec[:, 1].max() for b in blocks]
    sizes = [len(b) for b in blocks]

    def residual(model, data):
        out = []
        for b, hold in zip(blocks, holds):
            y, mm = data[b], model[b]
            if hold:
                y, mm = y - y.mean(), mm - mm.mean()
            out.append(mm - y)
        return np.concatenate(out)

    clean = depth[1.0]
    jac = (residual(depth[1.01], clean) - residual(depth[0.99], clean)) / (np.log(1.01) - np.log(0.99))
    g = -jac / (jac @ jac)
    print(f"| depth noise lag-1 | draws | sd of the error in ln eta | {' | '.join(f'{k}: mean s.e., covered' for k in ('white', 'scores', 'errors', 'prewhitened'))} |")
    print("|---|---|---|---|---|---|---|")
    for rho in (float(x) for x in a.rho.split(",")):
        errs, ests = [], []
        for k in range(a.draws):
            e = np.random.default_rng(k).standard_normal(len(t))
            for i in range(1, len(e)):
                e[i] = rho * e[i - 1] + np.sqrt(1 - rho * rho) * e[i]
            r0 = residual(clean, clean + e)
            d = g @ r0
            errs.append(d), ests.append(estimates(r0 + jac * d, g, sizes))
        errs = np.array(errs)
        cells = [f"{np.mean([x[k] for x in ests]):.4f}, {np.mean(np.abs(errs) < 2 * np.array([x[k] for x in ests])):.0%}"
                 for k in ("white", "scores", "errors", "prewhitened")]
        print(f"| {rho} | {a.draws} | {np.std(errs):.4f} | {' | '.join(cells)} |", flush=True)


if __name__ == "__main__":
    os.environ.setdefault("DRIVER", str(driver_path(root=cov.ROOT)))
    sys.exit(main())
