"""Plots of an indentation run of the FE driver (Yin, Liu & Borja 2021, Figs. 3-15).

Usage:
    post/indent_plots.py [ph] RUN [--out DIR] [--hold-stage hold]
    post/indent_plots.py compare RUN1 RUN2 ... [--labels a b ...] [--out DIR]
    post/indent_plots.py fields RUN [--window W] [--deformed [--scale S]] [--hold-times 100 500 2000]
                                    [--evp evp|evp_soft|evp_hard] [--region X0 X1 Y0 Y1 | --probe X Y]
                                    [--out DIR]
    post/indent_plots.py vectors RUN [--window W] [--deformed] [--max-arrows N] [--out DIR]
    post/indent_plots.py profile RUN [--time T] [--out DIR]

  ph       P-h curve over all stages, coloured by stage (ph.png); depth vs time over all stages and the
           creep depth h - h(start of hold) vs time since the start of the hold (creep.png); creep.json
           {max_load, depth_end_of_load, depth_end_of_hold, creep_depth, residual_depth, ...}. The default
           subcommand: `indent_plots.py RUN` is `indent_plots.py ph RUN`.
  compare  several runs on one P-h plot and one creep-depth plot (Figs. 7, 8, 14): compare_ph.png,
           compare_creep.png in --out (default: the current directory).
  fields   2D runs: maps at the output nearest to the start and to the end of the hold of tr(evp) and
           |dev evp| (fig9.png), |evp| (fig10.png); the change from the start of the hold of |evp|
           (fig11.png) and of |sigma| (fig12.png) at the outputs nearest to the --hold-times; the change
           of |sigma| vs time at every output of the hold (fig13.png), as docs/paper.md measures Fig. 13: its
           mean over a region beneath the tip (the cells clipped to it), --region X0 X1 Y0 Y1, by default
           |x| < a/4, -a/2 < y < 0 with a = 2.5 x the depth at the end of loading (the contact half-width of
           the paper's wedge: tan 68.26 deg = 2.5); --probe X Y: the one cell nearest instead. More outputs
           in the hold (output.fields_every) sample the curve more finely.
  vectors  2D runs: displacement increments u(end of hold) - u(start of hold) around the tip (Fig. 15,
           vectors.png).
  profile  residual surface profile (Fig. 5): vertical displacement of the top-surface vertices (y = 0 in
           2D, z = 0 in 3D) at the last output (or the one nearest to --time): a line vs x in 2D, a
           filled contour map over (x, y) in 3D (profile.png).

Every figure goes to --out DIR (default RUN), and the numbers plotted are printed, one line per curve.

Input, written by the driver into RUN: history.csv, one row per converged step (time, stage, stage_name, load,
depth, ...: docs/driver.md; load per unit thickness in plane strain, depth in um, time in s; only the columns a
subcommand uses are required), and fields.h5 (docs/driver.md, "Fields"; cell averages of the tensors, read
through camclay9.fields as 11 22 33 12 13 23, strains with engineering shear).

Colour scales of the maps (fields) are robust: they span the --clip .. 100 - --clip percentiles of the
cells in view (default 1-99 %), so the few singular cells at the tip do not wash the map out; the colour
bar says so, and its arrows mark the clipped ends. --clip 0 gives the full min..max.

Conventions: tension positive; 2D meshes are (x, y) with y up, the top surface at y = 0 and the tip at
the origin pushing along -y. Tensor norms are Frobenius norms with tensor shear (engineering shear / 2
for strains), over all six components (33 is the out-of-plane or hoop component in 2D).
"""
import argparse
import json
import sys
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure   # no pyplot: figures are saved with Agg, no global state
from matplotlib.tri import Triangulation

from camclay9 import read_history
from camclay9.fields import Fields, dev_norm, tensor_norm, trace
from camclay9.history import history_path
from camclay9.indent_fields import clipped_areas, region_mean

HISTORY_COLUMNS = ("time", "stage", "stage_name", "step", "dt", "newton_its", "cutbacks", "load", "depth",
                   "active_nodes", "active_changes", "contact_force", "max_penetration", "min_lambda",
                   "umat_calls", "wall")
