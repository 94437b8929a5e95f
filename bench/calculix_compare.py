#!/usr/bin/env python3
"""The FE driver against CalculiX 2.20 on the same mesh (issue 13, item 1).

For each element size, one gmsh mesh of the triaxial cylinder (input/triaxial.yaml's physics, phi drawn per
element by the driver and given to CalculiX per element) runs through the driver (P1, 1 point) and through
CalculiX (C3D4, 1 point) with the same fixed increments; python/camclay9/calculix_mesh.py writes both inputs.

1. Agreement. Where the full-precision trace of CalculiX stays small (elements x increments <= --trace-max),
   the traced CalculiX is compared with the driver per increment (volume-mean strain and stress, mean axial
   viscoplastic strain per frame) and per element at the driver's field outputs (stress, pc, evp). On every
   mesh, the mean axial displacement of the top at the end of each phase is compared at CalculiX's 7 printed
   digits (.dat).
2. Time. Driver with each --driver-opts (default: its default solver, and MUMPS), CalculiX (SPOOLES) with each
   --threads, interleaved (driver, driver-mumps, ccx 1, ccx 2, then again), medians of the repeats of the
   process wall and CPU time (the driver on one rank).
3. Adaptive (--adaptive-size): each code's own incrementation with PROPS(20) = 1e-6 as input/triaxial.yaml,
   with the end strain against the fixed-increment run.

Usage: bench/calculix_compare.py [--sizes 6 2.3 1.4] [--repeats 3 3 1] [--plans full short short]
         [--driver-opts "" "-pc_factor_mat_solver_type mumps"] [--threads 1 2] [--adaptive-size 6] [--no-doc]
Writes the section "CalculiX on the same mesh (issue 13)" of docs/performance.md.
"""
import argparse
import datetime
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import calculix_mesh
from camclay9.performance_doc import replace_section

ROOT = Path(__file__).resolve().parents[1]

TITLE = "## CalculiX on the same mesh (issue 13)"


def ccx_bindir(build):
    r = subprocess.run(["bash", str(ROOT / "tools" / "calculix" / "build_ccx.sh"), str(Path(build) / "umat" / "camclay9_umat.o")],
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"calculix_compare: CalculiX not available: {r.stderr.strip()}")
    return r.stdout.strip().splitlines()[-1]


def top_uz_ccx(dat, sta):
    """Mean u_z of the top nodes per increment, (time, mm), from the *NODE PRINT blocks of the .dat (7 digits),
    one block per increment; the times are those of the .sta (the .dat prints them with 7 digits only)."""
    out, lines = [], open(dat).read().splitlines()
    for i, line in enumerate(lines):
        if line.strip().startswith("displacements") and "NTOP" in line:
            rows = []
            for x in lines[i + 2:]:
                if not x.strip():
                    break
                rows.append(float(x.split()[3]))
            out.append(float(np.mean(rows)) / calculix_mesh.SCALE)
    times = np.cumsum([r[3] for r in sta])          # exact for the fixed plans; 6 digits per increment otherwise
    assert len(out) == len(times), f"{dat}: {len(out)} printed increments, {len(times)} in the .sta"
    return [(t, u, r[0]) for t, u, r in zip(times, out, sta)]


def top_uz_driver(outdir):
    """Mean u_z of the top nodes (z = H) at each field output of the driver, with its times."""
    import h5py
    with h5py.File(os.path.join(outdir, "fields.h5"), "r") as f:
        xyz = f["/mesh/coordinates"][:]
        top = np.abs(xyz[:, 2] - calculix_mesh.H) < 1e-9 * calculix_mesh.H
        times = f["/time"][:, 0]
        return [(t, float(f[f"/fields/displacement/{k:06d}"][:][top, 2].mean())) for k, t in enumerate(times)], int(top.sum())


def printed_agreement(dat, sta, outdir):
    """Worst relative difference of the mean top u_z at the driver's output times (t > 0)."""
    drv, _ = top_uz_driver(outdir)
    ccx = top_uz_ccx(dat, sta)
    worst = 0.0
    for t, u in drv:
        if t == 0:
            continue
        c = min(ccx, key=lambda x: abs(x[0] - t))
        assert abs(c[0] - t) < 1e-9 * t
        worst = max(worst, abs(c[1] - u) / abs(u))
    return worst


def median(runs, key):
    return statistics.median(r[key] for r in runs)


