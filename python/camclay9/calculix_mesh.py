"""One gmsh mesh of the triaxial cylinder in the FE driver and in CalculiX (issue 13); bench/calculix_compare.py
and tests/calculix/test_same_mesh.py run it.

The physics of input/triaxial.yaml (input/triaxial.yaml): the cylinder of meshes/cylinder.geo, both frames at
-35 MPa in equilibrium with 35 MPa on the top and the side, the bottom on rollers, its centre pinned, one rim
point held in y; phi per element from the seeded normal draw of the scene. The history is the one of
input/abaqus (camclay9.calculix_inputs): hold 1e6 s, ramp the top to 75 MPa in 1 s (a ramp: CalculiX has no zero-time
step for triaxial.yaml's `load: instant`), creep 36000 s.

- The mesh: `gmsh -3 -format msh41` of meshes/cylinder.geo; the driver reads that .msh (`mesh.file`), P1
  tetrahedra with 1 point; here it is read from its msh 2.2 conversion (`gmsh -0`, no remeshing); CalculiX reads the same nodes and tetrahedra as C3D4 (1 point), written here with
  calculix_inputs.fmt, so that no coordinate is cut by CalculiX's 20-character field (issue 13, item 7).
- phi: the driver draws it per element; the bench runs the driver first, reads its per-cell phi from
  fields.h5 and gives CalculiX one material per element with that phi (15 digits).
- Pressures: *DSLOAD on the element faces lying on the `top` and `side` triangles of the mesh (the consistent
  load of a linear triangle, p A / 3 per node, as the driver's).
- Units: CalculiX sets an equilibrium residual below 1e-6 force units to zero and converges (nonlingeo.c,
  docs/calculix.md); its coordinates are therefore written in um (x 1000: forces in uN-scale units, 1e6
  times larger), stresses in MPa as before. Strains and stresses are unchanged by the scaling.
- Increments: the same list of times in both (PLANS, fixed) or each code's automatic incrementation.
"""
import os
import resource
import subprocess
import time

import camclay9
import numpy as np
from camclay9 import calculix_inputs
from camclay9.fields import STRAINS, voigt  # fields.h5's 3x3 tensors as Voigt 11 22 33 12 13 23

R, H = 12.7, 50.8
SCALE = 1000.0                          # CalculiX's length unit: um (see the module docstring)
PHI = {"mean": 0.5, "std": 0.05, "min": 0.4, "max": 0.6, "seed": 2021}   # input/triaxial.yaml

# Fixed increments per phase as (increment, period); phase = hold / ramp / creep. "full": the 76 increments
# of input/abaqus; "short": the first increments of each phase of "full" (10 increments, same lengths).
PLANS = {
    "full": [("hold", dt, T) for dt, T in calculix_inputs.HOLD] + [("ramp", dt, T) for dt, T in calculix_inputs.RAMP]
            + [("creep", dt, T) for dt, T in calculix_inputs.CREEP],
    "short": [("hold", 100., 300.), ("ramp", 0.25, 1.), ("creep", 10., 30.)],
}
# Automatic incrementation: (first, period, min, max) per phase, as input/abaqus' cylinder (CYL_STEPS).
ADAPTIVE = [("hold",) + tuple(calculix_inputs.CYL_STEPS[0]), ("ramp",) + tuple(calculix_inputs.CYL_STEPS[1]),
            ("creep",) + tuple(calculix_inputs.CYL_STEPS[2])]
# CalculiX face numbers of a C3D4 (Abaqus convention, CalculiX's C3D4 faces): the local node triples.
TET_FACES = {1: (0, 1, 2), 2: (0, 3, 1), 3: (1, 3, 2), 4: (2, 3, 0)}


def props(tol):
    """The 20 constants of input/abaqus (calculix_inputs.PROPS, Yin et al. 2021 Tables 1-2) with PROPS(20) = tol."""
    nums = [float(x) for line in calculix_inputs.PROPS.splitlines()
            if line and line[0] == " " and not line.startswith("**") for x in line.split(",") if x.strip()]
    vals = nums[:20]
    assert len(vals) == 20
    vals[19] = tol
    return vals


