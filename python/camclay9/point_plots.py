"""Plots of one material-point run of the Cam-Clay IX driver.

    python3 post/point_plots.py RUN_DIR [--out DIR]

RUN_DIR holds `history.csv` (one row per converged step, columns HISTORY_COLUMNS) and `scene.json`
(name, props[23], normal, units, segments). Written to DIR (default RUN_DIR):

  stress_path.png     p-q of the overall stress and of each frame with a non-zero fraction: the soft
                      frame in p-q with its yield ellipse at the first and last pc, the hard frame in
                      the fictitious p'-q' (sigma' = P:sigma, theory.md §1.2) with its ellipse
  stress_strain.png   q vs axial strain of the loading axis, p vs volumetric strain
  creep_<name>.png    for every segment with "creep": true: axial creep strain with its Lomnitz fit,
                      and each frame's axial viscoplastic strain on a log time axis (Y21 Fig. 18)
  creep_fit.json      {segment name: {"B", "tau", "axis", "points"}} (B, tau null if the fit failed)

Conventions (theory.md §1.1): stresses and strains are tension positive, p = -tr(sigma)/3 and
q = sqrt(3/2 s:s). Strains on the plots are shown compression positive (-eps), like p.
Strain columns use engineering shear; only normal components are used here.
"""
import argparse
import json
import re
from pathlib import Path

import camclay9
import numpy as np
from matplotlib.figure import Figure   # no pyplot: figures are saved with Agg, no global state

from camclay9.lomnitz import lomnitz, lomnitz_fit

VOIGT = ("11", "22", "33", "12", "13", "23")
_TENSORS = ("eps", "sig", "sig_hard", "sig_soft", "evp_hard", "evp_soft", "evp")
HISTORY_COLUMNS = (("time", "stage", "step", "dt", "newton_its", "local_its", "cutbacks")
                   + tuple(f"{name}_{c}" for name in _TENSORS for c in VOIGT)
                   + ("pc_hard", "pc_soft", "flags"))
AXIS_LABEL = ("11", "22", "33")


# ------------------------------------------------------------------ reading and checking the run
def read_history(path):
    """history.csv -> dict column name -> 1-D float array, stage_name as text (camclay9.read_history). ValueError
    names the file on any defect."""
    h = camclay9.read_history(path, need=HISTORY_COLUMNS)
    if h.size == 0:
        raise ValueError(f"{path}: no data rows after the header")
    return {name: h[name] if h[name].dtype.kind == "U" else h[name].astype(float) for name in h.dtype.names}


def read_scene(path):
    """scene.json -> dict, with the defaults filled in (segment axis 2, normal from props 21-23)."""
    path = Path(path)
    with open(path) as fh:
        scene = json.load(fh)
    for key in ("props", "segments"):
        if key not in scene:
            raise ValueError(f"{path}: missing key '{key}'")
    if len(scene["props"]) < 19:
        raise ValueError(f"{path}: 'props' has {len(scene['props'])} values, need 23")
    normal = np.asarray(scene.get("normal", scene["props"][20:23] or [0, 0, 1]), float)
    if normal.shape != (3,) or not np.linalg.norm(normal) > 0:
        raise ValueError(f"{path}: 'normal' must be 3 numbers, not all zero")
    scene["normal"] = normal / np.linalg.norm(normal)
    for k, seg in enumerate(scene["segments"]):
        for key in ("name", "t_start", "t_end", "creep"):
            if key not in seg:
                raise ValueError(f"{path}: segment {k} has no '{key}'")
        seg.setdefault("axis", 2)
        if seg["axis"] not in (0, 1, 2):
            raise ValueError(f"{path}: segment {k} ('{seg['name']}') has axis {seg['axis']}, need 0, 1 or 2")
    scene.setdefault("name", path.parent.name)
    return scene


# ------------------------------------------------------------------ mechanics of the plotted quantities
def stress_tensors(hist, prefix):
    """(N, 3, 3) tensors from the six columns prefix_11 ... prefix_23 (tensor shear components)."""
    T = np.empty((len(hist["time"]), 3, 3))
    for c, (i, j) in zip(VOIGT, ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))):
        T[:, i, j] = T[:, j, i] = hist[f"{prefix}_{c}"]
    return T


def project(sig, c, n):
    """Fictitious stress sigma' = c1 sig + c2 (n.sig.n) n(x)n + (c3/2)[n(x)(sig n) + (sig n)(x)n] (§1.2)."""
    c1, c2, c3 = c
    sn = sig @ n                                           # (N, 3)
    nsn = sn @ n                                           # (N,)
    nn = np.outer(n, n)
    ns = n[None, :, None] * sn[:, None, :]                 # n (x) (sig n)
    return c1 * sig + c2 * nsn[:, None, None] * nn + 0.5 * c3 * (ns + ns.transpose(0, 2, 1))


