#!/usr/bin/env bash
# UMAT speed benchmark (CPU time per call; docs/performance.md, "UMAT: time per call"). Three builds of
# the same routine:
#   library    build/umat/libcamclay9.a, as the driver and C hosts link it: the material of the last
#              PROPS is kept per thread (ccix_material_cache, compiled with OpenMP: thread-local storage);
#   host file  build/umat/camclay9_umat.f90 compiled with a host's plain line (gfortran -O2 -fPIC, no
#              OpenMP): no module state, the material is derived from PROPS in every call (the flags
#              docs/umat.md recommends, and the cost of each: bench/umat_build_routes.sh);
#   no cache   the same file compiled with the library's flags (-O3 -funroll-loops -fPIC, no OpenMP): the
#              library as it would be without its cache, for deciding whether the cache is worth keeping.
# With --against REV, the UMAT of git revision REV is built in a scratch folder and measured the same
# way (library and host file, before/after). The builds take turns, one repetition each, so that the
# load of a shared machine falls on all of them alike; the times are medians over the repetitions.
# Instruction counts (valgrind, when installed) are deterministic. Writes the section of
# docs/performance.md.
# Usage: bench/run_umat_bench.sh [calls_per_repetition] [repetitions] [--against REV]
#        (long: run it under nice -n 10 on a shared machine)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
against=""
args=()
while [ $# -gt 0 ]; do
  case $1 in
    --against) against=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
calls=${args[0]:-100000}
reps=${args[1]:-9}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j 2 --target umat_bench camclay9_single_files > /dev/null
fflags=(-O3 -funroll-loops)   # the project's Release flags, for the benchmark program itself

# file_bench DIR SOURCE FLAGS...: the benchmark linked with SOURCE compiled with FLAGS.
file_bench() {
  local dir=$1 src=$2
  shift 2
  mkdir -p "$dir"
  gfortran "$@" -c "$src" -o "$dir/umat.o" -J "$dir" 2> /dev/null
  gfortran "${fflags[@]}" bench/umat_bench.f90 "$dir/umat.o" -o "$dir/umat_bench" -J "$dir"
}
file_bench "$work/after_host" build/umat/camclay9_umat.f90 -O2 -fPIC
file_bench "$work/after_nocache" build/umat/camclay9_umat.f90 "${fflags[@]}" -fPIC
labels=(after_lib after_host after_nocache)
exes=(build/bench/umat_bench "$work/after_host/umat_bench" "$work/after_nocache/umat_bench")
if [ -n "$against" ]; then
  rev=$(git rev-parse --short "$against")
  mkdir -p "$work/rev"
  git archive "$against" umat | tar -x -C "$work/rev"
  cmake -S "$work/rev/umat" -B "$work/rev/build" -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF > /dev/null
  cmake --build "$work/rev/build" -j 2 > /dev/null 2>&1
  mkdir -p "$work/before_lib"
  gfortran "${fflags[@]}" bench/umat_bench.f90 "$work/rev/build/libcamclay9.a" -o "$work/before_lib/umat_bench" \
    -J "$work/before_lib"
  file_bench "$work/before_host" "$work/rev/build/camclay9_umat.f90" -O2 -fPIC
  labels=(before_lib after_lib before_host after_host after_nocache)
  exes=("$work/before_lib/umat_bench" build/bench/umat_bench "$work/before_host/umat_bench"
        "$work/after_host/umat_bench" "$work/after_nocache/umat_bench")
fi

# Each run of a build: one repetition, rows "case|NTENS|ns per call|iterations".
for ((r = 1; r <= reps; r++)); do
  echo "repetition $r of $reps (${#labels[@]} builds, $calls calls per case)" >&2
  for i in "${!labels[@]}"; do
    "${exes[$i]}" "$calls" 1 | awk -F'|' 'NR > 2 {gsub(/^ +| +$/, "", $2); gsub(/ /, "", $3); gsub(/ /, "", $4);
      gsub(/ /, "", $6); print $2 "|" $3 "|" $4 "|" $6}' >> "$work/${labels[$i]}.runs"
  done
done
# Per build and case: "case|NTENS|median|min - max|iterations", in the benchmark's order of cases.
for l in "${labels[@]}"; do
  python3 - "$work/$l.runs" > "$work/$l.txt" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    case, ntens, t, it = line.rstrip("\n").split("|")
    rows.setdefault((case, ntens), ([], it))[0].append(float(t))
for (case, ntens), (ts, it) in rows.items():
    print(f"{case}|{ntens}|{statistics.median(ts):.1f}|{min(ts):.1f} - {max(ts):.1f}|{it}")
PY
done

# The table: one row per case, the builds side by side.
if [ -n "$against" ]; then
  head='| case | NTENS | library before | library after | change | host file before | host file after | change | library without cache | no cache / library | local iterations |'
  rule='|---|---|---|---|---|---|---|---|---|---|---|'
  table=$(paste -d'|' "$work/before_lib.txt" "$work/after_lib.txt" "$work/before_host.txt" "$work/after_host.txt" \
          "$work/after_nocache.txt" |
    awk -F'|' '{printf "| %s | %s | %.0f (%s) | %.0f (%s) | %+.1f %% | %.0f (%s) | %.0f (%s) | %+.1f %% | %.0f (%s) | %.2f | %s |\n",
      $1, $2, $3, $4, $8, $9, 100 * ($8 / $3 - 1), $13, $14, $18, $19, 100 * ($18 / $13 - 1), $23, $24, $23 / $8, $5}')
