#!/usr/bin/env bash
# UMAT speed benchmark: builds (Release) and writes the table to docs/performance.md (UMAT section).
# Usage: bench/run_umat_bench.sh [calls_per_repetition] [repetitions]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
calls=${1:-200000}
reps=${2:-9}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j "$(nproc)" --target umat_bench > /dev/null
table=$(build/bench/umat_bench "$calls" "$reps")
echo "$table"
instructions="(valgrind not installed: no instruction counts)"
if command -v valgrind > /dev/null; then
  instructions=$(bench/instructions_per_call.sh 5000 | awk 'BEGIN {print "| case | instructions per call |"; print "|---|---|"} {print "| " $1 " | " $2 " |"}')
  echo "$instructions"
fi
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
fc=$(gfortran --version | head -1)
out=docs/performance.md
section=$(cat <<MD
## UMAT: time per call

Command: \`bench/run_umat_bench.sh $calls $reps\` ($reps repetitions of $calls calls each; median and
range of the per-call time over the repetitions). Machine: $cpu, $(nproc) cores, shared and noisy.
Compiler: $fc, \`-O3 -funroll-loops\` (the default Release build; no \`-march=native\`). Measured
$(date -u +%Y-%m-%d).

Each case starts every call from the same state and cycles through 64 strain increments of
~1e-5 (elastic: ~1e-6): *elastic*, both frames inside their surfaces (pc = 60 MPa at -35 MPa);
*viscoplastic*, the paper's start (hard frame far outside with pc0 = 2 MPa, soft frame on its
surface), Woodford viscosities, dt = 10 s; *rate-independent*, eta = 0 in both frames. Plane strain
is NTENS = 4 with the normal in the 1-2 plane. Local iterations are Newton updates of the worse frame.

$table

Instructions per call (valgrind callgrind, \`bench/instructions_per_call.sh\`; deterministic, the
same whatever else the machine is doing; mean of NTENS 6 and 4; elastic / vp / ri as above):

$instructions

Goals of issue #2: <= 1 us per viscoplastic call and <= 0.1 us per elastic call.
MD
)
echo "$section" | python3 bench/performance_doc.py "## UMAT: time per call"
echo "written: $out"