PH_COLUMNS = ("time", "stage", "stage_name", "step", "load", "depth")
STAGE_COLUMNS = ("time", "stage", "stage_name")
VOIGT = ("11", "22", "33", "12", "13", "23")
ENGINEERING_SHEAR = {"stress": False, "strain": True, "evp": True, "evp_hard": True, "evp_soft": True}
SUBCOMMANDS = ("ph", "compare", "fields", "vectors", "profile")


# ------------------------------------------------------------------ history.csv
class History:
    """The columns `need` of history.csv (read by camclay9.read_history): float arrays, and `stage_name` a list of
    str. Errors: SystemExit naming the file (and line, column, value)."""

    def __init__(self, run, need=PH_COLUMNS):
        self.path = path = history_path(run)
        try:
            h = read_history(path, need=need)
        except (OSError, ValueError) as err:
            raise SystemExit(str(err)) from None
        if h.size == 0:
            raise SystemExit(f"{path}: no data rows after the header")
        self.columns = {c: [s.strip() for s in h[c].tolist()] if c == "stage_name" else h[c].astype(float) for c in need}

    def __getitem__(self, name):
        return self.columns[name]

    def stages(self):
        """[(stage index, name, rows)] in order of first appearance; each stage's rows begin with the last
        row before the stage (the end of the previous stage, or the initial state), so that curves join."""
        st = self["stage"]
        out = []
        for s in dict.fromkeys(st.tolist()):
            rows = np.flatnonzero(st == s)
            if rows[0] > 0:
                rows = np.r_[rows[0] - 1, rows]
            out.append((int(s), self["stage_name"][rows[-1]], rows))
        return out

    def hold_rows(self, name="hold"):
        """Rows of the first stage called `name`, starting with the row at the start of the hold (the last
        row before it); None if no stage has that name."""
        for s, sname, rows in self.stages():
            if sname == name:
                return rows
        return None

    def hold_times(self, name="hold"):
        """(t at the start, t at the end) of the hold; SystemExit if there is no such stage."""
        rows = self.hold_rows(name)
        if rows is None:
            raise SystemExit(f"{self.path}: no stage named '{name}' (stage names: {', '.join(self.stage_names())})")
        return self["time"][rows[0]], self["time"][rows[-1]]

    def stage_names(self):
        return list(dict.fromkeys(self["stage_name"]))


def creep_summary(h, hold="hold"):
    """The numbers of creep.json: max load, depth at the end of the load (= start of the hold), at the end
    of the hold, their difference (the creep depth), the depth of the last row (residual depth)."""
    rows = h.hold_rows(hold)
    if rows is None:
        d0 = d1 = t0 = t1 = None
    else:
        d0, d1 = float(h["depth"][rows[0]]), float(h["depth"][rows[-1]])
        t0, t1 = float(h["time"][rows[0]]), float(h["time"][rows[-1]])
    return {"max_load": float(np.max(h["load"])), "depth_end_of_load": d0, "depth_end_of_hold": d1,
            "creep_depth": None if rows is None else d1 - d0, "residual_depth": float(h["depth"][-1]),
            "hold_start_time": t0, "hold_end_time": t1}


# ------------------------------------------------------------------ plotting helpers
def out_dir(a, run):
    out = Path(a.out) if a.out else Path(run)
    out.mkdir(parents=True, exist_ok=True)
    return out


def stage_color(k):
    return f"C{k % 10}"


def window_limits(F, window):
    """(x0, x1, y0, y1) of the view: the mesh's bounding box, or [-W, W] x [-W, W/20] around the tip
    clipped to the mesh (a 5 % margin)."""
    lo, hi = F.x[:, :2].min(axis=0), F.x[:, :2].max(axis=0)
    pad = 0.05 * (hi - lo)
    if window is None:
        return lo[0] - pad[0], hi[0] + pad[0], lo[1] - pad[1], hi[1] + pad[1]
    w = float(window)
    return max(-w, lo[0] - pad[0]), min(w, hi[0] + pad[0]), max(-w, lo[1] - pad[1]), min(0.05 * w, hi[1] + pad[1])


