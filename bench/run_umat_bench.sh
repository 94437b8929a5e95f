#!/usr/bin/env bash
# UMAT speed benchmark (CPU time per call; docs/performance.md, "UMAT: time per call"). Two builds of
# the same routine:
#   library    build/umat/libcamclay9.a, as the driver and C hosts link it: the material of the last
#              PROPS is kept per thread (ccix_material_cache, compiled with OpenMP: thread-local storage);
#   host file  build/umat/camclay9_umat.f90 compiled as docs/umat.md tells a host (gfortran -O2 -fPIC, no
#              OpenMP): no module state, the material is derived from PROPS in every call.
# With --against REV, the UMAT of git revision REV is built in a scratch folder and measured the same
# way (before/after). Instruction counts (valgrind, when installed) are deterministic; the times are
# medians over the repetitions on a shared machine. Writes the section of docs/performance.md.
# Usage: bench/run_umat_bench.sh [calls_per_repetition] [repetitions] [--against REV]
#        (long: run it under nice -n 10 on a shared machine)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
repo=$(pwd)
against=""
args=()
while [ $# -gt 0 ]; do
  case $1 in
    --against) against=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
calls=${args[0]:-200000}
reps=${args[1]:-9}
host_calls=$((calls / 5))   # the host file is ~6x slower per call: fewer calls, the same repetitions
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target umat_bench camclay9_single_files > /dev/null
fflags=(-O3 -funroll-loops)   # the project's Release flags, for the benchmark program itself

# host_bench DIR SOURCE: the benchmark linked with SOURCE compiled as a host compiles it.
host_bench() {
  mkdir -p "$1"
  gfortran -O2 -fPIC -c "$2" -o "$1/umat.o" -J "$1" 2> /dev/null
  gfortran "${fflags[@]}" bench/umat_bench.f90 "$1/umat.o" -o "$1/umat_bench" -J "$1"
}
host_bench "$work/after_host" build/umat/camclay9_umat.f90
labels=(after_lib after_host)
exes=(build/bench/umat_bench "$work/after_host/umat_bench")
if [ -n "$against" ]; then
  rev=$(git rev-parse --short "$against")
  mkdir -p "$work/rev"
  git archive "$against" umat | tar -x -C "$work/rev"
  cmake -S "$work/rev/umat" -B "$work/rev/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF > /dev/null
  cmake --build "$work/rev/build" -j 2 > /dev/null 2>&1
  mkdir -p "$work/before_lib"
  gfortran "${fflags[@]}" bench/umat_bench.f90 "$work/rev/build/libcamclay9.a" -o "$work/before_lib/umat_bench" \
    -J "$work/before_lib"
  host_bench "$work/before_host" "$work/rev/build/camclay9_umat.f90"
  labels=(before_lib after_lib before_host after_host)
  exes=("$work/before_lib/umat_bench" build/bench/umat_bench "$work/before_host/umat_bench" "$work/after_host/umat_bench")
fi

# Each run: "case|NTENS|median|min - max|iterations" rows.
for i in "${!labels[@]}"; do
  n=$calls; [[ ${labels[$i]} == *host ]] && n=$host_calls
  echo "running ${labels[$i]} ($n calls x $reps repetitions)" >&2
  "${exes[$i]}" "$n" "$reps" | awk -F'|' 'NR > 2 {gsub(/^ +| +$/, "", $2); gsub(/ /, "", $3); gsub(/^ +| +$/, "", $4);
    gsub(/^ +| +$/, "", $5); gsub(/ +/, " ", $5); gsub(/ /, "", $6); print $2 "|" $3 "|" $4 "|" $5 "|" $6}' > "$work/${labels[$i]}.txt"
done

# The table: one row per case, the builds side by side.
if [ -n "$against" ]; then
  head='| case | NTENS | library before | library after | change | host file before | host file after | change | host file / library, after | local iterations |'
  rule='|---|---|---|---|---|---|---|---|---|---|'
  table=$(paste -d'|' "$work/before_lib.txt" "$work/after_lib.txt" "$work/before_host.txt" "$work/after_host.txt" |
    awk -F'|' '{printf "| %s | %s | %.0f (%s) | %.0f (%s) | %+.1f %% | %.0f (%s) | %.0f (%s) | %+.0f %% | %.2f | %s |\n",
      $1, $2, $3, $4, $8, $9, 100 * ($8 / $3 - 1), $13, $14, $18, $19, 100 * ($18 / $13 - 1), $18 / $8, $5}')
else
  head='| case | NTENS | library | host file | host file / library | local iterations |'
  rule='|---|---|---|---|---|---|'
  table=$(paste -d'|' "$work/after_lib.txt" "$work/after_host.txt" |
    awk -F'|' '{printf "| %s | %s | %.0f (%s) | %.0f (%s) | %.2f | %s |\n", $1, $2, $3, $4, $8, $9, $8 / $3, $5}')
fi
table=$(printf '%s\n%s\n%s' "$head" "$rule" "$table")
echo "$table"

