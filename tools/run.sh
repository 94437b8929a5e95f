#!/usr/bin/env bash
# Install what is missing, build, and run the main job.
#
# The main job is the triaxial creep scene (scenes.md §5). Until the FE driver lands (issue #4:
# `driver -input input/triaxial.yaml`), this runs its one-point twin through the UMAT: both frames
# at -35 MPa, confinement held 1e6 s, then sigma_d = 40 MPa; creep for 10 h at theta = 0 and 90 deg,
# printed beside the paper's Lomnitz fits (Yin et al. 2021, Fig. 17; natural logarithm).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)" > /dev/null
exe=build/tests/umat/creep_point
printf '%-8s %10s %16s %16s\n' theta 't [s]' 'creep (point)' 'paper fit'
for theta in 0 90; do
  if [ "$theta" = 0 ]; then B=9.97e-5; tau=385; else B=6.74e-5; tau=364; fi
  for t in 385 3600 36000; do
    creep=$("$exe" "$theta" "$t" 2000 1.003 1e6 | awk '{printf "%.3e", -$3}')
    fit=$(python3 -c "import math; print(f'{$B*math.log(1+$t/$tau):.3e}')")
    printf '%-8s %10s %16s %16s\n' "$theta" "$t" "$creep" "$fit"
  done
done