def in_window(xy, lim):
    return (xy[:, 0] >= lim[0]) & (xy[:, 0] <= lim[1]) & (xy[:, 1] >= lim[2]) & (xy[:, 1] <= lim[3])


def color_limits(values, mask, diverging, clip=1.0):
    """(vmin, vmax, cmap) from the values in the mask: the clip .. 100 - clip percentiles (robust to a few
    singular cells; clip = 0: min..max); symmetric about 0 for signed data."""
    v = values[mask] if np.any(mask) else values
    lo, hi = (float(x) for x in np.percentile(v, [clip, 100.0 - clip]))
    if diverging or (lo < 0 < hi):
        m = float(np.percentile(np.abs(v), 100.0 - clip)) or 1.0
        return -m, m, "RdBu_r"
    if lo == hi:
        lo, hi = lo - (abs(lo) or 1.0) * 1e-3, hi + (abs(hi) or 1.0) * 1e-3
    return lo, hi, "viridis"


def clip_label(clip):
    return "full range" if clip == 0 else f"colours: {clip:g}–{100 - clip:g} % percentiles of the cells in view"


def tri_map(fig, ax, F, k, values, title, lim, a, diverging=False, clim=None):
    """A map of per-cell values on the triangles (deformed at output k if --deformed)."""
    xy = F.x + (a.scale * F.u[k] if a.deformed else 0.0)
    tri = Triangulation(xy[:, 0], xy[:, 1], F.cells)
    vmin, vmax, cmap = clim if clim else color_limits(values, in_window(F.centroids, lim), diverging, a.clip)
    pc = ax.tripcolor(tri, facecolors=values, cmap=cmap, vmin=vmin, vmax=vmax, shading="flat")
    ax.set_xlim(lim[0], lim[1])
    ax.set_ylim(lim[2], lim[3])
    ax.set_aspect("equal")
    ax.set_title(title + (f" (deformed, ×{a.scale:g})" if a.deformed else ""), fontsize=9)
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("y [µm]")
    fig.colorbar(pc, ax=ax, shrink=0.85, extend="neither" if a.clip == 0 else "both").set_label(clip_label(a.clip), fontsize=7)


def shared_clim(arrays, F, lim, diverging=False, clip=1.0):
    """One colour scale for several maps, from the cells in the window."""
    mask = in_window(F.centroids, lim)
    if not np.any(mask):
        mask = np.ones_like(mask)
    v = np.concatenate([x[mask] for x in arrays])
    return color_limits(v, np.ones(v.size, bool), diverging, clip)


def stats(v, mask):
    v = v[mask] if np.any(mask) else v
    return f"min {np.min(v):.4g}, max {np.max(v):.4g}, cell mean {np.mean(v):.4g}"


def save(fig, path):
    fig.savefig(path, dpi=110)
    print(f"wrote {path}")


# ------------------------------------------------------------------ ph
def plot_ph(ax, h, label=None, color=None):
    """P-h over all stages: one line per stage (coloured by stage, or all `color` with one label)."""
    for j, (s, name, rows) in enumerate(h.stages()):
        ax.plot(h["depth"][rows], h["load"][rows], color=color or stage_color(s),
                label=(label if j == 0 else None) if color else f"stage {s}: {name}")


def creep_curve(h, hold):
    rows = h.hold_rows(hold)
    if rows is None:
        return None, None
    return h["time"][rows] - h["time"][rows[0]], h["depth"][rows] - h["depth"][rows[0]]


