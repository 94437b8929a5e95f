#!/usr/bin/env bash
# CTest calculix.per_object (issue 34): tools/calculix/build_ccx.sh keeps one CalculiX per UMAT object,
# so that checkouts testing at once never run or relink each other's. With the build's object A and a
# copy B that differs only by an added note section (another object to the script, the same code):
#   - A and B get different folders;
#   - linking B leaves A's executables as they were (same bytes, same modification time);
#   - calling the script with A again gives A's folder, not relinked.
# Before issue 34 the script printed one folder per user for both and relinked it for B: this fails.
# Exit 77 (skip) only when build_ccx.sh exits 77 (no CalculiX to be had here).
set -euo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
a=${CAMCLAY9_UMAT_OBJECT:?CAMCLAY9_UMAT_OBJECT: the build\'s camclay9_umat.o}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "calculix.per_object: a second object, the same code" > "$work/note"
objcopy --add-section .note.camclay9_per_object="$work/note" "$a" "$work/b.o"

build() {
  local rc=0
  bash "$repo/tools/calculix/build_ccx.sh" "$1" > "$work/out" 2> "$work/err" || rc=$?
  if [ $rc -eq 77 ]; then echo "calculix.per_object skipped: $(tail -1 "$work/err")"; exit 77; fi
  [ $rc -eq 0 ] || { cat "$work/err"; echo "calculix.per_object: build_ccx.sh $1: exit $rc"; exit 1; }
  tail -1 "$work/out"
}
fail() { echo "calculix.per_object: FAIL: $*"; exit 1; }

dir_a=$(build "$a")
sum_a=$(sha256sum < "$dir_a/ccx_camclay9")
time_a=$(stat -c %Y.%y "$dir_a/ccx_camclay9" "$dir_a/ccx_camclay9_trace")
dir_b=$(build "$work/b.o")
[ "$dir_a" != "$dir_b" ] || fail "objects A and B share the folder $dir_a"
[ -x "$dir_b/ccx_camclay9" ] && [ -x "$dir_b/ccx_camclay9_trace" ] || fail "no executables in $dir_b"
[ "$(sha256sum < "$dir_a/ccx_camclay9")" = "$sum_a" ] || fail "linking B changed A's executable"
[ "$(stat -c %Y.%y "$dir_a/ccx_camclay9" "$dir_a/ccx_camclay9_trace")" = "$time_a" ] ||
  fail "linking B touched A's executables"
[ "$(build "$a")" = "$dir_a" ] || fail "A's folder changed on a second call"
[ "$(stat -c %Y.%y "$dir_a/ccx_camclay9" "$dir_a/ccx_camclay9_trace")" = "$time_a" ] ||
  fail "A was relinked on a second call"
echo "calculix.per_object: A in $dir_a, B in $dir_b; A untouched by B and not relinked"