def bench_mesh(a, bindir, size, repeats, plan_name, tmp):
    plan = calculix_mesh.PLANS[plan_name]
    msh = calculix_mesh.make_mesh(size, str(tmp / f"cyl{size}.msh"))
    mesh = calculix_mesh.read_msh22(msh + "22")
    ntet, nnode = len(mesh["tets"]), len(mesh["ids"])
    scene = calculix_mesh.write_scene(msh, str(tmp / f"scene{size}.yaml"), str(tmp / "out"), 0.0, plan)
    first = str(tmp / f"drv{size}")
    incs = sum(round(T / dt) for _, dt, T in plan)
    traced = ntet * incs <= a.trace_max
    # The driver's phi of this mesh: from a whole run where it is compared with the trace, else from the
    # fields written before the first step (-max_steps 1).
    calculix_mesh.run_driver(a.driver, scene, first, a.driver_opts[-1].split() + ([] if traced else ["-max_steps", "1"]))
    cell_of, f = calculix_mesh.driver_cells(first, mesh)
    with f:
        phi = f["/fields/phi/000000"][:][cell_of]
    wd = tmp / f"ccx{size}"
    wd.mkdir()
    calculix_mesh.write_inp(mesh, str(wd / "cyl.inp"), phi, 0.0, plan)
    agree = {}
    if traced:
        c = calculix_mesh.run_ccx(bindir, str(wd), "cyl", threads=1, trace=str(wd / "trace.bin"))
        agree, _, _ = calculix_mesh.compare(first, mesh, str(wd / "trace.bin"), c["sta"])
        os.remove(wd / "trace.bin")
    print(f"size {size}: {ntet} tets, {nnode} nodes, plan {plan_name} ({incs} increments); agreement "
          + (", ".join(f"{k} {v:.1e}" for k, v in agree.items()) or "(trace skipped)"), flush=True)
    configs = [("driver", o) for o in a.driver_opts] + [("ccx", t) for t in a.threads]
    runs = {c: [] for c in configs}
    printed = 0.0
    for rep in range(repeats):
        for kind, opt in configs:
            if kind == "driver":
                out = str(tmp / "out")
                r = calculix_mesh.run_driver(a.driver, scene, out, opt.split())
                printed_d = out
            else:
                r = calculix_mesh.run_ccx(bindir, str(wd), "cyl", threads=opt)
            runs[(kind, opt)].append(r)
            print(f"  rep {rep} {kind} {opt or 'default'}: {r['steps']} incs, {r['its']} its, wall {r['wall']:.2f} s, "
                  f"cpu {r['cpu']:.2f} s", flush=True)
        printed = max(printed, printed_agreement(str(wd / "cyl.dat"), runs[("ccx", a.threads[0])][-1]["sta"], printed_d))
        shutil.rmtree(printed_d, ignore_errors=True)
    shutil.rmtree(first, ignore_errors=True)
    return dict(size=size, ntet=ntet, nnode=nnode, plan=plan_name, incs=incs, repeats=repeats, agree=agree,
                printed=printed, runs=runs)


def bench_adaptive(a, bindir, size, tmp):
    """Each code's own step control (PROPS(20) = 1e-6) against its fixed-increment run, one run each."""
    msh = calculix_mesh.make_mesh(size, str(tmp / f"ad{size}.msh"))
    mesh = calculix_mesh.read_msh22(msh + "22")
    res = {}
    for label, plan, tol in (("fixed", calculix_mesh.PLANS["full"], 0.0), ("adaptive", None, 1e-6)):
        out = str(tmp / f"ad_{label}")
        scene = calculix_mesh.write_scene(msh, str(tmp / f"ad_{label}.yaml"), out, tol, plan)
        d = calculix_mesh.run_driver(a.driver, scene, out, a.driver_opts[0].split())
        cell_of, f = calculix_mesh.driver_cells(out, mesh)
        with f:
            phi = f["/fields/phi/000000"][:][cell_of]
        drv_uz, _ = top_uz_driver(out)
        wd = tmp / f"adccx_{label}"
        wd.mkdir()
        calculix_mesh.write_inp(mesh, str(wd / "cyl.inp"), phi, tol, plan)
        c = calculix_mesh.run_ccx(bindir, str(wd), "cyl", threads=1)
        ccx_uz = top_uz_ccx(str(wd / "cyl.dat"), c["sta"])
        loaded = 1e6 + 1                                                    # end of the ramp
        ramp_step = 1 + max(k for k, st in enumerate(plan or calculix_mesh.ADAPTIVE) if st[0] == "ramp")
        u_load_d = [u for t, u in drv_uz if abs(t - loaded) < 1e-9 * loaded]
        res[label] = dict(driver=d, ccx=c, u_driver=drv_uz[-1][1], u_ccx=ccx_uz[-1][1],
                          u_load_driver=u_load_d[0], u_load_ccx=[u for _, u, st in ccx_uz if st == ramp_step][-1])
        shutil.rmtree(out, ignore_errors=True)
        print(f"adaptive study {label}: driver {d['steps']} steps {d['its']} its {d['wall']:.1f} s; ccx {c['steps']} incs "
              f"{c['its']} its {c['wall']:.1f} s; top u_z end driver {drv_uz[-1][1]:.6e} ccx {ccx_uz[-1][1]:.6e}", flush=True)
    return dict(size=size, ntet=len(mesh["tets"]), res=res)