def make_mesh(size, path, root=None):
    """gmsh -3 of meshes/cylinder.geo at the element size into `path` (msh 4.1, as the driver meshes a .geo),
    and the same mesh converted without remeshing (gmsh -0) to msh 2.2, `path` + "22", read here. The .geo is the
    one of the repository `root` (default: camclay9.repo_root())."""
    geo = os.path.join(camclay9.repo_root(root), "meshes", "cylinder.geo")
    cmds = [["gmsh", geo, "-3", "-format", "msh41", "-setnumber", "R", str(R), "-setnumber", "H", str(H),
             "-setnumber", "size", str(size), "-o", path], ["gmsh", path, "-0", "-format", "msh22", "-o", path + "22"]]
    for cmd in cmds:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        if r.returncode != 0 or not os.path.exists(cmd[-1]):
            raise RuntimeError(f"{' '.join(cmd)} failed: {r.stdout[-2000:]}{r.stderr[-2000:]}")
    return path


def read_msh22(path):
    """Nodes (ids, xyz), tetrahedra (node ids), triangles and points per physical name of a msh 2.2 file."""
    with open(path) as f:
        text = f.read()
    sec = lambda name: text.split(f"${name}\n")[1].split(f"$End{name}")[0].split("\n")[1:-1]  # noqa: E731
    names = {int(w.split()[1]): w.split('"')[1] for w in sec("PhysicalNames")}
    nodes = np.array([[float(x) for x in line.split()] for line in sec("Nodes")])
    tets, groups = [], {}
    for line in sec("Elements"):
        w = [int(x) for x in line.split()]
        etype, ntags, tag = w[1], w[2], w[3]
        conn = w[3 + ntags:]
        if etype == 4:
            tets.append(conn)
        elif etype in (2, 15):
            groups.setdefault(names[tag], []).append(conn)
    ids = nodes[:, 0].astype(int)
    return {"ids": ids, "xyz": nodes[:, 1:], "tets": np.array(tets), "groups": {k: np.array(v) for k, v in groups.items()}}


def tet_geometry(mesh):
    """Volumes and centroids of the tetrahedra (mm)."""
    where = {n: i for i, n in enumerate(mesh["ids"])}
    x = mesh["xyz"][np.vectorize(where.get)(mesh["tets"])]
    vol = np.einsum("ij,ij->i", np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), x[:, 3] - x[:, 0]) / 6
    return vol, x.mean(axis=1)


def _faces(mesh, group):
    """(element number, face number) of the C3D4 faces lying on the triangles of a physical group."""
    owner = {}
    for e, t in enumerate(mesh["tets"], 1):
        for k, (a, b, c) in TET_FACES.items():
            owner[frozenset((t[a], t[b], t[c]))] = (e, k)
    return [owner[frozenset(tri)] for tri in mesh["groups"][group]]


