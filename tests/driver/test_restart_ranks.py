"""Restarts on another number of ranks (issue 23): a run checkpointed on 1 rank continues on 2, and one
checkpointed on 2 continues on 1, with the same history as the uninterrupted run.

The checkpoint's shared file (checkpoint.STEP.h5) holds the displacement, the predictor's increment, every
quadrature point's state, the contact multipliers and the active set in the serial mesh's order, so each rank of
the new partition reads exactly what was written for its points; from there the run is one on the new number of
ranks. Reference [self]: the uninterrupted run on 1 rank (1 and 2 ranks agree to round-off on these scenes:
fixed steps, full Newton convergence). Asserted: the same steps, stages, Newton iterations and cutbacks (and
active contact nodes), every other history column within 1e-10 of its quantity's largest value, and the
fields continued in the same fields.h5 (its times, the last stress field within 1e-10); and the checkpoint the
restarted run writes after its first step (step 6) against the uninterrupted run's, every dataset within 1e-10
(measured 7e-14): it holds the multipliers' increment over that step, which sees the restored multipliers.

Two scenes: a heterogeneous Cam-Clay IX box on P2 (phi field, bedding at 30 degrees: edges carry unknowns, every
point a different state) under an instant axial load held in creep, then a lateral ramp; an axisymmetric
Cam-Clay IX (kerogen) cone indentation, load, hold and unload. Both restart mid-stage (step 5).
"""
import shutil
from pathlib import Path

import h5py
import numpy as np
from camclay9 import read_history, run_driver
import pytest

ROOT = Path(__file__).resolve().parents[2]
MESHES = ROOT / "meshes"
TOL = 1e-10

BOX = f"""scene: fe
mesh: {{geometry: {MESHES}/box.geo, parameters: {{Lx: 1, Ly: 1, Lz: 2, size: 0.5}}, order: 2}}
material: {{props: woodford, set: {{phi: 0.5}}, bedding_angle: 30}}
phi: {{mean: 0.5, std: 0.05, min: 0.4, max: 0.6, seed: 7}}
initial: {{stress: [-35, -35, -35, 0, 0, 0], pressure: {{x1: 35, y1: 35, z1: 35}}}}
boundary:
  fixed: [{{group: x0, components: [x]}}, {{group: y0, components: [y]}}, {{group: z0, components: [z]}}]
  pressure: [x1, y1, z1]
stages:
  - {{name: creep, duration: 3600, load: instant, pressure: {{z1: 75}}, steps: {{count: 8, spacing: geometric, ratio: 1.6}}}}
  - {{name: more, duration: 3600, pressure: {{x1: 40}}, steps: {{count: 4}}}}
output: {{fields_every: 3}}
"""

CONE = f"""scene: fe
mesh:
  geometry: {MESHES}/indent_block2d.geo
  parameters: {{W: 2, H: 2, half: 1, h_tip: 0.08, h_far: 0.3, r_fine: 0.4, r_contact: 0.9}}
  kinematics: axisymmetric
material: {{props: woodford, set: {{phi: 0}}}}
boundary:
  fixed: [{{group: bottom, components: [x, y]}}, {{group: left, components: [x]}}, {{group: right, components: [x]}}]
indenter: {{shape: cone, half_angle: 70.3, contact: contact}}
stages:
  - {{name: load, duration: 10, indenter: {{load: 150}}, steps: {{count: 6}}}}
  - {{name: hold, duration: 20, indenter: {{load: hold}}, steps: {{count: 6, spacing: geometric, ratio: 1.3}}}}
  - {{name: unload, duration: 5, indenter: {{load: 0}}, steps: {{count: 3}}}}
output: {{fields_every: 3}}
"""

EXACT = ("stage", "step", "newton_its", "cutbacks", "active_nodes", "active_changes")   # the same decisions
SKIP = ("wall", "umat_calls", "stage_name", "max_penetration")   # timing, rank 0's count, round-off around 0


def run(text, out, ranks=1, args=()):
    scene = out.parent / (out.name + ".yaml")
    scene.write_text(text)
    return run_driver(scene, out, args, root=ROOT, ranks=ranks, cwd=out.parent, timeout=600)  # DriverError: failed


def history(out):
    return read_history(out)


