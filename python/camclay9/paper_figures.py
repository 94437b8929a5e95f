"""The figures of docs/paper.md, drawn from the runs of tools/reproduce.py into DIR/figures.

P-h and creep curves come from post/indent_plots.py and post/triaxial_plots.py (their output is logged to
DIR/figures/plots.log); the 2D fields (Figs. 9-13, 15: nodal averages, one colour scale across the loading rates,
region probes) from camclay9.paper_fields; Fig. 17 (both theta with the paper's fits under both readings of eq.
28's log) and Fig. 18's soft/hard ratio are drawn here. draw_all returns {figure id: [(png path, caption)]}.
"""
import contextlib
import shutil
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from camclay9 import indent_plots, paper_fields, read_summary, triaxial_plots
from camclay9.lomnitz import lomnitz
from camclay9.paper_numbers import (ALPHAS, PAPER_LOMNITZ, SOFT_OVER_HARD, THETAS_BEDDING, THETAS_TRIAXIAL,
                           triaxial_series)

DPI = 90


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    return path


def _plot(log, argv, main=indent_plots.main):
    """Run a plot script's main(argv), its printout into the log; False if the run is missing or fails."""
    with contextlib.redirect_stdout(log):
        print("$ " + " ".join(str(a) for a in argv))
        try:
            return main([str(a) for a in argv]) == 0
        except SystemExit as e:
            print(f"skipped: {e}")
            return False


def _fields(log, draw, *args):
    """A figure of camclay9.paper_fields; its failure (a missing output) is logged, not raised."""
    try:
        return draw(*args)
    except SystemExit as e:
        print(f"skipped {draw.__name__}: {e}", file=log)
        return {} if draw is paper_fields.draw_loading_rate else None


def _copy(src, dest):
    if Path(src).is_file():
        shutil.copyfile(src, dest)
        return dest
    return None


def fig17(out, figs):
    fig = Figure(figsize=(10, 4))
    ax1, ax2 = fig.subplots(1, 2)
    drawn = False
    for k, th in enumerate(THETAS_TRIAXIAL):
        run = out / f"triaxial_theta{th}"
        if not (run / "history.csv").is_file():
            continue
        t, eps, _, _ = triaxial_series(run)
        B, tau = PAPER_LOMNITZ[th]
        for ax in (ax1, ax2):
            ax.plot(t[1:] / 3600, eps[1:], "-", color=f"C{k}", label=f"ours, θ = {th}")
            ax.plot(t[1:] / 3600, lomnitz(t[1:], B, tau), "--", color=f"C{k}",
                    label=f"paper's fit θ = {th} (B = {B:.3g}, τ = {tau:g} s), eq. 28 with ln")
            ax.plot(t[1:] / 3600, lomnitz(t[1:], B, tau) / np.log(10.0), ":", color=f"C{k}",
                    label="the same fit with log10")
        drawn = True
    if not drawn:
        return None
    ax2.set_xscale("log")
    ax2.set_xlim(left=1.0 / 3600)
    for ax in (ax1, ax2):
        ax.set_xlabel("time after σd [h]")
        ax.set_ylabel("axial creep strain (compression +)")
        ax.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    ax1.set_title("cf. Fig. 17 (linear time); eq. 28's log read as ln and as log10", fontsize=9)
    ax2.set_title("the same, log time", fontsize=9)
    return _save(fig, figs / "fig17_creep.png")


def fig18_ratio(out, figs):
    fig = Figure(figsize=(6, 4))
    ax = fig.subplots()
    drawn = False
    for k, th in enumerate(THETAS_TRIAXIAL):
        run = out / f"triaxial_theta{th}"
        if not (run / "history.csv").is_file():
            continue
        t, _, soft, hard = triaxial_series(run)
        pos = t > 0
        ax.loglog(t[pos], soft[pos] / np.maximum(hard[pos], 1e-300), color=f"C{k}", label=f"θ = {th}")
        drawn = True
    if not drawn:
        return None
    ax.axhline(SOFT_OVER_HARD, color="k", ls="--", lw=0.8, label="paper: > 10 over the whole test")
    ax.set_xlabel("time after σd [s]")
    ax.set_ylabel("soft / hard mean axial creep")
    ax.set_title("cf. Fig. 18: ratio of the frames' creep", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    return _save(fig, figs / "fig18_ratio.png")


def _adapted(run):
    """Whether the run in this folder was made on adapted meshes (its summary.json, which every run writes beside the
    history its profile is drawn from, states a mesh error)."""
    return read_summary(run)["mesh_error"] is not None


def draw_all(out, numbers=None):
    out = Path(out)
    figs = out / "figures"
    figs.mkdir(exist_ok=True)
    images = {}

    def add(fid, path, caption):
        if path:
            images.setdefault(fid, []).append((Path(path), caption))

    with open(figs / "plots.log", "w", encoding="utf-8") as log:
        for key, fid in (("nanoindent_kerogen", "fig3"), ("microindent_BN", "fig4a"), ("microindent_BP", "fig4b")):
            if _plot(log, ["ph", out / key, "--out", out / key]):
                add(fid, _copy(out / key / "ph.png", figs / f"{fid}_ph.png"), f"P–h, {key}")
        if _plot(log, ["profile", out / "microindent_BN", "--out", out / "microindent_BN"]):
            add("fig5", _copy(out / "microindent_BN" / "profile.png", figs / "fig5_profile.png"),
                "residual surface profile after unloading, microindent_BN (" + (
                    "on meshes adapted to the answer: the run of the table above, with the mesh error it states"
                    if _adapted(out / "microindent_BN") else
                    "one mesh: a lower bound, its residual depth below the converged one") + "; § Nano- and microindentation)")
        runs = [out / f"loading_rate_a{a}" for a in ALPHAS]
        if _plot(log, ["compare", *runs, "--labels", *[f"α = {a}" for a in ALPHAS], "--out", figs / "lr"]):
            add("fig7", _copy(figs / "lr" / "compare_ph.png", figs / "fig7_ph.png"), "P–h for α = 0.1, 1, 10")
            add("fig8", _copy(figs / "lr" / "compare_creep.png", figs / "fig8_creep.png"), "creep depth vs hold time")
        for fid, items in _fields(log, paper_fields.draw_loading_rate, runs, [f"α = {a}" for a in ALPHAS], figs).items():
            for path, caption in items:
                add(fid, path, caption)
        runs = [out / f"bedding_theta{t}" for t in THETAS_BEDDING]
        if _plot(log, ["compare", *runs, "--labels", *[f"θ = {t}" for t in THETAS_BEDDING], "--out", figs / "bed"]):
            add("fig14", _copy(figs / "bed" / "compare_creep.png", figs / "fig14_creep.png"), "creep depth vs hold time")
        if (out / "bedding_theta45" / "fields.h5").is_file():
            add("fig15", _fields(log, paper_fields.fig15, out / "bedding_theta45", 45, paper_fields.A_BED,
                                 figs / "fig15_vectors.png"),
                "displacement increments during the hold, θ = 45, the bedding planes and the measured flow axis drawn")
        add("fig17", fig17(out, figs), "axial creep strain after σd, both θ, with the paper's Lomnitz fits")
        for th in THETAS_TRIAXIAL:
            run = out / f"triaxial_theta{th}"
            if _plot(log, [run, "--theta", th], main=triaxial_plots.main):
                add("fig18", _copy(run / "frames.png", figs / f"fig18_frames_theta{th}.png"),
                    f"per-frame axial viscoplastic strain, θ = {th}")
        add("fig18", fig18_ratio(out, figs), "soft/hard ratio of the mean axial creep")
    return images