def cmd_ph(a):
    h = History(a.run)
    out = out_dir(a, a.run)
    for s, name, rows in h.stages():
        print(f"P-h stage {s} ({name}): {rows.size} points, t {h['time'][rows[0]]:.6g} -> {h['time'][rows[-1]]:.6g} s, "
              f"P {h['load'][rows[0]]:.6g} -> {h['load'][rows[-1]]:.6g} uN (max {h['load'][rows].max():.6g}), "
              f"h {h['depth'][rows[0]]:.6g} -> {h['depth'][rows[-1]]:.6g} um (max {h['depth'][rows].max():.6g})")
    fig = Figure(figsize=(6, 4.5))
    ax = fig.subplots()
    plot_ph(ax, h)
    ax.set_xlabel("indentation depth h [µm]")
    ax.set_ylabel("load P [µN]")
    ax.set_title(f"P-h: {Path(a.run).resolve().name}", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out / "ph.png")

    summary = creep_summary(h, a.hold_stage)
    t, dh = creep_curve(h, a.hold_stage)
    fig = Figure(figsize=(10, 4))
    ax1, ax2 = fig.subplots(1, 2)
    for s, name, rows in h.stages():
        ax1.plot(h["time"][rows], h["depth"][rows], color=stage_color(s), label=f"stage {s}: {name}")
    ax1.set_xlabel("time [s]")
    ax1.set_ylabel("depth h [µm]")
    ax1.set_title("depth vs time, all stages", fontsize=9)
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    if t is None:
        print(f"creep: no stage named '{a.hold_stage}' in {h.path} (stages: {', '.join(h.stage_names())}): "
              f"no creep curve")
        ax2.text(0.5, 0.5, f"no stage named '{a.hold_stage}'", ha="center", va="center", transform=ax2.transAxes)
    else:
        print(f"creep ({a.hold_stage}): {t.size} points over {t[-1]:.6g} s from t = {summary['hold_start_time']:.6g} s, "
              f"h {summary['depth_end_of_load']:.6g} -> {summary['depth_end_of_hold']:.6g} um, "
              f"creep depth {summary['creep_depth']:.6g} um")
        ax2.plot(t, dh, "k-")
        ax2.set_title(f"creep during '{a.hold_stage}': {summary['creep_depth']:.4g} µm", fontsize=9)
    ax2.set_xlabel("time since the start of the hold [s]")
    ax2.set_ylabel("creep depth h - h(start of hold) [µm]")
    ax2.grid(alpha=0.3)
    fig.tight_layout()
    save(fig, out / "creep.png")
    print("creep.json: " + ", ".join(f"{k} = {v:.6g}" if v is not None else f"{k} = null" for k, v in summary.items()))
    (out / "creep.json").write_text(json.dumps(summary, indent=1) + "\n")
    return 0


# ------------------------------------------------------------------ compare
def cmd_compare(a):
    labels = a.labels or [Path(r).resolve().name for r in a.runs]
    if len(labels) != len(a.runs):
        raise SystemExit(f"compare: {len(a.runs)} runs but {len(labels)} labels")
    hs = [History(r) for r in a.runs]
    out = Path(a.out) if a.out else Path(".")
    out.mkdir(parents=True, exist_ok=True)
    fig1 = Figure(figsize=(6, 4.5))
    ax1 = fig1.subplots()
    fig2 = Figure(figsize=(6, 4.5))
    ax2 = fig2.subplots()
    for k, (h, label) in enumerate(zip(hs, labels)):
        c = stage_color(k)
        plot_ph(ax1, h, label=label, color=c)
        s = creep_summary(h, a.hold_stage)
        print(f"P-h {label}: {h['depth'].size} points, max P {s['max_load']:.6g} uN, max h {h['depth'].max():.6g} um, "
              f"residual h {s['residual_depth']:.6g} um")
        t, dh = creep_curve(h, a.hold_stage)
        if t is None:
            print(f"creep {label}: no stage named '{a.hold_stage}' in {h.path}, left out")
            continue
        ax2.plot(t, dh, color=c, label=label)
        print(f"creep {label}: {t.size} points over {t[-1]:.6g} s, h(start of hold) {s['depth_end_of_load']:.6g} um, "
              f"creep depth {s['creep_depth']:.6g} um")
    ax1.set_xlabel("indentation depth h [µm]")
    ax1.set_ylabel("load P [µN]")
    ax1.legend(fontsize=8)
    ax1.grid(alpha=0.3)
    fig1.tight_layout()
    save(fig1, out / "compare_ph.png")
    ax2.set_xlabel("time since the start of the hold [s]")
    ax2.set_ylabel("creep depth h - h(start of hold) [µm]")
    if ax2.lines:
        ax2.legend(fontsize=8)
    ax2.grid(alpha=0.3)
    fig2.tight_layout()
    save(fig2, out / "compare_creep.png")
    return 0


