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
# Instruction counts (valgrind, when installed) are deterministic. Keeps every number of the section in
# docs/results/umat_time.json and writes the section of docs/performance.md from it (bench/umat_time_store.py).
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
# Instructions per call (valgrind, when installed): "label kind count" lines.
if command -v valgrind > /dev/null; then
  for i in "${!labels[@]}"; do
    bench/instructions_per_call.sh 2000 "${exes[$i]}" | awk -v b="${labels[$i]}" '{print b, $0}' >> "$work/instructions.txt"
  done
fi

# Accuracy in the same run: the host file against the numbers stored from the Jacobi derivation
# (tests/umat/test_against_jacobi.f90; 64 calls, relative differences per group).
gfortran -O2 tests/umat/test_against_jacobi.f90 "$work/after_host/umat.o" -o "$work/against_jacobi" -J "$work/after_host"
"$work/against_jacobi" check tests/umat/data/jacobi_reference.txt | sed -n '2,9p' > "$work/accuracy.txt"

# The store (every number the section prints) and the section written from it.
niceness=$(nice)
command="bench/run_umat_bench.sh $calls $reps${against:+ --against $against}"
[ "$niceness" -gt 0 ] && command="nice -n $niceness $command"
old_ifs=$IFS; IFS=,; label_list="${labels[*]}"; IFS=$old_ifs
python3 bench/umat_time_store.py "$work" --labels "$label_list" --calls "$calls" --repetitions "$reps" \
  ${against:+--against "$rev"} --command "$command" --compiler "$(gfortran --version | head -1)" \
  --machine "$(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) cores"
