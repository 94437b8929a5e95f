"""The 2D fields of the paper's loading-rate and bedding studies (Yin, Liu & Borja 2021, §4, Figs. 9-13 and 15): their
numbers and their figures, from the runs of tools/reproduce.py.

Every map is drawn from nodal averages (camclay9.indent_fields), so the cell-to-cell checkerboard of linear triangles
does not show, on the undeformed mesh with the tip at the origin; the panels of one figure (the three loading rates,
the hold times) share one colour scale. Every number is a mean over a fixed region or a ring of the undeformed
mesh (cells clipped to it), never one cell. The loading-rate regions are scaled by A_LR, the contact half-width at
the end of loading rounded (h tan 68.26 deg: 0.53, 0.48, 0.43 um for alpha = 0.1, 1, 10), the same for every alpha.
"""
import math
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.tri import Triangulation

from camclay9.fields import Fields, dev_norm, tensor_norm, trace
from camclay9.indent_fields import cell_areas, checkerboard, clipped_areas, nodal_average, region_mean, six
from camclay9.indent_plots import History, STAGE_COLUMNS, thin

A_LR = 0.5
BENEATH = (-A_LR / 4, A_LR / 4, -A_LR / 2, 0.0)       # Fig. 13's probe and Fig. 12's 'beneath' (bench/indent2d_...)
SIDES = ((-1.5 * A_LR, -0.5 * A_LR, -A_LR / 2, 0.0), (0.5 * A_LR, 1.5 * A_LR, -A_LR / 2, 0.0))
HOLD_TIMES = (100.0, 500.0, 2000.0)
A_BED = 5.0     # the bedding scenes' contact half-width, rounded (h tan 68.26 deg: 5.2-5.5 um over theta)
REGION_KEYS = ("a_ref", "tr_p99", "tr_frac", "dev_p99", "dev_frac", "dsig_beneath", "dsig_sides")
ZONE_LEVELS = (0.05, 0.1, 0.2)   # Fig. 11's zone: above this x its 99th percentile (0.1 the verdict's); sensitivity
ZONE_CUTOFFS = (2.0, 3.0, 4.0)   # ... and within this x a of the tip (3 the verdict's)
WINDOW = 0.6    # half-width of the loading-rate maps [um]
DPI = 90


def half_model(F):
    """Whether the run's mesh is a half model x >= 0 (the loading-rate scenes, bedding at theta = 0 and 90: mirror plane
    x = 0, indenter.copies 2)."""
    return bool(F.x[:, 0].min() >= -1e-9 * np.ptp(F.x[:, 0]))


class Hold:
    """A 2D run's fields at the start of the hold (k0), its end (k1), the hold times (ks) and every output in it."""

    def __init__(self, run):
        self.run = Path(run)
        self.t0, self.t1 = History(run, need=STAGE_COLUMNS).hold_times()
        self.F = Fields(run)
        F = self.F
        self.k0, self.k1 = F.nearest(self.t0), F.nearest(self.t1)
        self.ks = [F.nearest(self.t0 + th, self.t0, self.t1) for th in HOLD_TIMES]
        self.kall = [k for k in range(F.times.size) if self.t0 - 1e-9 <= F.times[k] <= self.t1 + 1e-9]
        self.A = cell_areas(F)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.F.f.close()

    def evp(self, k):
        return tensor_norm(six(self.F, "evp", k), True)

    def sig(self, k):
        return tensor_norm(six(self.F, "stress", k), False)


# ------------------------------------------------------------------ numbers
def area_percentile(values, areas, q):
    """The q-th percentile of cell values weighted by the cells' areas: the value below which q % of the area lies.
    Not the cells' count: on a graded or adapted mesh the small cells near the tip would outweigh the rest, and a
    count percentile would move with the mesh, not with the field."""
    o = np.argsort(values)
    cum = np.cumsum(areas[o])
    return float(values[o][min(np.searchsorted(cum, q / 100 * cum[-1]), cum.size - 1)])


def count_percentile(values, areas, q):
    """The q-th percentile of cell values over the cells by their count, whatever their areas (docs/paper.md before
    2026-12-02; bench/paper_measures_bench.py compares the two)."""
    return float(np.percentile(values, q))


