#!/bin/bash
# The 3D indentation scenes on 1 and 2 ranks (issue 25, item 6): wall, user and system seconds of each run and the
# driver's last line, into times.txt in the working directory. Usage: bench/indent_ranks.sh [driver]
set -u
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
D=${1:-$ROOT/build/bin/driver}
for s in nanoindent_kerogen_sector microindent_BN_sector microindent_BP; do
  for n in 1 2; do
    rm -rf out_${s}_$n
    /usr/bin/time -f "$s ranks $n wall %e s user %U s sys %S s" mpiexec --allow-run-as-root -n $n $D -input $ROOT/input/$s.yaml -output_dir out_${s}_$n > log_${s}_$n.txt 2>> times.txt
    tail -1 log_${s}_$n.txt | cut -c1-200 >> times.txt
  done
done