def p_q(sig):
    """p = -tr(sig)/3 (compression positive) and q = sqrt(3/2 s:s) for (N, 3, 3) stresses."""
    p = -np.trace(sig, axis1=1, axis2=2) / 3.0
    s = sig + p[:, None, None] * np.eye(3)
    return p, np.sqrt(1.5 * np.einsum("kij,kij->k", s, s))


def ellipse(pc, M, npts=200):
    """Yield surface f = q^2/M^2 + p(p - pc) = 0 as (p, q): q = M sqrt(p (pc - p)), 0 <= p <= pc."""
    p = np.linspace(0.0, pc, npts)
    return p, M * np.sqrt(np.clip(p * (pc - p), 0.0, None))


def frames(scene):
    """The frames with a non-zero volume fraction: (key, title, M, projection constants or None)."""
    props, phi = scene["props"], scene["props"][0]
    out = []
    if phi > 0:
        out.append(("hard", "hard frame (fictitious stress)", props[6], tuple(props[8:11])))
    if phi < 1:
        out.append(("soft", "soft frame", props[15], None))
    return out


def loading_axis(scene):
    """Axis of the first creep segment, else of the first segment, else 2."""
    segs = scene["segments"]
    for seg in segs:
        if seg["creep"]:
            return seg["axis"]
    return segs[0]["axis"] if segs else 2


def segment_rows(hist, k, t_start):
    """(base row, rows of segment k). The base row is the state at the segment start: the segment's
    last row with time <= t_start (a driver that writes the state right after a load jump), else the
    row just before the segment. Returns (None, rows) for a segment without rows."""
    rows = np.flatnonzero(hist["stage"] == k)
    if rows.size == 0:
        return None, rows
    at_start = rows[hist["time"][rows] <= t_start + 1e-12 * max(1.0, abs(t_start))]
    if at_start.size:
        return at_start[-1], rows
    return max(rows[0] - 1, 0), rows


# ------------------------------------------------------------------ the plots
def _mark_ends(ax, x, y, color):
    ax.plot(x[0], y[0], "o", color=color, mfc="none")
    ax.plot(x[-1], y[-1], "s", color=color)


def plot_stress_path(hist, scene, out):
    """stress_path.png: overall p-q, then one panel per frame with its first/last yield ellipse."""
    frs = frames(scene)
    fig = Figure(figsize=(5.0 * (1 + len(frs)), 4.5), layout="constrained")
    axes = fig.subplots(1, 1 + len(frs), squeeze=False)[0]
    p, q = p_q(stress_tensors(hist, "sig"))
    axes[0].plot(p, q, ".-", color="k")
    _mark_ends(axes[0], p, q, "k")
    axes[0].set(title="overall stress", xlabel="p (MPa)", ylabel="q (MPa)")
    for ax, (key, title, M, c) in zip(axes[1:], frs):
        sig = stress_tensors(hist, f"sig_{key}")
        if c is not None:
            sig = project(sig, c, scene["normal"])
        fp, fq = p_q(sig)
        prime = "'" if c is not None else ""
        for row, style, when in ((0, "--", "first"), (-1, "-", "last")):
            pc = hist[f"pc_{key}"][row]
            ax.plot(*ellipse(pc, M), style, color="0.5", label=f"yield surface, {when} pc = {pc:.3g} MPa")
        ax.plot(fp, fq, ".-", color="C0" if key == "hard" else "C3", label=f"{key} frame path")
        _mark_ends(ax, fp, fq, "C0" if key == "hard" else "C3")
        ax.set(title=title, xlabel=f"p{prime} (MPa)", ylabel=f"q{prime} (MPa)")
        ax.legend(fontsize=8)
    for ax in axes:
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    fig.suptitle(f"{scene['name']}: stress paths (o first row, \u25a0 last row)")
    fig.savefig(Path(out) / "stress_path.png", dpi=110)


def plot_stress_strain(hist, scene, out):
    """stress_strain.png: q vs -eps_axis, p vs -eps_v, coloured by segment."""
    axis = loading_axis(scene)
    p, q = p_q(stress_tensors(hist, "sig"))
    ea = -hist[f"eps_{AXIS_LABEL[axis]}"]
    ev = -(hist["eps_11"] + hist["eps_22"] + hist["eps_33"])
    fig = Figure(figsize=(10.0, 4.5), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    ax1.plot(ea, q, color="0.7", lw=0.8)
    ax2.plot(ev, p, color="0.7", lw=0.8)
    for k, seg in enumerate(scene["segments"]):
        rows = hist["stage"] == k
        if rows.any():
            ax1.plot(ea[rows], q[rows], ".", ms=4, label=seg["name"])
            ax2.plot(ev[rows], p[rows], ".", ms=4, label=seg["name"])
    ax1.set(xlabel=f"axial strain $-\\varepsilon_{{{AXIS_LABEL[axis]}}}$ (compression +)", ylabel="q (MPa)")
    ax2.set(xlabel="volumetric strain $-(\\varepsilon_{11}+\\varepsilon_{22}+\\varepsilon_{33})$ (compression +)",
            ylabel="p (MPa)")
    for ax in (ax1, ax2):
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-2, 3))
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{scene['name']}: stress-strain")
    fig.savefig(Path(out) / "stress_strain.png", dpi=110)


