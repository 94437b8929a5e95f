#!/usr/bin/env bash
# Install what is missing, build, and run the main job.
#
# The main job: the triaxial creep cylinder (Yin, Liu & Borja 2021 §5), `driver -input input/triaxial.yaml`, with
# its plots (creep curve and Lomnitz fit beside the paper's; per-frame statistics) in out/triaxial_theta0/.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)" > /dev/null
mpiexec --allow-run-as-root --oversubscribe -n 2 build/bin/driver -input input/triaxial.yaml
python3 post/triaxial_plots.py out/triaxial_theta0 --theta 0