else
  head='| case | NTENS | library | host file | library without cache | no cache / library | local iterations |'
  rule='|---|---|---|---|---|---|---|'
  table=$(paste -d'|' "$work/after_lib.txt" "$work/after_host.txt" "$work/after_nocache.txt" |
    awk -F'|' '{printf "| %s | %s | %.0f (%s) | %.0f (%s) | %.0f (%s) | %.2f | %s |\n", $1, $2, $3, $4, $8, $9,
      $13, $14, $13 / $3, $5}')
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
      name["after_host"] = "host file"; name["after_nocache"] = "library without cache";
      if (nb == 5) {name["after_lib"] = "library after"; name["after_host"] = "host file after"}
      h = "| case |"; r = "|---|"; for (j = 1; j <= nb; j++) {h = h " " name[builds[j]] " |"; r = r "---|"}
      print h; print r
      for (k = 1; k <= nk; k++) {l = "| " kinds[k] " |"; for (j = 1; j <= nb; j++) l = l " " v[builds[j] " " kinds[k]] " |"; print l}
    }')
  echo "$instructions"
fi

# Accuracy in the same run: the host file against the numbers stored from the Jacobi derivation
# (tests/umat/test_against_jacobi.f90; 64 calls, relative differences per group).
gfortran -O2 tests/umat/test_against_jacobi.f90 "$work/after_host/umat.o" -o "$work/against_jacobi" -J "$work/after_host"
accuracy=$("$work/against_jacobi" check tests/umat/data/jacobi_reference.txt | sed -n '2,9p' |
  awk '{v = $NF; $NF = ""; sub(/ +$/, ""); sub(/^ +/, ""); printf "%s%s %s", (NR > 1 ? ", " : ""), $0, v}')

# The figures of the summary: the viscoplastic and elastic cases, NTENS 6.
t() { awk -F'|' -v c="$2" '$1 ~ "^" c && $2 == 6 {print $3}' "$work/$1.txt"; }
pct() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%+.0f %%", 100 * (a / b - 1)}'; }
summary="Without its cache the library would take $(pct "$(t after_nocache viscoplastic)" "$(t after_lib viscoplastic)")
per viscoplastic and $(pct "$(t after_nocache elastic)" "$(t after_lib elastic)") per elastic call (NTENS 6, medians above),
so it keeps the cache."
if [ -n "$against" ]; then
  summary="Against \`$rev\`, the host file takes $(pct "$(t after_host viscoplastic)" "$(t before_host viscoplastic)")
per viscoplastic and $(pct "$(t after_host elastic)" "$(t before_host elastic)") per elastic call (its material was
kept in module variables, shared by threads), the library $(pct "$(t after_lib viscoplastic)" "$(t before_lib viscoplastic)")
and $(pct "$(t after_lib elastic)" "$(t before_lib elastic)"). $summary"
fi
meaning=$(fmt -w 104 <<TXT
**What it means.** A host file derives its material in every call: the checks of PROPS, the bedding
normal and Walpole's basis of it, the Walpole coefficients of both frames (ccix_walpole), and, only in
a step that yields, the closed-form diagonalisation of the frame's pencil (H, C^-1) (ccix_pencil). This
replaced a 6 x 6 Cholesky, Jacobi and inverses that cost 4.4-4.7 us per material (\`a309f2a\`: 5698 ns
per viscoplastic and 4570 ns per elastic call in the host file). $summary The library's cache
now also holds what a call would otherwise derive on demand (both frames' pencils and stiffness
matrices, Cbar's DDSDDE: \`material_prepare\`), computed by the same routines: library, object and host
files give the same numbers bit for bit (\`umat.host_against_jacobi\`).
TXT
)
accuracy_text=$(fmt -w 104 <<TXT
Accuracy, measured in the same run: the host file against the UMAT with the Jacobi derivation
(\`a309f2a\`, numbers stored in tests/umat/data/jacobi_reference.txt; 64 calls, phi 0, 0.5, 1, NTENS 4
and 6, inclined normals; largest difference relative to each group): $accuracy.
TXT
)
cpu=$(lscpu | sed -n 's/^Model name: *//p' | head -1)
fc=$(gfortran --version | head -1)
compare=""
if [ -n "$against" ]; then
  compare="*Before*: the UMAT of revision \`$rev\`, built and measured by the same script (\`--against $against\`)."
fi
section=$(cat <<MD
## UMAT: time per call

Command: \`nice -n 10 bench/run_umat_bench.sh $calls $reps${against:+ --against $against}\` ($reps repetitions of
$calls calls per case and build; the builds take turns, one repetition each; CPU time (\`cpu_time\`),
median and range of the per-call time in ns over the repetitions). Machine: $cpu, $(nproc) cores, shared
with other jobs. Compiler: $fc. Measured $(date -u +%Y-%m-%d).

Three builds of the same routine. *Library*: \`libcamclay9.a\` as the driver and C hosts link it
(\`-O3 -funroll-loops\`, the default Release build): each thread keeps the material of the last PROPS it
saw (ccix_material_cache, compiled with OpenMP into thread-local storage), as does \`camclay9_umat.o\`.
*Host file*: \`camclay9_umat.f90\` compiled with a host's plain line (\`gfortran -O2 -fPIC\`, no
OpenMP flag; docs/umat.md, "Cost of each build route", for other flags): it keeps no module state, so that no host flag can make threads share it, and derives
the material from PROPS in every call. *Library without cache*: the same file compiled with the
library's flags, the library as it would be without its cache.
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

$meaning

$accuracy_text

Goals of issue #2: <= 1 us per viscoplastic call and <= 0.1 us per elastic call (library).
MD
)
echo "$section" | python3 bench/performance_doc.py "## UMAT: time per call"
echo "written: docs/performance.md"