# ------------------------------------------------------------------ fields
def probe_cell(F, probe):
    """The cell whose (undeformed) centroid is nearest to `probe` (default just beneath the tip)."""
    p = np.array(probe if probe is not None else (0.0, -1e-6 * F.extent), float)
    return int(np.argmin(np.sum((F.centroids[:, :2] - p) ** 2, axis=1))), p


def tip_region(h, a):
    """Fig. 13's region beneath the tip (x0, x1, y0, y1): --region, else |x| < a/4, -a/2 < y < 0 with a = 2.5 x the
    depth at the end of loading (docs/paper.md's region for the loading-rate scenes: a = 0.5 um at 0.19-0.22 um)."""
    if a.region:
        return tuple(a.region)
    half = 2.5 * creep_summary(History(a.run), a.hold_stage)["depth_end_of_load"]
    return (-half / 4, half / 4, -half / 2, 0.0)


def cmd_fields(a):
    h = History(a.run, need=STAGE_COLUMNS)
    t0, t1 = h.hold_times(a.hold_stage)
    out = out_dir(a, a.run)
    with Fields(a.run) as F:
        F.require_2d("fields")
        eng = ENGINEERING_SHEAR[a.evp]
        lim = window_limits(F, a.window)
        mask = in_window(F.centroids, lim)
        k0, k1 = F.nearest(t0), F.nearest(t1)
        T = F.times
        print(f"hold '{a.hold_stage}': {t0:.6g} -> {t1:.6g} s; outputs used: start {T[k0]:.6g} s (#{k0}), "
              f"end {T[k1]:.6g} s (#{k1}); window x {lim[0]:.4g}..{lim[1]:.4g}, y {lim[2]:.4g}..{lim[3]:.4g} um")
        e0, e1 = F.cell(a.evp, k0), F.cell(a.evp, k1)
        s0 = F.cell("stress", k0)
        when = {k0: "start of hold", k1: "end of hold"}

        # Fig. 9: tr(evp) and |dev evp| at the start and at the end of the hold
        fig = Figure(figsize=(11, 7), layout="constrained")
        axs = fig.subplots(2, 2)
        trs, devs = [trace(e0), trace(e1)], [dev_norm(e0, eng), dev_norm(e1, eng)]
        ctr, cdev = shared_clim(trs, F, lim, clip=a.clip), shared_clim(devs, F, lim, clip=a.clip)
        for row, k in enumerate((k0, k1)):
            tag = f"{when[k]}, t = {T[k]:.4g} s"
            tri_map(fig, axs[row, 0], F, k, trs[row], f"tr ε$^{{vp}}$ ({a.evp}), {tag}", lim, a, clim=ctr)
            tri_map(fig, axs[row, 1], F, k, devs[row], f"‖dev ε$^{{vp}}$‖, {tag}", lim, a, clim=cdev)
            print(f"fig9 tr({a.evp}) at {tag}: {stats(trs[row], mask)}")
            print(f"fig9 |dev {a.evp}| at {tag}: {stats(devs[row], mask)}")
        save(fig, out / "fig9.png")

        # Fig. 10: |evp| at the start and at the end of the hold
        fig = Figure(figsize=(11, 3.8), layout="constrained")
        axs = fig.subplots(1, 2)
        ns = [tensor_norm(e0, eng), tensor_norm(e1, eng)]
        cn = shared_clim(ns, F, lim, clip=a.clip)
        for ax, k, n in zip(axs, (k0, k1), ns):
            tag = f"{when[k]}, t = {T[k]:.4g} s"
            tri_map(fig, ax, F, k, n, f"‖ε$^{{vp}}$‖ ({a.evp}), {tag}", lim, a, clim=cn)
            print(f"fig10 |{a.evp}| at {tag}: {stats(n, mask)}")
        save(fig, out / "fig10.png")

        # Figs. 11, 12: change of |evp| and of |sigma| from the start of the hold at the hold times
        ks = []
        for th in a.hold_times:
            if th > t1 - t0 + 1e-9 * max(1.0, abs(t1)):
                print(f"hold time {th:g} s is beyond the hold ({t1 - t0:.6g} s): using the output nearest to its end")
            ks.append(F.nearest(t0 + th, t0, t1))
        n0, sn0 = ns[0], tensor_norm(s0, False)
        for fname, label, plain, series in (
                ("fig11", f"Δ‖ε$^{{vp}}$‖ ({a.evp})", f"change of |{a.evp}|",
                 [tensor_norm(F.cell(a.evp, k), eng) - n0 for k in ks]),
                ("fig12", "Δ‖σ‖ [MPa]", "change of |sigma| [MPa]",
                 [tensor_norm(F.cell("stress", k), False) - sn0 for k in ks])):
            fig = Figure(figsize=(5.5 * len(ks), 3.8), layout="constrained")
            axs = np.atleast_1d(fig.subplots(1, len(ks)))
            c = shared_clim(series, F, lim, diverging=True, clip=a.clip)
            for ax, k, th, v in zip(axs, ks, a.hold_times, series):
                tag = f"hold time {T[k] - T[k0]:.4g} s (asked {th:g} s)"
                tri_map(fig, ax, F, k, v, tag, lim, a, clim=c)
                print(f"{fname} {plain} since the start of the hold at {tag}: {stats(v, mask)}")
            fig.suptitle(f"{label} since the start of the hold (t = {T[k0]:.4g} s)", fontsize=10)
            save(fig, out / f"{fname}.png")

        # Fig. 13: change of |sigma| beneath the tip vs time during the hold: a region mean (or one cell, --probe)
        idx = np.flatnonzero((T >= T[k0]) & (T <= T[k1]))
        if a.probe is not None:
            c, p = probe_cell(F, a.probe)
            sig = tensor_norm(F.cell_history("stress", c)[idx], False)
            where = f"cell {c} (centroid {F.centroids[c, 0]:.3g}, {F.centroids[c, 1]:.3g} µm)"
        else:
            box = tip_region(h, a)
            w = clipped_areas(F, box)
            sig = np.array([region_mean(tensor_norm(F.cell("stress", k), False), w) for k in idx])
            where = f"mean over |x| < {box[1]:.3g}, {box[2]:.3g} < y < 0 µm ({np.count_nonzero(w)} cells clipped to it)"
        dt, ds = T[idx] - T[k0], sig - sig[0]
        print(f"fig13 {where}: |sigma| {sig[0]:.6g} -> {sig[-1]:.6g} MPa, change {ds[-1]:.6g} MPa (min {ds.min():.6g}, "
              f"max {ds.max():.6g}) over {dt[-1]:.6g} s, {idx.size} outputs")
        fig = Figure(figsize=(6, 4))
        ax = fig.subplots()
        ax.plot(dt, ds, "k.-", ms=3)
        ax.set_xlabel("time since the start of the hold [s]")
        ax.set_ylabel("Δ‖σ‖ [MPa]")
        ax.set_title(f"beneath the tip: {where}", fontsize=8)
        ax.grid(alpha=0.3)
        fig.tight_layout()
        save(fig, out / "fig13.png")
    return 0


