#!/usr/bin/env bash
# Instructions per UMAT call (valgrind callgrind): deterministic, unlike times on a shared machine.
# The count of a run with 2N calls minus that with N calls, divided by N, removes start-up costs.
# Usage: bench/instructions_per_call.sh [N] [BENCH]   (BENCH: a build of bench/umat_bench.f90, by default
#        build/bench/umat_bench; prints: case, NTENS 6 and 4 together, instructions per call)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
n=${1:-10000}
exe=${2:-build/bench/umat_bench}
out=$(mktemp)
trap 'rm -f "$out"' EXIT
count() {
  valgrind --tool=callgrind --callgrind-out-file="$out" "$exe" "$1" 1 "$2" > /dev/null 2>&1
  callgrind_annotate "$out" 2> /dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}'
}
for kind in elastic vp ri; do
  a=$(count "$n" "$kind"); b=$(count $((2 * n)) "$kind")
  # each run calls NTENS 6 and NTENS 4: 2 n calls per n
  echo "$kind $(( (b - a) / (2 * n) ))"
done