def worst_difference(a, b):
    """The largest difference of b from a over the columns that are not decisions, relative to the largest
    value of its quantity (eps_*, sig_*, reaction_*, evp33_*: one scale per group of components)."""
    cols = [c for c in a.dtype.names if c not in EXACT + SKIP and a[c].dtype.kind in "fi"]
    scale = {}
    for c in cols:
        g = c.split("_")[0]
        scale[g] = max(scale.get(g, 1e-300), float(np.max(np.abs(a[c]))))
    return max((float(np.max(np.abs(a[c] - b[c]))) / scale[c.split("_")[0]], c) for c in cols)


def last_stress(out):
    with h5py.File(out / "fields.h5") as f:
        keys = sorted(f["/fields/stress"])
        return f["/time"][:, 0], f[f"/fields/stress/{keys[-1]}"][()]


def checkpoint_difference(a, b):
    """The largest difference between two shared checkpoint files over every dataset but the UMAT call count, each
    relative to its own largest value: the state a run carries into its next step, in the serial mesh's order."""
    worst = (0.0, "")
    with h5py.File(a) as fa, h5py.File(b) as fb:
        names = []
        fa.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) and n != "umat_calls" else None)
        assert "contact/nodes" in names or "cells/state" in names, names
        for n in names:
            x, y = fa[n][()], fb[n][()]
            assert x.shape == y.shape, n
            scale = max(float(np.max(np.abs(x))), 1e-300)
            worst = max(worst, (float(np.max(np.abs(x - y))) / scale, n))
    return worst


@pytest.mark.parametrize("name,text", [("box_p2", BOX), ("cone", CONE)])
def test_restart_on_another_number_of_ranks(tmp_path, name, text):
    """Besides the histories: the state after the first step of the restarted run, as its checkpoint at step 6
    holds it, against the uninterrupted run's checkpoint at step 6 [self]. The step's rates are its end less its
    start (semismooth_commit: the multipliers' increment lambda_6 - lambda_5), so a wrongly restored lambda_5
    shows there even where Newton, converging fully, reaches the same lambda_6 (the cone's history: 1.9e-16 with
    the restored multipliers corrupted)."""
    full = tmp_path / f"{name}_full"
    run(text, full)
    ref = history(full)
    t_ref, s_ref = last_stress(full)
    six = tmp_path / f"{name}_six"
    run(text, six, 1, ["-checkpoint_every", "6", "-max_steps", "6"])
    for first, then in ((1, 2), (2, 1)):
        out = tmp_path / f"{name}_{first}to{then}"
        run(text, out, first, ["-checkpoint_every", "5", "-max_steps", "6"])
        assert (out / "checkpoint.5.h5").is_file() and len(list(out.glob("checkpoint.5.rank*.bin"))) == first
        probe = tmp_path / f"{name}_{first}to{then}_probe"
        shutil.copytree(out, probe)
        run(text, probe, then, ["-restart", "-checkpoint_every", "6", "-max_steps", "6"])
        cdiff, cname = checkpoint_difference(six / "checkpoint.6.h5", probe / "checkpoint.6.h5")
        print(f"{name}: restarted on {then} rank(s), its checkpoint at step 6 against the uninterrupted run's: {cdiff:.1e} ({cname})")
        assert cdiff < TOL, (cname, cdiff)
        proc = run(text, out, then, ["-restart"])
        assert "restart at step 5" in proc.stdout and "on another number of ranks" in proc.stdout, proc.stdout
        h = history(out)
        assert len(h) == len(ref)
        for c in EXACT:
            if c in ref.dtype.names:
                assert np.array_equal(h[c], ref[c]), (c, h[c], ref[c])
        diff, col = worst_difference(ref, h)
        t, s = last_stress(out)
        sdiff = float(np.max(np.abs(s - s_ref)) / np.max(np.abs(s_ref)))
        print(f"{name}: checkpoint on {first} rank(s) at step 5, restarted on {then}: {len(h) - 1} steps as uninterrupted, "
              f"worst history difference {diff:.1e} ({col}), last stress field {sdiff:.1e}")
        assert diff < TOL and sdiff < TOL
        assert np.allclose(t, t_ref, rtol=1e-13, atol=0)