# ------------------------------------------------------------------ vectors
def thin(xy, lim, nmax):
    """At most about nmax of the points, one per cell of a regular grid over the window."""
    if xy.shape[0] <= nmax:
        return np.arange(xy.shape[0])
    nb = max(1, int(np.sqrt(nmax)))
    ix = np.clip(((xy[:, 0] - lim[0]) / (lim[1] - lim[0]) * nb).astype(int), 0, nb - 1)
    iy = np.clip(((xy[:, 1] - lim[2]) / (lim[3] - lim[2]) * nb).astype(int), 0, nb - 1)
    _, first = np.unique(ix * nb + iy, return_index=True)
    return np.sort(first)


def cmd_vectors(a):
    h = History(a.run, need=STAGE_COLUMNS)
    t0, t1 = h.hold_times(a.hold_stage)
    out = out_dir(a, a.run)
    with Fields(a.run) as F:
        F.require_2d("vectors")
        k0, k1 = F.nearest(t0), F.nearest(t1)
        u0, u1 = F.u[k0], F.u[k1]
        du = u1 - u0
        lim = window_limits(F, a.window)
        xy = F.x + (a.scale * u0 if a.deformed else 0.0)
        sel = np.flatnonzero(in_window(xy, lim))
        sel = sel[thin(xy[sel], lim, a.max_arrows)]
        mag = np.hypot(du[:, 0], du[:, 1])
        j = sel[np.argmax(mag[sel])] if sel.size else int(np.argmax(mag))
        mean = du[sel].mean(axis=0) if sel.size else np.zeros(2)
        print(f"vectors: u(t = {F.times[k1]:.6g} s) - u(t = {F.times[k0]:.6g} s) at {sel.size} vertices in the window; "
              f"max |du| {mag[j]:.6g} um at ({F.x[j, 0]:.4g}, {F.x[j, 1]:.4g}) um, "
              f"du = ({du[j, 0]:.4g}, {du[j, 1]:.4g}); mean du in the window ({mean[0]:.4g}, {mean[1]:.4g}) um")
        fig = Figure(figsize=(8, 5), layout="constrained")
        ax = fig.subplots()
        ref = float(mag[sel].max()) if sel.size else 0.0
        q = ax.quiver(xy[sel, 0], xy[sel, 1], du[sel, 0], du[sel, 1], mag[sel], cmap="viridis", angles="xy",
                      pivot="tail", scale=None if ref > 0 else 1.0)
        ref = ref if ref > 0 else 1.0
        ax.quiverkey(q, 0.8, -0.16, ref, f"{ref:.3g} µm", labelpos="E", coordinates="axes")
        fig.colorbar(q, ax=ax, shrink=0.7, label="|Δu| [µm]")
        ax.set_xlim(lim[0], lim[1])
        ax.set_ylim(lim[2], lim[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x [µm]")
        ax.set_ylabel("y [µm]")
        ax.set_title(f"displacement increment during the hold ({F.times[k1] - F.times[k0]:.4g} s)", fontsize=9)
        save(fig, out / "vectors.png")
    return 0


# ------------------------------------------------------------------ profile
def cmd_profile(a):
    out = out_dir(a, a.run)
    with Fields(a.run) as F:
        k = F.times.size - 1 if a.time is None else F.nearest(a.time)
        d = F.dim
        tol = 1e-6 * F.extent
        top = np.flatnonzero(np.abs(F.x[:, d - 1]) <= tol)
        axis = "xyz"[d - 1]
        if top.size < d:
            rng = (F.x[:, d - 1].min(), F.x[:, d - 1].max())
            raise SystemExit(f"{F.h5path}: {top.size} vertices on the top surface {axis} = 0 ({axis} spans "
                             f"{rng[0]:.4g}..{rng[1]:.4g}); the profile needs the top at {axis} = 0")
        uv = F.u[k][top, d - 1]
        j = int(np.argmin(uv))
        print(f"profile at t = {F.times[k]:.6g} s (output #{k}): {top.size} vertices on {axis} = 0, vertical "
              f"displacement min {uv.min():.6g} um at ({', '.join(f'{c:.4g}' for c in F.x[top[j], :d - 1])}), "
              f"max {uv.max():.6g} um")
        if d == 2:
            o = np.argsort(F.x[top, 0])
            fig = Figure(figsize=(7, 4))
            ax = fig.subplots()
            ax.plot(F.x[top[o], 0], uv[o], "k.-", ms=3)
            ax.set_xlabel("x [µm]")
            ax.set_ylabel("vertical displacement u$_y$ of the surface [µm]")
            ax.axhline(0.0, color="0.6", lw=0.8)
        else:
            xy = F.x[top, :2]
            fig = Figure(figsize=(11, 4.5))
            ax, ax2 = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.2, 1]})
            cs = ax.tricontourf(Triangulation(xy[:, 0], xy[:, 1]), uv, levels=20, cmap="viridis")
            fig.colorbar(cs, ax=ax, label="u$_z$ [µm]")
            ax.set_aspect("equal")
            ax.set_xlabel("x [µm]")
            ax.set_ylabel("y [µm]")
            r = np.hypot(xy[:, 0], xy[:, 1])
            ax2.plot(r, uv, "k.", ms=3)
            ax2.set_xlabel("distance from the indenter axis [µm]")
            ax2.set_ylabel("u$_z$ [µm]")
            ax2.grid(alpha=0.3)
        ax.set_title(f"surface profile at t = {F.times[k]:.4g} s", fontsize=9)
        fig.tight_layout()
        save(fig, out / "profile.png")
    return 0