def ring_profile(H, values, a, nbins=12, rmax=2.0):
    """Area means of cell values (below the surface) in rings around the tip, r/a in [0, rmax] in nbins rings."""
    F = H.F
    r = np.hypot(F.centroids[:, 0], F.centroids[:, 1]) / a
    edges = np.linspace(0, rmax, nbins + 1)
    means = [float(np.sum(values[m] * H.A[m]) / np.sum(H.A[m])) if np.any(m) else float("nan")
             for m in ((r >= lo) & (r < hi) for lo, hi in zip(edges[:-1], edges[1:]))]
    return 0.5 * (edges[:-1] + edges[1:]), np.array(means)


def sector_shares(H, values, a, rmax=3.0, level=0.1, percentile=area_percentile):
    """Fig. 11: the inelastic zone (cells within rmax a of the tip where values > level x their 99th percentile
    there, by area), split by the angle from the surface (0-30, 30-60, 60-90 deg: beside the indent ... beneath it): each
    part's share of the zone's integral of values; and the zone's fill of the half-disc of its 95th-percentile
    radius (by area) (1: a whole circular region). percentile: area_percentile, or count_percentile to compare."""
    F = H.F
    x, y = F.centroids[:, 0], F.centroids[:, 1]
    r = np.hypot(x, y)
    near = (r < rmax * a) & (y < 0)
    top = percentile(values[near], H.A[near], 99)
    zone = near & (values > level * top)
    ang = np.degrees(np.arctan2(-y, np.abs(x)))          # 0: along the surface, 90: straight down
    w = values * H.A
    tot = np.sum(w[zone])
    shares = [float(np.sum(w[zone & (ang >= lo) & (ang < hi)]) / tot) for lo, hi in ((0, 30), (30, 60), (60, 90.01))]
    R = percentile(r[zone], H.A[zone], 95)
    whole = 2 if half_model(F) else 1                 # a half model holds half of the zone's area
    fill = float(whole * np.sum(H.A[zone & (r <= R)]) / (0.5 * math.pi * R * R))
    return dict(surface=shares[0], middle=shares[1], beneath=shares[2], fill=fill, radius=float(R / a))


def loading_rate_numbers(run, percentile=area_percentile):
    """Figs. 9-13 as numbers (docs/paper.md), None without fields.h5; percentile: as sector_shares'."""
    if not (Path(run) / "fields.h5").is_file():
        return None
    with Hold(run) as H:
        F, a = H.F, A_LR
        e0, e1 = H.evp(H.k0), H.evp(H.k1)
        near05 = np.hypot(F.centroids[:, 0], F.centroids[:, 1]) < 0.5
        w05 = H.A * near05
        res = {"evp_start": {"mean": float(np.sum(e0 * w05) / np.sum(w05)),
                             "max": float(np.nanmax(nodal_average(F, e0)[np.hypot(F.x[:, 0], F.x[:, 1]) < 0.5]))}}
        # Fig. 9: volumetric against deviatoric vp strain at the end of the hold: the 99th percentile within 2a of
        # the tip, and the fraction of that half-disc's area where each exceeds 10 % of it (how concentrated)
        ev = six(F, "evp", H.k1)
        near = np.hypot(F.centroids[:, 0], F.centroids[:, 1]) < 2 * a
        for name, v in (("tr", np.abs(trace(ev))), ("dev", dev_norm(ev, True))):
            top = percentile(v[near], H.A[near], 99)
            res[f"{name}_p99"] = top
            res[f"{name}_frac"] = float(H.A[near & (v > 0.1 * top)].sum() / H.A[near].sum())
        # Fig. 10(b): where the hold's vp strain grows most, relative to the tip
        de = e1 - e0
        rc, prof = ring_profile(H, de, a)
        nod = nodal_average(F, de)
        below = (F.x[:, 1] <= 0) & np.isfinite(nod)
        j = np.flatnonzero(below)[np.argmax(nod[below])]
        res["fig10b"] = {"ring_r": rc.tolist(), "ring_mean": prof.tolist(), "r_peak": float(rc[np.nanargmax(prof)]),
                         "peak_over_tip_ring": float(np.nanmax(prof) / prof[0]), "nodal_max_at": F.x[j, :2].tolist(),
                         "nodal_max_r": float(np.hypot(*F.x[j, :2]) / a)}
        # ... and of the total |evp| at the end of the hold, which is what the paper's Fig. 10 draws
        rc, prof = ring_profile(H, e1, a)
        res["fig10b_total"] = {"ring_mean": prof.tolist(), "r_peak": float(rc[np.nanargmax(prof)]),
                               "peak_over_tip_ring": float(np.nanmax(prof) / prof[0])}
        # Fig. 11: shape of the zone where the vp strain grows, at each hold time, and for other zone levels and cutoffs
        res["fig11"], res["fig11_sens"] = {}, {}
        for th, k in zip(HOLD_TIMES, H.ks):
            d = H.evp(k) - e0
            res["fig11"][f"{th:g}"] = sector_shares(H, d, a, percentile=percentile)
            res["fig11_sens"][f"{th:g}"] = {f"{lv:g}/{rm:g}": sector_shares(H, d, a, rmax=rm, level=lv, percentile=percentile)
                                            for lv in ZONE_LEVELS for rm in ZONE_CUTOFFS}
        # Figs. 12, 13: |sigma| beneath the tip and beside the indent (region means)
        s0 = H.sig(H.k0)
        wb = clipped_areas(F, BENEATH)
        ws = clipped_areas(F, SIDES[0]) + clipped_areas(F, SIDES[1])
        ds = H.sig(H.k1) - s0
        res["dsig_beneath"], res["dsig_sides"] = region_mean(ds, wb), region_mean(ds, ws)
        res["fig13"] = {"t": [float(F.times[k] - F.times[H.k0]) for k in H.kall],
                        "dsig": [region_mean(H.sig(k) - s0, wb) for k in H.kall], "sig0": region_mean(s0, wb)}
        res["a_ref"] = a
        res["checker"] = checkerboard(F, H.sig(H.k1), near & (np.hypot(F.centroids[:, 0], F.centroids[:, 1]) < a))
        return res