def creep_curve(hist, scene, k):
    """Creep data of segment k: (t since segment start, |axial strain increment|, base row, rows)."""
    seg = scene["segments"][k]
    base, rows = segment_rows(hist, k, seg["t_start"])
    if base is None:
        return None
    rows = np.union1d([base], rows)
    col = f"eps_{AXIS_LABEL[seg['axis']]}"
    return hist["time"][rows] - seg["t_start"], np.abs(hist[col][rows] - hist[col][base]), base, rows


def plot_creep(hist, scene, k, out):
    """creep_<name>.png for creep segment k; returns the fit record {"B", "tau", "axis", "points"}."""
    seg = scene["segments"][k]
    name, axis = seg["name"], seg["axis"]
    curve = creep_curve(hist, scene, k)
    if curve is None:
        print(f"creep {name}: no rows in history.csv, skipped")
        return {"B": None, "tau": None, "axis": axis, "points": 0, "error": "no rows"}
    t, creep, base, rows = curve
    record = {"B": None, "tau": None, "axis": axis, "points": int(t.size)}
    try:
        record["B"], record["tau"] = lomnitz_fit(t, creep)
        print(f"creep {name}: B = {record['B']:.4e}, tau = {record['tau']:.4g} s")
    except (ValueError, RuntimeError) as err:
        record["error"] = str(err)
        print(f"creep {name}: Lomnitz fit failed: {err}")

    fig = Figure(figsize=(10.0, 4.5), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    comp = AXIS_LABEL[axis]
    ax1.plot(t, creep, "o", ms=3, color="k", label="model")
    if record["B"] is not None:
        tt = np.linspace(0.0, t.max(), 400)
        ax1.plot(tt, lomnitz(tt, record["B"], record["tau"]), "-", color="C1",
                 label=f"Lomnitz B ln(1 + t/\u03c4): B = {record['B']:.3e}, \u03c4 = {record['tau']:.3g} s")
    ax1.set(xlabel="time since segment start (s)", ylabel=f"axial creep strain |\u0394\u03b5$_{{{comp}}}$|",
            title="creep strain")
    ax1.ticklabel_format(axis="y", style="sci", scilimits=(0, 0))
    pos = t > 0                                            # log time axis: t = 0 is left out
    positive = bool(pos.any())
    for key, _, _, _ in frames(scene):
        evp = hist[f"evp_{key}_{comp}"]
        d = np.abs(evp[rows] - evp[base])[pos]
        positive &= bool(np.all(d > 0))
        ax2.plot(t[pos], d, ".-", color="C0" if key == "hard" else "C3", label=f"{key} frame")
    ax2.set_xscale("log")
    if positive:                                           # log strain axis shows soft >> hard
        ax2.set_yscale("log")
    ax2.set(xlabel="time since segment start (s)",
            ylabel=f"viscoplastic strain |\u0394\u03b5$^{{vp}}_{{{comp}}}$|", title="per frame (cf. Y21 Fig. 18)")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle(f"{scene['name']}: creep segment '{name}'")
    fig.savefig(Path(out) / f"creep_{_safe(name)}.png", dpi=110)
    return record


def _safe(name):
    """Segment name usable in a file name."""
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", str(name)) or "segment"


def make_plots(run_dir, out=None):
    """All plots of RUN_DIR into out (default RUN_DIR); returns {creep segment name: fit record}."""
    run_dir = Path(run_dir)
    out = Path(out) if out is not None else run_dir
    out.mkdir(parents=True, exist_ok=True)
    hist = read_history(run_dir / "history.csv")
    scene = read_scene(run_dir / "scene.json")
    nseg = len(scene["segments"])
    bad = np.unique(hist["stage"][(hist["stage"] < 0) | (hist["stage"] >= nseg)])
    if bad.size:
        raise ValueError(f"{run_dir / 'history.csv'}: column 'stage' (the segment's index) has {bad.tolist()}, "
                         f"not in scene.json ({nseg} segments)")
    plot_stress_path(hist, scene, out)
    plot_stress_strain(hist, scene, out)
    fits = {seg["name"]: plot_creep(hist, scene, k, out)
            for k, seg in enumerate(scene["segments"]) if seg["creep"]}
    with open(out / "creep_fit.json", "w") as fh:
        json.dump(fits, fh, indent=2)
    return fits


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", help="directory with history.csv and scene.json")
    parser.add_argument("--out", help="output directory (default: RUN_DIR)")
    args = parser.parse_args(argv)
    try:
        make_plots(args.run_dir, args.out)
    except (OSError, ValueError) as err:
        parser.exit(2, f"point_plots.py: error: {err}\n")
    return 0