def table(results):
    lines = ["| tets (nodes) | increments | code, options | Newton its | wall s | CPU s | wall ms / increment | "
             "wall ms / Newton it. | CPU ms / increment | per increment vs CalculiX 1 thread: wall, CPU |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        ref = None
        for (kind, opt), runs in r["runs"].items():
            if kind == "ccx" and opt == 1:
                ref = (median(runs, "wall") / runs[0]["steps"], median(runs, "cpu") / runs[0]["steps"])
        for (kind, opt), runs in r["runs"].items():
            wall, cpu, steps, its = median(runs, "wall"), median(runs, "cpu"), runs[0]["steps"], runs[0]["its"]
            name = f"driver {opt}" if kind == "driver" and opt else ("driver (default solver)" if kind == "driver"
                                                                     else f"CalculiX SPOOLES, {opt} thread{'s' if opt > 1 else ''}")
            ratio = f"{wall / steps / ref[0]:.2f}, {cpu / steps / ref[1]:.2f}" if ref else ""
            lines.append(f"| {r['ntet']} ({r['nnode']}) | {steps} ({r['plan']}) | {name} | {its} | {wall:.2f} | {cpu:.2f} | "
                         f"{1e3 * wall / steps:.1f} | {1e3 * wall / max(its, 1):.1f} | {1e3 * cpu / steps:.1f} | {ratio} |")
    return "\n".join(lines)


def agreement_table(results):
    lines = ["| tets | increments | mean strain | mean stress | mean evp33 hard / soft | cell stress | cell pc hard / soft "
             "| cell evp | top u_z (7 printed digits) |", "|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        g = r["agree"]
        full = (f"{g['mean strain']:.1e} | {g['mean stress']:.1e} | {g['mean evp33 hard']:.1e} / {g['mean evp33 soft']:.1e} | "
                f"{g['cell stress']:.1e} | {g['cell pc_hard']:.1e} / {g['cell pc_soft']:.1e} | {g['cell evp']:.1e}") if g \
            else "(no trace: too large) | | | | | "
        lines.append(f"| {r['ntet']} | {r['incs']} | {full} | {r['printed']:.1e} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=float, nargs="+", default=[6.0, 2.3, 1.4], help="gmsh element sizes [mm]")
    ap.add_argument("--repeats", type=int, nargs="+", default=[3, 3, 1], help="repeats per size")
    ap.add_argument("--plans", nargs="+", default=["full", "short", "short"], choices=sorted(calculix_mesh.PLANS),
                    help="fixed increments per size: full (76) or short (10)")
    ap.add_argument("--driver-opts", nargs="+", default=["", "-pc_factor_mat_solver_type mumps"],
                    help="PETSc options of each driver configuration, one quoted string each ('' = the driver's defaults; "
                         "a single option without a space needs a trailing space, as '-snes_monitor ', for argparse)")
    ap.add_argument("--threads", type=int, nargs="+", default=[1, 2], help="CalculiX threads (OMP_NUM_THREADS)")
    ap.add_argument("--adaptive-size", type=float, default=6.0, help="element size of the adaptive study (0: none)")
    ap.add_argument("--trace-max", type=int, default=120000, help="largest tets x increments traced at full precision")
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--no-doc", action="store_true", help="print only, do not write docs/performance.md")
    a = ap.parse_args(argv)
    a.driver = str(Path(a.build) / "bin" / "driver")
    n = len(a.sizes)
    if len(a.repeats) != n or len(a.plans) != n:
        sys.exit("calculix_compare: give one --repeats and one --plans value per --sizes value")
    bindir = ccx_bindir(a.build)
    load = os.getloadavg()
    start = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        results = [bench_mesh(a, bindir, s, r, p, tmp) for s, r, p in zip(a.sizes, a.repeats, a.plans)]
        adaptive = bench_adaptive(a, bindir, a.adaptive_size, tmp) if a.adaptive_size > 0 else None
    load_end = os.getloadavg()
    cmd = "bench/calculix_compare.py " + " ".join(
        [f"--sizes {' '.join(f'{s:g}' for s in a.sizes)}", f"--repeats {' '.join(map(str, a.repeats))}",
         f"--plans {' '.join(a.plans)}", "--driver-opts " + " ".join(f'"{o}"' for o in a.driver_opts),
         f"--threads {' '.join(map(str, a.threads))}", f"--adaptive-size {a.adaptive_size:g}"])
    text = (f"{TITLE}\n\nCommand: `{cmd}`. Run {start}; load average {load[0]:.1f} at the start and {load_end[0]:.1f} "
            "at the end (2 cores shared with other jobs: take the times as rough, compare CPU beside wall).\n\n"
            + AGREE_TEXT + agreement_table(results) + "\n\n" + TIME_TEXT + table(results) + "\n")
    if adaptive:
        text += "\n" + adaptive_text(adaptive)
    print(text)
    if not a.no_doc:
        replace_section(TITLE, text)
        print("written: docs/performance.md")


AGREE_TEXT = """One gmsh mesh per row (meshes/cylinder.geo), run by the driver (P1 tetrahedra, 1 point) and by CalculiX 2.20
(C3D4, 1 point), with the same UMAT, PROPS (tol = 0), per-element phi (the driver's draw of input/triaxial.yaml,
written into CalculiX as one material per element), supports, pressures and fixed increments: "full" is the
76 increments of input/abaqus (hold 1e6 s, ramp the top from 35 to 75 MPa in 1 s, creep 36000 s), "short" the
first increments of each phase (10). How: python/camclay9/calculix_mesh.py, docs/calculix.md. **Agreement**, worst
relative difference over all increments (per element: over the field outputs at the end of each phase); the
full-precision columns need the traced CalculiX and are left out on large meshes:

"""

TIME_TEXT = """**Time.** Process wall and CPU time (user + system), medians of the repeats, runs interleaved (each
configuration once per round). The driver on one rank, its Newton to 1e-12 relative; CalculiX with SPOOLES,
`*CONTROLS` residual and correction ratios 1e-12 (it symmetrises DDSDDE, so its Newton converges linearly and
takes more iterations). Both times include start-up and input (CalculiX reads one material per element).
The driver's default solver (docs/driver.md, "Solvers"): MUMPS inside GMRES, its factorisation kept across
Newton iterations and steps while the Krylov iterations stay few, the Jacobian assembled by COO; the option
`-ksp_type preonly -fe_coo false -pc_factor_mat_solver_type mumps` is the set-up before issue 13's solver
work (a fresh MUMPS factorisation at every Newton iteration, MatSetValues). Issue 13 asks for the default to be
at least 2x faster per increment than CalculiX at 10k tets and above: the last column at most 0.5.

"""


def adaptive_text(ad):
    lines = [f"**Adaptive** ({ad['ntet']} tets, one run each). Each code's own incrementation with PROPS(20) = tol = 1e-6 "
             "as input/triaxial.yaml: the driver's worst-point control (PNEWDT), CalculiX's automatic incrementation "
             "(first, minimum and maximum increments of input/abaqus' cylinder; it grows by its iteration counts and "
             "cuts where the UMAT's PNEWDT asks). Creep = top u_z at 36000 s minus at the end of the ramp, against "
             "the same code's fixed 76 increments.", "",
             "| run | code | increments | cutbacks | Newton its | wall s | CPU s | creep [mm] | creep vs fixed |",
             "|---|---|---|---|---|---|---|---|---|"]
    fixed = ad["res"]["fixed"]
    for label in ("fixed", "adaptive"):
        r = ad["res"][label]
        for code in ("driver", "ccx"):
            x = r[code]
            creep = r[f"u_{code}"] - r[f"u_load_{code}"]
            ref = fixed[f"u_{code}"] - fixed[f"u_load_{code}"]
            lines.append(f"| {label} | {'driver' if code == 'driver' else 'CalculiX, 1 thread'} | {x['steps']} | {x['cutbacks']} | {x['its']} | "
                         f"{x['wall']:.2f} | {x['cpu']:.2f} | {creep:.5e} | {creep / ref - 1:+.1e} |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    sys.exit(main())