# ------------------------------------------------------------------ command line
def parser():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], epilog="Without a subcommand: ph.",
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)

    def common(p, hold=True):
        p.add_argument("--out", help="output directory (default: the run directory)")
        if hold:
            p.add_argument("--hold-stage", default="hold", help="name of the creep stage (default: hold)")

    p = sub.add_parser("ph", help="P-h curve, depth vs time, creep depth (ph.png, creep.png, creep.json)")
    p.add_argument("run")
    common(p)
    p = sub.add_parser("compare", help="several runs: compare_ph.png, compare_creep.png")
    p.add_argument("runs", nargs="+")
    p.add_argument("--labels", nargs="+", help="one label per run (default: the directory names)")
    p.add_argument("--out", help="output directory (default: the current directory)")
    p.add_argument("--hold-stage", default="hold", help="name of the creep stage (default: hold)")

    def view(p):
        p.add_argument("--window", type=float, help="half-width [um] of the view around the tip (default: the whole mesh)")
        p.add_argument("--deformed", action="store_true", help="draw on the deformed mesh (default: undeformed)")
        p.add_argument("--scale", type=float, default=1.0, help="displacement scale with --deformed (default 1)")

    p = sub.add_parser("fields", help="2D maps of evp and stress (fig9.png ... fig13.png)")
    p.add_argument("run")
    common(p)
    view(p)
    p.add_argument("--hold-times", type=float, nargs="+", default=[100.0, 500.0, 2000.0],
                   help="times since the start of the hold for figs 11, 12 (default 100 500 2000 s)")
    p.add_argument("--evp", choices=("evp", "evp_soft", "evp_hard"), default="evp",
                   help="viscoplastic strain field (default evp, the mixture's)")
    p.add_argument("--clip", type=float, default=1.0,
                   help="colour scales span the CLIP .. 100-CLIP percentiles of the cells in view (default 1; 0: min..max)")
    p.add_argument("--region", type=float, nargs=4, metavar=("X0", "X1", "Y0", "Y1"),
                   help="fig13: the region whose mean of |sigma| is followed (default |x| < a/4, -a/2 < y < 0, a = 2.5 h)")
    p.add_argument("--probe", type=float, nargs=2, metavar=("X", "Y"),
                   help="fig13: follow the one cell whose centroid is nearest to (X, Y) instead of the region mean")
    p = sub.add_parser("vectors", help="2D displacement increments during the hold (vectors.png)")
    p.add_argument("run")
    common(p)
    view(p)
    p.add_argument("--max-arrows", type=int, default=900, help="at most about this many arrows (default 900)")
    p = sub.add_parser("profile", help="surface profile at the last output (profile.png)")
    p.add_argument("run")
    common(p, hold=False)
    p.add_argument("--time", type=float, help="use the output nearest to this time (default: the last output)")
    return ap


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] not in SUBCOMMANDS and argv[0] not in ("-h", "--help"):
        argv.insert(0, "ph")
    a = parser().parse_args(argv)
    return {"ph": cmd_ph, "compare": cmd_compare, "fields": cmd_fields, "vectors": cmd_vectors,
            "profile": cmd_profile}[a.cmd](a)

