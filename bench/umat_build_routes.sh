#!/usr/bin/env bash
# The cost of each way to build the UMAT (issue 34; docs/umat.md, "Which file for which host"): the
# project's UMAT benchmark (bench/umat_bench.f90) linked with
#   library     build/umat/libcamclay9.a (-O3 -funroll-loops, the per-thread material cache)
#   and the host file build/umat/camclay9_umat.f90 compiled by gfortran with each flag set of ROUTES
#   below (no OpenMP: the material is derived in every call), the first a host's plain line,
#   "gfortran -O2 -fPIC". The numbers are in docs/umat.md, "Cost of each build route".
# Per route, elastic and viscoplastic calls (NTENS 6 and 4): CPU time per call, median and range over
# REPS repetitions of CALLS calls (the routes take turns, one repetition each, so that the load of a
# shared machine falls on all alike), and instructions per call (valgrind callgrind,
# bench/instructions_per_call.sh: deterministic). Prints a Markdown table and the ratios to the library.
# Usage: bench/umat_build_routes.sh [calls_per_repetition] [repetitions]   (under nice -n 10)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
calls=${1:-100000}
reps=${2:-15}
routes=("-O2 -fPIC"
        "-O3 -fPIC"
        "-O3 -funroll-loops -fPIC"
        "-O2 -fPIC -fno-semantic-interposition"
        "-O3 -fPIC -fno-semantic-interposition"
        "-O3 -funroll-loops -fPIC -fno-semantic-interposition")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target umat_bench camclay9_single_files > /dev/null
labels=("library")
exes=(build/bench/umat_bench)
for i in "${!routes[@]}"; do
  d=$work/r$i
  mkdir -p "$d"
  # shellcheck disable=SC2086  # the flags are words
  gfortran ${routes[$i]} -c build/umat/camclay9_umat.f90 -o "$d/umat.o" -J "$d" 2> /dev/null
  gfortran -O3 -funroll-loops bench/umat_bench.f90 "$d/umat.o" -o "$d/umat_bench" -J "$d"
  labels+=("host file, gfortran ${routes[$i]}")
  exes+=("$d/umat_bench")
done

for ((r = 1; r <= reps; r++)); do
  echo "repetition $r of $reps (${#exes[@]} builds, $calls calls per case)" >&2
  for i in "${!exes[@]}"; do
    for kind in elastic vp; do
      "${exes[$i]}" "$calls" 1 "$kind" | awk -F'|' -v b="$i" -v k="$kind" \
        'NR > 2 {gsub(/ /, "", $3); gsub(/ /, "", $4); print b, k, $3, $4}' >> "$work/runs"
    done
  done
done
for i in "${!exes[@]}"; do
  echo "instructions: ${labels[$i]}" >&2
  bench/instructions_per_call.sh 2000 "${exes[$i]}" | awk -v b="$i" '$1 != "ri" {print b, $1, $2}' >> "$work/instr"
done

python3 - "$work/runs" "$work/instr" "${labels[@]}" <<'PY'
import collections, statistics, sys
runs, instr, labels = sys.argv[1], sys.argv[2], sys.argv[3:]
t = collections.defaultdict(list)
for line in open(runs):
    b, k, nt, ns = line.split()
    t[(int(b), k, nt)].append(float(ns))
ins = {(int(b), k): int(n) for b, k, n in (l.split() for l in open(instr))}
med = {key: statistics.median(v) for key, v in t.items()}
print("| build | elastic: ns per call, NTENS 6 / 4 | instructions | viscoplastic: ns per call, NTENS 6 / 4 | instructions |")
print("|---|---|---|---|---|")
for b, name in enumerate(labels):
    cells = []
    for k in ("elastic", "vp"):
        ts = " / ".join(f"{med[(b, k, nt)]:.0f} ({min(t[(b, k, nt)]):.0f}-{max(t[(b, k, nt)]):.0f})" for nt in ("6", "4"))
        rel = "" if b == 0 else " ({:+.0f} %)".format(100 * (sum(med[(b, k, nt)] for nt in "64") /
                                                        sum(med[(0, k, nt)] for nt in "64") - 1))
        irel = "" if b == 0 else f" ({100 * (ins[(b, k)] / ins[(0, k)] - 1):+.0f} %)"
        cells += [ts + rel, f"{ins[(b, k)]}{irel}"]
    print(f"| {name} | " + " | ".join(cells) + " |")
PY