def flow_direction(run, a, theta):
    """Fig. 15: the displacement increments of the hold within 2a of the tip (vertices below the surface), their
    principal direction (flow_axis). A half model's (bedding at theta = 0 and 90) with its mirror image: the whole
    block's field."""
    if not (Path(run) / "fields.h5").is_file():
        return None
    with Hold(run) as H:
        F = H.F
        x, du, w = F.x, F.u[H.k1] - F.u[H.k0], nodal_areas(F, H.A)
        if half_model(F):
            x, du, w = mirrored(x, du, w)
        return flow_axis(x, du, a, theta, w)


def nodal_areas(F, areas):
    """Each vertex's share of the area around it: every cell's area split equally among its vertices (a lumped mass),
    so that sums over the vertices weigh the field by area, not by how densely the mesh holds vertices."""
    w = np.zeros(len(F.x))
    np.add.at(w, F.cells.ravel(), np.repeat(areas / F.cells.shape[1], F.cells.shape[1]))
    return w


def mirrored(x, v, *scalars):
    """A half model's nodal vectors v at x (x >= 0) with their mirror image about x = 0: the whole block's, the nodes on
    the axis once (the mirror plane holds v_x = 0 there); nodal scalars (weights) follow their nodes unchanged."""
    m = x[:, 0] > 1e-9 * np.ptp(x[:, 0])
    return (np.r_[x, x[m] * [-1, 1]], np.r_[v, v[m] * [-1, 1]], *(np.r_[s, s[m]] for s in scalars))


def flow_axis(x, du, a, theta, w=None):
    """The principal direction of the increments du at x within 2a of the tip (vertices below the surface): the
    orientation tensor's axis, weighted by |du|^2 and by the vertices' areas w (nodal_areas; None: equal weights), as the angle from the downward vertical, positive toward +x; and on
    the same convention the bedding normal's axis (BN; n = (sin t, cos t) with y up, so its downward half points at -t)
    and the planes' (BP, at 90 - t). A principal axis tilted from the load toward BN's side is flow toward BN."""
    sel = (np.hypot(x[:, 0], x[:, 1]) < 2 * a) & (x[:, 1] < 0)
    wt = np.ones(len(x)) if w is None else np.asarray(w)
    T = (du[sel] * wt[sel, None]).T @ du[sel]
    w, v = np.linalg.eigh(T)
    d = v[:, -1] * (1 if v[1, -1] < 0 else -1)          # the principal axis, pointing down
    beta = math.degrees(math.atan2(d[0], -d[1]))
    mean = np.average(du[sel], axis=0, weights=wt[sel])
    return {"beta": beta, "anisotropy": float(w[-1] / max(w[0], 1e-300)), "theta": theta, "beta_bn": -float(theta),
            "mean_du": mean.tolist(), "mean_angle": math.degrees(math.atan2(mean[0], -mean[1]))}


