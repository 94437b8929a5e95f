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

Every number the tables print goes, at full digits and with the run's provenance, into the results store
docs/results/calculix.json; the section "CalculiX on the same mesh (issue 13)" of docs/performance.md is written
from it (camclay9.calculix_study, whose docstring gives the store's layout; tools/doc_numbers.py checks it).

Usage: bench/calculix_compare.py [--sizes 6 2.3 1.4] [--repeats 3 3 1] [--plans full short short]
         [--driver-opts "" "-pc_factor_mat_solver_type mumps"] [--threads 1 2] [--adaptive-size 6] [--note TEXT] [--no-doc]
       bench/calculix_compare.py --from-store      (the section again from the store, nothing run)
"""
import argparse
import datetime
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from camclay9 import calculix_mesh, results_store
from camclay9 import calculix_study as study
from camclay9.performance_doc import publish, republish

ROOT = Path(__file__).resolve().parents[1]
TARGET = {"ratio": 0.5, "from_tets": 10000}    # issue 13: the default >= 2x faster per increment from 10k tets on


def ccx_bindir(build):
    """The folder of the CalculiX executables linked with this build's UMAT (tools/calculix/build_ccx.sh: built once,
    cached by the object's hash; the first build fetches and compiles CalculiX)."""
    r = subprocess.run(["bash", str(ROOT / "tools" / "calculix" / "build_ccx.sh"), str(Path(build) / "umat" / "camclay9_umat.o")],
                       capture_output=True, text=True, timeout=4 * 3600)
    if r.returncode != 0:
        sys.exit(f"calculix_compare: CalculiX not available: {r.stderr.strip()}")
    return r.stdout.strip().splitlines()[-1]


def ccx_version(bindir):
    """The version CalculiX prints (`ccx -v`)."""
    r = subprocess.run([os.path.join(bindir, "ccx_camclay9"), "-v"], capture_output=True, text=True, timeout=60)
    m = re.search(r"Version\s+([0-9][0-9.]*)", r.stdout)
    if not m:
        sys.exit(f"calculix_compare: no version in the output of ccx -v: {r.stdout[-300:]}")
    return m.group(1)


def printed_digits(dat):
    """The significant digits of the displacements CalculiX prints into the .dat (its first printed u_z)."""
    lines = open(dat).read().splitlines()
    at = next(i for i, line in enumerate(lines) if line.strip().startswith("displacements") and "NTOP" in line)
    mantissa = lines[at + 2].split()[3].upper().split("E")[0]
    return len(mantissa.lstrip("+-").replace(".", "").lstrip("0"))


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
                printed=printed, printed_digits=printed_digits(str(wd / "cyl.dat")),
                runs=[store_run(kind, opt, rs) for (kind, opt), rs in runs.items()])


def store_run(kind, opt, runs):
    """One configuration's repeats as the store keeps them (camclay9.calculix_study): increments and iterations of
    the first repeat, medians and each repeat's wall and CPU time."""
    which = {"code": "driver", "options": opt} if kind == "driver" else {"code": "calculix", "threads": opt}
    return dict(which, steps=runs[0]["steps"], its=runs[0]["its"], wall=median(runs, "wall"), cpu=median(runs, "cpu"),
                walls=[r["wall"] for r in runs], cpus=[r["cpu"] for r in runs])


AD_TOL = 1e-6   # PROPS(20) of the adaptive runs, as input/triaxial.yaml


def bench_adaptive(a, bindir, size, tmp):
    """Each code's own step control (PROPS(20) = AD_TOL) against its fixed-increment run, one run each."""
    msh = calculix_mesh.make_mesh(size, str(tmp / f"ad{size}.msh"))
    mesh = calculix_mesh.read_msh22(msh + "22")
    res = {}
    for label, plan, tol in (("fixed", calculix_mesh.PLANS["full"], 0.0), ("adaptive", None, AD_TOL)):
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
        keep = ("steps", "cutbacks", "its", "wall", "cpu")
        res[label] = {"driver": dict({k: d[k] for k in keep}, u_end=drv_uz[-1][1], u_load=u_load_d[0]),
                      "calculix": dict({k: c[k] for k in keep}, u_end=ccx_uz[-1][1],
                                       u_load=[u for _, u, st in ccx_uz if st == ramp_step][-1])}
        shutil.rmtree(out, ignore_errors=True)
        print(f"adaptive study {label}: driver {d['steps']} steps {d['its']} its {d['wall']:.1f} s; ccx {c['steps']} incs "
              f"{c['its']} its {c['wall']:.1f} s; top u_z end driver {drv_uz[-1][1]:.6e} ccx {ccx_uz[-1][1]:.6e}", flush=True)
    return dict(size=size, ntet=len(mesh["tets"]), tol=AD_TOL, runs=res)


def method(a):
    """The store's "method": the plans the runs used (increments and each phase's period), PROPS(20) of the fixed
    increments, the trace's limit and issue 13's target (camclay9.calculix_study)."""
    plans = {}
    for name in sorted(set(a.plans) | ({"full"} if a.adaptive_size > 0 else set())):
        plan = calculix_mesh.PLANS[name]
        plans[name] = dict(increments=sum(round(T / dt) for _, dt, T in plan),
                           **{ph: sum(T for p, _, T in plan if p == ph) for ph in ("hold", "ramp", "creep")})
    return dict(plans=plans, tol_fixed=0.0, trace_max=a.trace_max, target=TARGET)


def command(a):
    return "bench/calculix_compare.py " + " ".join(
        [f"--sizes {' '.join(f'{s:g}' for s in a.sizes)}", f"--repeats {' '.join(map(str, a.repeats))}",
         f"--plans {' '.join(a.plans)}", "--driver-opts " + " ".join(f'"{o}"' for o in a.driver_opts),
         f"--threads {' '.join(map(str, a.threads))}", f"--adaptive-size {a.adaptive_size:g}"])


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


def run_all(a):
    """Every run of the command line; the store (camclay9.calculix_study)."""
    bindir = ccx_bindir(a.build)
    load, start, rev = os.getloadavg(), now(), results_store.revision(ROOT)
    with tempfile.TemporaryDirectory() as t:
        tmp = Path(t)
        meshes = [bench_mesh(a, bindir, s, r, p, tmp) for s, r, p in zip(a.sizes, a.repeats, a.plans)]
        adaptive = bench_adaptive(a, bindir, a.adaptive_size, tmp) if a.adaptive_size > 0 else None
    pv = {"command": command(a), "date": start, "finished": now(), "rev": rev, "calculix": ccx_version(bindir),
          "cores": os.cpu_count(), "load": {"start": list(load), "end": list(os.getloadavg())}}
    if a.note:
        pv["note"] = a.note
    return {"provenance": pv, "method": method(a), "meshes": meshes, "adaptive": adaptive}


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
    ap.add_argument("--note", default="", help="a sentence for the provenance (what the run left out, and why)")
    ap.add_argument("--from-store", action="store_true",
                    help="run nothing: the section again from docs/results/calculix.json")
    ap.add_argument("--no-doc", action="store_true", help="print only, write neither the store nor docs/performance.md")
    a = ap.parse_args(argv)
    if a.from_store:
        return republish(study, write=not a.no_doc) or 0
    a.driver = str(Path(a.build) / "bin" / "driver")
    n = len(a.sizes)
    if len(a.repeats) != n or len(a.plans) != n:
        sys.exit("calculix_compare: give one --repeats and one --plans value per --sizes value")
    store = run_all(a)
    publish(study.TITLE, study.section(store), study.STORE, store, write=not a.no_doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