def write_inp(mesh, path, phi, tol, plan=None, trace_out=True):
    """The CalculiX input: C3D4 of the mesh (positively oriented), one material per element with its phi,
    the scene's supports and pressures, fixed increments (plan, a PLANS entry) or automatic (plan None)."""
    vol, _ = tet_geometry(mesh)
    tets = mesh["tets"].copy()
    tets[vol < 0] = tets[vol < 0][:, [0, 2, 1, 3]]
    fmt = calculix_inputs.fmt
    lines = ["** The triaxial cylinder of input/triaxial.yaml on a gmsh mesh shared with the FE driver",
             "** (python/camclay9/calculix_mesh.py): C3D4, lengths in um (x 1000), stresses in MPa.",
             "*HEADING", "Cam-Clay IX triaxial cylinder, same mesh as the driver", "*NODE, NSET=NALL"]
    lines += [f" {i}, {fmt(SCALE * x)}, {fmt(SCALE * y)}, {fmt(SCALE * z)}" for i, (x, y, z) in zip(mesh["ids"], mesh["xyz"])]
    lines.append("*ELEMENT, TYPE=C3D4, ELSET=EALL")
    lines += [f" {e}, {t[0]}, {t[1]}, {t[2]}, {t[3]}" for e, t in enumerate(tets, 1)]
    g = mesh["groups"]
    for name, nodes in (("NBOTTOM", np.unique(g["bottom"])), ("NPIN", g["pin"].ravel()), ("NRIM", g["rim"].ravel()),
                        ("NTOP", np.unique(g["top"]))):
        lines.append(f"*NSET, NSET={name}")
        lines.append(calculix_inputs.ids_lines(nodes).rstrip("\n"))
    m = dict(mesh, tets=tets)
    for name, grp in (("TOP", "top"), ("SIDE", "side")):
        lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        lines += [f" {e}, S{k}" for e, k in _faces(m, grp)]
    p = props(tol)
    for e in range(1, len(tets) + 1):
        vals = [phi[e - 1]] + p[1:]
        lines += [f"*ELSET, ELSET=E{e}", f" {e}", f"*SOLID SECTION, ELSET=E{e}, MATERIAL=ABAQUS_E{e}",
                  f"*MATERIAL, NAME=ABAQUS_E{e}", "*USER MATERIAL, CONSTANTS=20"]
        lines += [" " + ", ".join(fmt(v) for v in vals[k:k + 8]) for k in range(0, 20, 8)]
        lines += ["*DEPVAR", " 36"]
    lines += ["*AMPLITUDE, NAME=CONST", " 0., 1., 1.E10, 1.", "*BOUNDARY", " NBOTTOM, 3", " NPIN, 1, 2", " NRIM, 2",
              "*INITIAL CONDITIONS, TYPE=STRESS"]
    lines += [f" {e}, 1, -35., -35., -35., 0., 0., 0." for e in range(1, len(tets) + 1)]
    out = "*NODE PRINT, NSET=NTOP, TOTALS=ONLY\n U\n"
    loads = {"hold": "*DSLOAD, AMPLITUDE=CONST\n SIDE, P, 35.\n TOP, P, 35.\n",
             "ramp": "** the top pressure ramps from 35 to 75 MPa over this step\n*DSLOAD\n TOP, P, 75.\n", "creep": ""}
    text, done = "\n".join(lines) + "\n", set()
    steps = plan if plan is not None else ADAPTIVE
    for k, st in enumerate(steps):
        phase = st[0]
        card = (f"*STATIC, DIRECT\n {fmt(st[1])}, {fmt(st[2])}\n" if plan is not None else
                f"*STATIC\n {fmt(st[1])}, {fmt(st[2])}, {fmt(st[3])}, {fmt(st[4])}\n")
        text += ("*STEP, INC=100000\n" + card + (calculix_inputs.CONTROLS if k == 0 else "")
                 + (loads[phase] if phase not in done else "") + out + "*END STEP\n")
        done.add(phase)
    with open(path, "w") as f:
        f.write(text)
    return path


def write_scene(msh, path, outdir, tol, plan=None, phi=True):
    """The driver's scene: input/triaxial.yaml's physics on the .msh, the plan's increments (or adaptive)."""
    p = props(tol)
    st = []
    for k, s in enumerate(plan if plan is not None else ADAPTIVE):
        phase = s[0]
        pres = {"hold": "{top: 35, side: 35}", "ramp": "{top: 75, side: 35}", "creep": "{top: 75, side: 35}"}[phase]
        if plan is not None:
            dt, T = s[1], s[2]
            steps = f"{{count: {round(T / dt)}}}"
        else:
            first, T, tmin, tmax = s[1:]
            steps = f"{{adaptive: true, first: {first!r}, min: {tmin!r}, max: {tmax!r}}}"
        st.append(f"  - {{name: {phase}{k}, duration: {T!r}, pressure: {pres}, steps: {steps}}}")
    phi_line = ("phi: {" + ", ".join(f"{k}: {v}" for k, v in PHI.items()) + "}\n") if phi else ""
    text = f"""# The triaxial cylinder on a fixed gmsh mesh, shared with CalculiX (python/camclay9/calculix_mesh.py).
scene: fe
name: same_mesh
units: {{length: mm, force: N, stress: MPa, time: s}}
mesh: {{file: {os.path.abspath(msh)}, order: 1}}
material: {{props: [{", ".join(repr(v) for v in p)}]}}
{phi_line}initial:
  stress: [-35, -35, -35, 0, 0, 0]
  pressure: {{top: 35, side: 35}}
boundary:
  fixed:
    - {{group: bottom, components: [z]}}
    - {{group: pin, components: [x, y]}}
    - {{group: rim, components: [y]}}
  pressure: [top, side]
stages:
{chr(10).join(st)}
output: {{directory: {outdir}}}
"""
    with open(path, "w") as f:
        f.write(text)
    return path