instructions="(valgrind not installed: no instruction counts)"
if command -v valgrind > /dev/null; then
  rows=""
  for i in "${!labels[@]}"; do
    rows+=$(bench/instructions_per_call.sh 2000 "${exes[$i]}" | awk -v b="${labels[$i]}" '{print b, $0}')$'\n'
  done
  instructions=$(echo -n "$rows" | awk '
    {v[$1 " " $2] = $3; if (!($2 in seen)) {seen[$2] = 1; kinds[++nk] = $2}; if (!($1 in sb)) {sb[$1] = 1; builds[++nb] = $1}}
    END {
      name["before_lib"] = "library before"; name["after_lib"] = "library"; name["before_host"] = "host file before";
      name["after_host"] = "host file";
      if (nb == 4) name["after_lib"] = "library after"; if (nb == 4) name["after_host"] = "host file after";
      h = "| case |"; r = "|---|"; for (j = 1; j <= nb; j++) {h = h " " name[builds[j]] " |"; r = r "---|"}
      print h; print r
      for (k = 1; k <= nk; k++) {l = "| " kinds[k] " |"; for (j = 1; j <= nb; j++) l = l " " v[builds[j] " " kinds[k]] " |"; print l}
    }')
  echo "$instructions"
fi

# The price of deriving the material per call, in the viscoplastic case (NTENS 6).
vp() { awk -F'|' '$1 ~ /^viscoplastic/ && $2 == 6 {print $3}' "$work/$1.txt"; }
if [ -n "$against" ]; then
  price=$(awk -v a="$(vp after_host)" -v b="$(vp before_host)" -v l="$(vp after_lib)" 'BEGIN {
    printf "%.1f us per viscoplastic call (the host file after minus before: the same compiler flags, the\nmaterial derived in every call against a kept one), %.1f times the library'"'"'s whole viscoplastic call", (a - b) / 1000, (a - b) / l}')
else
  price=$(awk -v a="$(vp after_host)" -v l="$(vp after_lib)" 'BEGIN {
    printf "about %.1f us per viscoplastic call (host file minus library; their flags differ), %.1f times\nthe library'"'"'s whole viscoplastic call", (a - l) / 1000, (a - l) / l}')
fi
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
fc=$(gfortran --version | head -1)
compare=""
if [ -n "$against" ]; then
  compare="Before: the UMAT of revision \`$rev\`, built and measured by the same script (\`--against $against\`).
Its host file kept the material of the last PROPS in module variables, compiled without OpenMP: fast,
but shared by every thread of the host (wrong results with several threads and materials, issue 21)."
fi
section=$(cat <<MD
## UMAT: time per call

Command: \`nice -n 10 bench/run_umat_bench.sh $calls $reps${against:+ --against $against}\` ($reps repetitions of
$calls calls each for the library, $host_calls for the host file; CPU time (\`cpu_time\`), median and range
of the per-call time in ns over the repetitions). Machine: $cpu, $(nproc) cores, shared with other
jobs. Compiler: $fc. Measured $(date -u +%Y-%m-%d).

Two builds of the same routine. *Library*: \`libcamclay9.a\` as the driver and C hosts link it
(\`-O3 -funroll-loops\`, the default Release build): each thread keeps the material of the last PROPS it
saw (ccix_material_cache, compiled with OpenMP into thread-local storage), as does \`camclay9_umat.o\`.
*Host file*: \`camclay9_umat.f90\` compiled as docs/umat.md tells a host (\`gfortran -O2 -fPIC\`, no
OpenMP flag): it keeps no module state, so that no host flag can make threads share it, and derives
the material from PROPS (stiffness, projection tensor, their simultaneous diagonalisation) in every
call. The ratio of the two is the price of deriving per call.
$compare

Each case starts every call from the same state and cycles through 64 strain increments of
~1e-5 (elastic: ~1e-6): *elastic*, both frames inside their surfaces (pc = 60 MPa at -35 MPa);
*viscoplastic*, the paper's start (hard frame far outside with pc0 = 2 MPa, soft frame on its
surface), Woodford viscosities, dt = 10 s; *rate-independent*, eta = 0 in both frames. Plane strain
is NTENS = 4 with the normal in the 1-2 plane. Local iterations are Newton updates of the worse frame.

$table

Instructions per call (valgrind callgrind, \`bench/instructions_per_call.sh\`; deterministic, the
same whatever else the machine is doing; mean of NTENS 6 and 4; elastic / vp / ri as above):

$instructions

**What it means (issue 21).** Deriving the material per call costs $price. Issue 21 allowed 10 %: out of
reach without a cache. And a cache that is correct whatever flags a host compiles with needs storage
of one thread, which standard Fortran does not have: without OpenMP a module variable is shared by the
host's threads (the race of issue 21), and flags such as \`-fopenmp-simd\` compile the OpenMP sentinel
lines while ignoring \`threadprivate\` (docs/umat.md, "Threads"). Hence the two builds: the library and
\`camclay9_umat.o\`, compiled by this project with OpenMP, keep the material per thread at the cost of
before (library: the same time and instruction count); the files hosts compile themselves are correct
under any flags and pay the derivation. A host that wants both links \`camclay9_umat.o\` or the library.

Goals of issue #2: <= 1 us per viscoplastic call and <= 0.1 us per elastic call (library).
MD
)
echo "$section" | python3 bench/performance_doc.py "## UMAT: time per call"
echo "written: docs/performance.md"
