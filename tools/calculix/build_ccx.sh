#!/usr/bin/env bash
# Build CalculiX 2.20 from Debian's source package with this project's UMAT as its Abaqus user
# material (issue #6). No CalculiX code or binary enters this repository: the source package is
# fetched with apt-get and built in a cache outside the source tree, so later runs skip the compile.
#
# usage: tools/calculix/build_ccx.sh [UMAT_OBJECT]
#   UMAT_OBJECT defaults to camclay9_umat.o of a build: $CAMCLAY9_BUILD/umat/ or $CAMCLAY9_BUILD/ when
#   CAMCLAY9_BUILD is set, else build/umat/ (the whole project) or build-umat/ (the UMAT alone,
#   cmake -S umat -B build-umat).
# Prints the directory holding the executables on the last line of stdout ($cache/bin/<hash of the
# object>/, one per object, so that concurrent checkouts never share or relink one):
#   ccx_camclay9        CalculiX with camclay9_umat.o placed before ccx_2.20.a (replaces the stub umat)
#   ccx_camclay9_trace  the same, with umat_trace.f90 in front: logs every UMAT call (see that file)
# Exit 77 (with the reason on stderr) when CalculiX cannot be had here: the tests then skip.
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
if [ $# -ge 1 ]; then
  candidates=("$1")
elif [ -n "${CAMCLAY9_BUILD:-}" ]; then
  candidates=("$CAMCLAY9_BUILD/umat/camclay9_umat.o" "$CAMCLAY9_BUILD/camclay9_umat.o")
else
  candidates=("$repo/build/umat/camclay9_umat.o" "$repo/build-umat/camclay9_umat.o")
fi
umat_obj=""
for c in "${candidates[@]}"; do
  if [ -f "$c" ]; then umat_obj=$c; break; fi
done
cache=${XDG_CACHE_HOME:-$HOME/.cache}/camclay9/calculix
suite=bookworm           # the Debian release that carries calculix-ccx 2.20
ccx=ccx_2.20
skip() { echo "build_ccx: cannot build CalculiX: $*" >&2; exit 77; }
log() { echo "build_ccx: $*" >&2; }

[ -n "$umat_obj" ] || { echo "build_ccx: no UMAT object: looked for ${candidates[*]} (build the project, or only the UMAT: cmake -S umat -B build-umat && cmake --build build-umat)" >&2; exit 2; }
umat_obj=$(realpath "$umat_obj")
for tool in gfortran gcc make objcopy flock sha256sum; do
  command -v $tool >/dev/null || skip "$tool is not installed"
done
mkdir -p "$cache/bin"
exec 9>"$cache/.lock"
flock 9                  # one build at a time (ctest -j, two shells)

src="$cache/src/calculix-ccx-2.20/$ccx/src"
if [ ! -f "$cache/archive.ok" ]; then
  t0=$(date +%s)
  # A private sources list and lists folder: the system's apt lists are not touched. The archive's
  # address is taken from the system's own apt configuration (the entry serving $suite).
  command -v apt-get >/dev/null && command -v dpkg-source >/dev/null ||
    skip "apt-get/dpkg-source not available (not Debian?)"
  uri=${CAMCLAY9_DEBIAN_URI:-$(apt-get indextargets --format '$(REPO_URI) $(RELEASE) $(TARGET_OF)' 2>/dev/null |
                               awk -v s="$suite" '$2 == s && $3 == "deb" {print $1; exit}')}
  [ -n "$uri" ] || skip "no apt entry for Debian $suite in this system's configuration (set CAMCLAY9_DEBIAN_URI)"
  key=/usr/share/keyrings/debian-archive-keyring.gpg
  opt=""; [ -f $key ] && opt="[signed-by=$key] "
  mkdir -p "$cache/apt/lists/partial" "$cache/apt/parts" "$cache/src"
  printf 'deb %s%s %s main\ndeb-src %s%s %s main\n' "$opt" "$uri" $suite "$opt" "$uri" $suite > "$cache/apt/sources.list"
  apt=(apt-get -q -o Dir::Etc::SourceList="$cache/apt/sources.list" -o Dir::Etc::SourceParts="$cache/apt/parts"
       -o Dir::State::Lists="$cache/apt/lists")
  log "apt-get update (private lists in $cache/apt)"
  "${apt[@]}" update >"$cache/apt.log" 2>&1 || true     # apt-get update warns, and exits 0, on fetch errors
  compgen -G "$cache/apt/lists/*_source_Sources*" >/dev/null ||
    skip "apt-get update could not fetch Debian's source index for $suite ($(grep -m1 -E '^(E|W):' "$cache/apt.log"))"

  # Build dependencies by name (apt-get build-dep does not work with a private list).
  deps=(libarpack2-dev libspooles-dev liblapack-dev libblas-dev)
  missing=()
  for p in "${deps[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    [ "$(id -u)" -eq 0 ] || skip "build dependencies missing (${missing[*]}) and not root to install them"
    log "installing ${missing[*]}"
    DEBIAN_FRONTEND=noninteractive "${apt[@]}" install -y --no-install-recommends "${missing[@]}" \
      >>"$cache/apt.log" 2>&1 || skip "could not install ${missing[*]} (see $cache/apt.log)"
  fi

  log "apt-get source calculix-ccx"
  rm -rf "$cache/src" && mkdir -p "$cache/src"
  (cd "$cache/src" && "${apt[@]}" source calculix-ccx >>"$cache/apt.log" 2>&1) ||
    skip "apt-get source calculix-ccx failed (see $cache/apt.log)"
  [ -f "$src/Makefile" ] || skip "unexpected source layout: no $src/Makefile"

  # The flags of debian/rules: dpkg-buildflags with hardening=+all, plus the upstream flags there.
  export DEB_BUILD_MAINT_OPTIONS=hardening=+all
  cd "$cache/src/calculix-ccx-2.20"      # dpkg-buildflags maps the current directory to "."
  cflags="-Wall -I/usr/include/spooles -DARCH=\"Linux\" -DSPOOLES -DARPACK -DMATRIXSTORAGE -DUSE_MT=1"
  cflags="$cflags $(dpkg-buildflags --get CFLAGS) $(dpkg-buildflags --get CPPFLAGS) $(dpkg-buildflags --get LDFLAGS)"
  fflags="-fallow-argument-mismatch $(dpkg-buildflags --get FFLAGS)"
  log "make $ccx.a $ccx.o in $src (2-14 min on 2 cores, 3-4.5 min CPU, docs/calculix.md; log: $cache/make.log)"
  make -C "$src" -j "$(nproc)" CFLAGS="$cflags" FFLAGS="$fflags" $ccx.a $ccx.o >"$cache/make.log" 2>&1 ||
    { echo "build_ccx: make failed, see $cache/make.log" >&2; exit 1; }
  dpkg-buildflags --get LDFLAGS > "$cache/ldflags"
  echo "$(( $(date +%s) - t0 )) s" > "$cache/archive.ok"
  log "CalculiX objects built in $(cat "$cache/archive.ok")"
fi

# Link (cheap): the user object before ccx_2.20.a replaces the archive's stub umat. Same line as
# the Makefile's. One folder of executables per UMAT object, named by the hash of what is linked
# (the object, the trace wrapper, the archive's size and time): checkouts that test at once with
# different objects each get their own, and never relink one another's (issue 34; before, one folder
# per user was relinked whenever another checkout called this script with another object). A folder
# is complete once its "linked" file exists (written last, under the lock); folders not used for 7
# days are removed.
libs=(-lspooles -lpthread -larpack -llapack -lblas -lm -lc -fopenmp $(cat "$cache/ldflags"))
stamp=$( (cat "$umat_obj" "$here/umat_trace.f90"; stat -c '%s %Y' "$src/$ccx.a") | sha256sum | cut -c1-16)
bin="$cache/bin/$stamp"
if [ ! -f "$bin/linked" ]; then
  log "linking ccx_camclay9 and ccx_camclay9_trace with $umat_obj in $bin"
  rm -rf "$bin" && mkdir -p "$bin"
  work=$(mktemp -d)
  # The trace wrapper calls the real routine under another name: rename umat_ in a copy.
  objcopy --redefine-sym umat_=camclay9_umat_ "$umat_obj" "$work/renamed.o"
  gfortran -O2 -c "$here/umat_trace.f90" -o "$work/umat_trace.o" -J "$work"
  gfortran -Wall -O2 -o "$bin/ccx_camclay9" "$src/$ccx.o" "$umat_obj" "$src/$ccx.a" "${libs[@]}"
  gfortran -Wall -O2 -o "$bin/ccx_camclay9_trace" "$src/$ccx.o" "$work/umat_trace.o" "$work/renamed.o" \
    "$src/$ccx.a" "${libs[@]}"
  # The stub umat of ccx_2.20.a (isotropic elasticity from PROPS 1-2) must not be the one linked:
  # it would run without a word and give wrong results.
  for exe in ccx_camclay9 ccx_camclay9_trace; do
    nm "$bin/$exe" > "$work/symbols"
    grep -q ccix_mixture "$work/symbols" || { echo "build_ccx: the UMAT is not linked into $exe" >&2; exit 1; }
  done
  rm -rf "$work"
  echo "$umat_obj" > "$bin/linked"
fi
touch "$bin/linked"
find "$cache/bin" -mindepth 1 -maxdepth 1 -type d ! -newermt '7 days ago' -exec rm -rf {} + 2>/dev/null || true
echo "$bin"