def _timed(cmd, timeout=7200, **kw):
    """Run (killed after `timeout` seconds); wall time and CPU time (user + system of the child) in seconds."""
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, **kw)
    wall = time.perf_counter() - t0
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r, wall, (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)


def run_driver(driver, scene, outdir, opts=()):
    """Run the driver on one rank; steps, Newton iterations and times from its summary line."""
    r = camclay9.run_driver(scene, outdir, ["-progress_every", "0", *opts], driver=driver, timeout=24 * 3600)
    s = camclay9.summary_line(r.stdout, index=0)
    return dict(steps=s["steps"], its=s["newton_iterations"], cutbacks=s["cutbacks"], wall=r.wall, cpu=r.cpu,
                assembly=s["assembly_s"])


def run_ccx(bindir, workdir, name, threads=1, trace=None):
    """Run CalculiX (plain, or traced into the binary log `trace`); increments and iterations from the .sta."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), CCX_NPROC_RESULTS=str(threads))
    exe = os.path.join(bindir, "ccx_camclay9_trace" if trace else "ccx_camclay9")
    if trace:
        env["CAMCLAY9_TRACE_BIN"] = trace
    r, wall, cpu = _timed([exe, "-i", name], cwd=workdir, env=env)
    if r.returncode != 0 or "Job finished" not in r.stdout:
        raise RuntimeError(f"CalculiX failed on {workdir}/{name}.inp: {r.stdout[-3000:]}{r.stderr[-1000:]}")
    with open(os.path.join(workdir, name + ".sta")) as f:
        rows = [line.split() for line in f.readlines()[2:] if line.strip()]
    # An attempt that did not converge, or that the UMAT's PNEWDT cut, is listed with "U" after its
    # attempt number; its iterations were spent all the same.
    done = [w for w in rows if not w[2].endswith("U")]
    return dict(steps=len(done), its=sum(int(w[3]) for w in rows), cutbacks=len(rows) - len(done), wall=wall, cpu=cpu,
                sta=[(int(w[0]), int(w[1]), float(w[4]), float(w[6])) for w in done])


def read_trace(path, nstatv=36):
    """The converged record of each (step, increment, element) of a binary trace: the last call of each
    (docs/calculix.md: the call after convergence repeats the converged strain). Returns a structured array
    sorted by step, increment, element."""
    dt = np.dtype([("jstep", "<i4"), ("kinc", "<i4"), ("noel", "<i4"), ("npt", "<i4"),
                   ("strain", "<f8", 6), ("stress", "<f8", 6), ("statev", "<f8", nstatv)])
    rec = np.fromfile(path, dtype=dt)
    key = (rec["jstep"].astype(np.int64) << 40) + (rec["kinc"].astype(np.int64) << 20) + rec["noel"]
    rev = key[::-1]
    _, first_in_rev = np.unique(rev, return_index=True)          # sorted keys, last occurrence in rec
    return rec[len(rec) - 1 - first_in_rev]


def trace_history(rec, vol):
    """Per converged increment: volume-mean strain and stress (as the driver's history.csv) and the
    unweighted means of the axial viscoplastic strain per frame (STATEV 9 and 22: evp33 of each frame)."""
    n = len(vol)
    inc = rec.reshape(-1, n)
    assert np.all(inc["noel"] == np.arange(1, n + 1)), "every increment must have every element once"
    w = vol / vol.sum()
    return dict(eps=np.einsum("ike,i->ke", inc["strain"].transpose(1, 0, 2), w),
                sig=np.einsum("ike,i->ke", inc["stress"].transpose(1, 0, 2), w),
                evp33_hard=inc["statev"][:, :, 8].mean(axis=1), evp33_soft=inc["statev"][:, :, 21].mean(axis=1),
                statev=inc["statev"], stress=inc["stress"])


def driver_history(outdir):
    h = camclay9.read_history(outdir)
    return dict(time=h["time"], its=h["newton_its"].astype(float),
                eps=np.column_stack([h[f"eps_{c}"] for c in ("11", "22", "33", "12", "13", "23")]),
                sig=np.column_stack([h[f"sig_{c}"] for c in ("11", "22", "33", "12", "13", "23")]),
                evp33_hard=h["evp33_hard_mean"], evp33_soft=h["evp33_soft_mean"])


def driver_cells(outdir, mesh):
    """Map from the gmsh tetrahedra to the driver's cells (by centroid) and the driver's fields.h5 reader."""
    import h5py
    f = h5py.File(os.path.join(outdir, "fields.h5"), "r")
    xyz, cells = f["/mesh/coordinates"][:], f["/mesh/cells"][:]
    cen = xyz[cells].mean(axis=1)
    _, mine = tet_geometry(mesh)
    order_d, order_m = np.lexsort(np.round(cen, 9).T[::-1]), np.lexsort(np.round(mine, 9).T[::-1])
    cell_of = np.empty(len(mine), dtype=int)
    cell_of[order_m] = order_d
    gap = np.abs(cen[cell_of] - mine).max()
    assert gap < 1e-9 * H, f"driver cells and gmsh tetrahedra do not match by centroid (gap {gap:g} mm)"
    return cell_of, f


def rel(a, b):
    """Relative difference per row (Euclidean norms); rows whose reference is 0 compare absolutely."""
    a, b = np.atleast_2d(a), np.atleast_2d(b)
    nb = np.linalg.norm(b, axis=1)
    d = np.linalg.norm(a - b, axis=1)
    return np.where(nb > 0, d / np.where(nb > 0, nb, 1), d)


def compare(outdir, mesh, trace_path, sta):
    """Worst relative difference, driver against CalculiX (full-precision trace), over the increments: the
    volume-mean strain and stress, the mean axial viscoplastic strain of each frame (history.csv, 15 and 12
    digits), and per element at every field output of the driver (fields.h5, doubles): stress, pc of both
    frames, the viscoplastic strain. Also returns the increment times of both (they must be equal)."""
    vol, _ = tet_geometry(mesh)
    th = trace_history(read_trace(trace_path), vol)
    dh = driver_history(outdir)
    t_ccx = np.cumsum([s[3] for s in sta])
    assert len(dh["time"]) - 1 == len(t_ccx), f"{len(dh['time']) - 1} driver steps, {len(t_ccx)} CalculiX increments"
    worst = {"time": float(np.abs(dh["time"][1:] - t_ccx).max() / t_ccx[-1]),
             "mean strain": float(rel(dh["eps"][1:], th["eps"]).max()),
             "mean stress": float(rel(dh["sig"][1:], th["sig"]).max()),
             "mean evp33 hard": float(rel(dh["evp33_hard"][1:, None], th["evp33_hard"][:, None]).max()),
             "mean evp33 soft": float(rel(dh["evp33_soft"][1:, None], th["evp33_soft"][:, None]).max())}
    cell_of, f = driver_cells(outdir, mesh)
    with f:
        times = f["/time"][:, 0]
        for name, sl in (("cell stress", None), ("cell pc_hard", 12), ("cell pc_soft", 25), ("cell evp", slice(26, 32))):
            w = 0.0
            for k, t in enumerate(times):
                if t == 0:
                    continue
                i = int(np.argmin(np.abs(t_ccx - t)))
                assert abs(t_ccx[i] - t) <= 1e-12 * t, f"no CalculiX increment at the driver's output time {t}"
                field = name.split()[1]
                d = f[f"/fields/{field}/{k:06d}"][:][cell_of]
                if d.ndim == 2 and d.shape[1] == 9:           # a tensor: back to the UMAT's Voigt order and shear
                    d = voigt(d, field in STRAINS)
                c = th["statev"][i][:, sl] if sl is not None else th["stress"][i]
                w = max(w, float(rel(d.reshape(len(d), -1), c.reshape(len(c), -1)).max()))
            worst[name] = w
    return worst, dh, th

