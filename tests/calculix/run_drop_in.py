#!/usr/bin/env python3
"""CTest entries calculix.drop_in and calculix.same_mesh: exit 77 (CTest: skipped) only when
tools/calculix/build_ccx.sh says CalculiX cannot be had here (its exit 77); otherwise run the CalculiX cases
of test_calculix.py (or of the test file given as the first argument) with CAMCLAY9_REQUIRE_CCX=1, so that
none of them can turn into a skip, and return pytest's exit code."""
import os
import subprocess
import sys

from replay import umat_object  # beside this script: CAMCLAY9_UMAT_OBJECT, or found in the build folder

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, "..", ".."))

r = subprocess.run(["bash", os.path.join(REPO, "tools", "calculix", "build_ccx.sh"), umat_object()],
                   capture_output=True, text=True, timeout=3600)
if r.returncode == 77:
    print("calculix.drop_in skipped: " + (r.stderr.strip().splitlines() or ["build_ccx.sh exit 77"])[-1])
    sys.exit(77)
if r.returncode != 0:
    print(f"calculix.drop_in: build_ccx.sh failed (exit {r.returncode}):\n{r.stderr}")
    sys.exit(1)
env = dict(os.environ, CAMCLAY9_REQUIRE_CCX="1")
tests = [os.path.join(HERE, sys.argv[1])] if len(sys.argv) > 1 else \
    [os.path.join(HERE, "test_calculix.py"), "-k", "not test_inputs_are_generated"]
sys.exit(subprocess.run([sys.executable, "-m", "pytest", "-q", "-s", "-p", "no:cacheprovider", *tests],
                        env=env, timeout=3600).returncode)
