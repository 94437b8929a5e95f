#!/usr/bin/env bash
# Install what is missing, build, and run the main job.
#
# The main job is the triaxial creep scene (scenes.md §5). Until the FE driver runs the cylinder
# (issue #4: `driver -input input/triaxial.yaml`), this runs the scene's one-point twin with the same
# driver: both frames at -35 MPa, confinement held to steady state, then sigma_d = 40 MPa for 10 h, at
# theta = 0 and 90 deg; plots in out/point/, creep printed beside the paper's Lomnitz fits (Yin et al.
# 2021, Fig. 17; natural logarithm).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)" > /dev/null
for theta in 0 90; do
  build/bin/driver -input "input/point/triaxial_creep_theta$theta.yaml"
  python3 post/point_plots.py "out/point/triaxial_creep_theta$theta"
done
python3 - <<'PY'
import json, math
import numpy as np
fits = {0: (9.97e-5, 385.0), 90: (6.74e-5, 364.0)}    # Yin et al. 2021, Fig. 17
print(f"{'theta':>5} {'t [s]':>8} {'creep (point)':>14} {'paper fit':>10}")
for theta, (B, tau) in fits.items():
    d = f"out/point/triaxial_creep_theta{theta}"
    h = np.genfromtxt(f"{d}/history.csv", delimiter=",", names=True)
    rows = np.where(h["segment"] == 1)[0]
    t = h["time"][rows] - h["time"][rows[0]]
    eps = -(h["eps_33"][rows] - h["eps_33"][rows[0]])
    fit = json.load(open(f"{d}/creep_fit.json"))
    for tt in (385, 3600, 36000):
        print(f"{theta:>5} {tt:>8} {np.interp(tt, t, eps):>14.3e} {B * math.log(1 + tt / tau):>10.3e}")
    print(f"      Lomnitz fit of the point: {json.dumps(fit)}")
PY