# ------------------------------------------------------------------ figures
def _map(fig, ax, F, nodal, lim, clim, cmap, title):
    """A map of nodal values; a half model's with its mirror image, so that it shows the whole block."""
    for sign in ((1, -1) if half_model(F) else (1,)):
        tri = Triangulation(sign * F.x[:, 0], F.x[:, 1], F.cells)
        pc = ax.tripcolor(tri, nodal, shading="gouraud", cmap=cmap, vmin=clim[0], vmax=clim[1])
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, 0.05 * lim)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=8)
    ax.tick_params(labelsize=7)
    return pc


def _clim(arrays, Fs, lim, diverging):
    """The colour limits of nodal arrays within the window; Fs: each array's fields (runs on meshes of their own, as
    adapted ones are)."""
    v = np.concatenate([x[(np.abs(G.x[:, 0]) <= lim) & (G.x[:, 1] >= -lim)] for x, G in zip(arrays, Fs)])
    v = v[np.isfinite(v)]
    if diverging:
        s = float(np.percentile(np.abs(v), 99)) or 1.0
        return (-s, s), "RdBu_r"
    lo, hi = np.percentile(v, [1, 99])
    return (float(lo), float(hi) if hi > lo else float(lo) + 1e-12), "viridis"


def _grid(runs, labels, columns, fields, title, label, path, diverging=False):
    """One figure, a row per run, a column per output; fields(H) gives one cell array per column; one scale."""
    Hs = [Hold(r) for r in runs]
    try:
        nods = [[nodal_average(H.F, v) for v in fields(H)] for H in Hs]
        clim, cmap = _clim([x for row in nods for x in row], [H.F for H, row in zip(Hs, nods) for _ in row], WINDOW, diverging)
        fig = Figure(figsize=(3.3 * len(columns) + 1.2, 2.3 * len(Hs) + 0.6), layout="constrained")
        axs = np.atleast_2d(fig.subplots(len(Hs), len(columns), squeeze=False))
        for i, (H, row) in enumerate(zip(Hs, nods)):
            for j, v in enumerate(row):
                pc = _map(fig, axs[i, j], H.F, v, WINDOW, clim, cmap, f"{labels[i]}, {columns[j]}")
        fig.colorbar(pc, ax=axs, shrink=0.8, extend="both").set_label(label + " (nodal averages; 1–99 % of all panels)", fontsize=8)
        fig.suptitle(title, fontsize=9)
        fig.savefig(path, dpi=DPI)
        return path
    finally:
        for H in Hs:
            H.__exit__()


def draw_loading_rate(runs, labels, figs):
    """Figs. 9-13 into figs/; returns {figure id: [(path, caption)]}."""
    runs = [Path(r) for r in runs]
    if not all((r / "fields.h5").is_file() for r in runs):
        return {}
    out = {}
    a1 = runs[labels.index("α = 1")]
    # Fig. 9: the two quantities have scales of their own, each shared by its two times
    with Hold(a1) as H:
        fig = Figure(figsize=(8, 5), layout="constrained")
        axs = fig.subplots(2, 2)
        for i, (name, f) in enumerate((("tr ε^vp", lambda e: trace(e)), ("‖dev ε^vp‖", lambda e: dev_norm(e, True)))):
            vals = [nodal_average(H.F, f(six(H.F, "evp", k))) for k in (H.k0, H.k1)]
            clim, cmap = _clim(vals, [H.F] * len(vals), WINDOW, name.startswith("tr") and min(v.min() for v in vals) < 0 < max(v.max() for v in vals))
            for j, (v, when) in enumerate(zip(vals, ("start of hold", "end of hold"))):
                pc = _map(fig, axs[i, j], H.F, v, WINDOW, clim, cmap, f"{name}, {when}")
            fig.colorbar(pc, ax=axs[i, :], shrink=0.8).set_label(name, fontsize=8)
        fig.suptitle("cf. Fig. 9, α = 1 (nodal averages)", fontsize=9)
        fig.savefig(figs / "fig9_a1.png", dpi=DPI)
    out["fig9"] = [(figs / "fig9_a1.png", "α = 1: tr ε^vp and ‖dev ε^vp‖ at the start and the end of the hold")]
    out["fig10"] = [(_grid(runs, labels, ["start of hold", "end of hold"], lambda H: [H.evp(H.k0), H.evp(H.k1)],
                           "cf. Fig. 10: ‖ε^vp‖", "‖ε^vp‖", figs / "fig10.png"), "‖ε^vp‖, all α, one colour scale")]
    cols = [f"{t:g} s into the hold" for t in HOLD_TIMES]
    out["fig11"] = [(_grid(runs, labels, cols, lambda H: [H.evp(k) - H.evp(H.k0) for k in H.ks],
                           "cf. Fig. 11: Δ‖ε^vp‖ since the start of the hold", "Δ‖ε^vp‖", figs / "fig11.png"),
                     "Δ‖ε^vp‖ since the start of the hold, all α, one colour scale")]
    out["fig12"] = [(_grid(runs, labels, cols, lambda H: [H.sig(k) - H.sig(H.k0) for k in H.ks],
                           "cf. Fig. 12: Δ‖σ‖ since the start of the hold [MPa]", "Δ‖σ‖ [MPa]", figs / "fig12.png",
                           diverging=True), "Δ‖σ‖ since the start of the hold, all α, one colour scale")]
    out["fig13"] = [(fig13(runs, labels, figs / "fig13_tip_stress.png"),
                     f"Δ‖σ‖ over the region beneath the tip (|x| < {BENEATH[1]:g}, −{-BENEATH[2]:g} < y < 0 µm), all α")]
    return out


