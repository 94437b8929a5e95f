"""The driver's BLAS note (driver/src/app/blas_check.h) against tools/blas_core.py (camclay9.blas), the same rule in Python: after
a run the driver says that OpenBLAS fell back to kernels below what the CPU runs exactly where tools/blas_core.py
would name a core, and names the same one; with OPENBLAS_CORETYPE set it says nothing. On a machine where OpenBLAS
recognises the CPU both say nothing (the case the note is for is measured in docs/performance.md, "BLAS kernels";
driver.blas_check tests the decision on every case)."""
import os
import re
import subprocess
import sys
from pathlib import Path

from camclay9 import run_driver

ROOT = Path(__file__).resolve().parents[2]
SCENE = ROOT / "input" / "point" / "isotropic_compression.yaml"
NOTE = re.compile(r"^note: OpenBLAS did not recognise this CPU .* export OPENBLAS_CORETYPE=(\w+) ", re.M)


def blas_core_export(env):
    """The core tools/blas_core.py names here (None: none needed)."""
    out = subprocess.run([sys.executable, str(ROOT / "tools" / "blas_core.py"), "--export"], env=env, capture_output=True,
                         text=True, timeout=60, check=True).stdout
    m = re.search(r"OPENBLAS_CORETYPE=(\w+)", out)
    return m.group(1) if m else None


def note(tmp_path, env, name):
    proc = run_driver(SCENE, tmp_path / name, root=ROOT, env=env, timeout=300)
    m = NOTE.search(proc.stdout)
    return m.group(1) if m else None


def test_note_as_blas_core_says(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_CORETYPE"}
    want = blas_core_export(env)
    print(f"tools/blas_core.py names: {want}")
    assert note(tmp_path, env, "own_pick") == want
    named = dict(env, OPENBLAS_CORETYPE=want or "Prescott")   # Prescott (SSE3) runs on every x86-64
    assert blas_core_export(named) is None and note(tmp_path, named, "named") is None