def fig13(runs, labels, path):
    fig = Figure(figsize=(6, 4))
    ax = fig.subplots()
    for k, (run, lab) in enumerate(zip(runs, labels)):
        n = loading_rate_numbers(run)["fig13"]
        ax.plot(n["t"], n["dsig"], ".-", ms=4, color=f"C{k}", label=lab)
    ax.axhline(0, color="k", lw=0.6)
    ax.set_xlabel("time since the start of the hold [s]")
    ax.set_ylabel("Δ‖σ‖, mean over the region [MPa]")
    ax.set_title(f"cf. Fig. 13: region |x| < {BENEATH[1]:g} µm, −{-BENEATH[2]:g} < y < 0 µm (paper: a rise for α = 0.1)",
                 fontsize=8)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    return path


def fig15(run, theta, a, path, max_arrows=400):
    """Displacement increments of the hold around the tip, the bedding planes drawn, the normal (BN) and the
    measured principal flow axis marked."""
    d = flow_direction(run, a, theta)
    with Hold(run) as H:
        F = H.F
        du = F.u[H.k1] - F.u[H.k0]
        lim = 2.5 * a
        sel = np.flatnonzero((np.abs(F.x[:, 0]) < lim) & (F.x[:, 1] > -lim) & (F.x[:, 1] <= 0))
        sel = sel[thin(F.x[sel], (-lim, lim, -lim, 0.0), max_arrows)]
        mag = np.hypot(du[sel, 0], du[sel, 1])
        fig = Figure(figsize=(7.5, 4.6), layout="constrained")
        ax = fig.subplots()
        t = math.radians(theta)
        along = np.array([math.cos(t), -math.sin(t)])          # bedding planes: normal (sin t, cos t)
        for s in np.linspace(-2 * lim, 2 * lim, 17):
            p = s * np.array([math.sin(t), math.cos(t)])
            q = np.array([p - 3 * lim * along, p + 3 * lim * along])
            ax.plot(q[:, 0], q[:, 1], color="0.85", lw=0.7, zorder=0)
        q = ax.quiver(F.x[sel, 0], F.x[sel, 1], du[sel, 0], du[sel, 1], mag, cmap="viridis", angles="xy", zorder=2)
        fig.colorbar(q, ax=ax, shrink=0.7, label="|Δu| over the hold [µm]")
        c = np.array([0.0, -1.2 * a])
        for ang, col, lab in ((-theta, "C3", f"bedding normal (BN), {theta:g}° from the load axis"),
                              (d["beta"], "k", f"principal axis of the flow, {abs(d['beta']):.1f}° from the load axis, "
                                                f"{'on BN' if d['beta'] * theta < 0 else 'on BP'}'s side")):
            v = 0.9 * a * np.array([math.sin(math.radians(ang)), -math.cos(math.radians(ang))])
            ax.plot([c[0] - v[0], c[0] + v[0]], [c[1] - v[1], c[1] + v[1]], color=col, lw=2, label=lab, zorder=3)
        ax.plot([], [], color="0.85", label=f"bedding planes (θ = {theta:g}°)")
        ax.legend(fontsize=7, loc="lower right")
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, 0.1 * lim)
        ax.set_aspect("equal")
        ax.set_xlabel("x [µm]")
        ax.set_ylabel("y [µm]")
        ax.set_title(f"cf. Fig. 15: displacement increments over the hold, θ = {theta:g}°", fontsize=9)
        fig.savefig(path, dpi=DPI)
    return path
