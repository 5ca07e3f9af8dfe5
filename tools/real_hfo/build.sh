#!/usr/bin/env bash
# Build the real RoboCup Half Field Offense from source: LARG/HFO with the rcssserver fork (15.2.2) and the
# librcsc it is made for, pinned by default to the commits sb3-hfo was validated against.
#
# Usage: tools/real_hfo/build.sh [options] DEST
#
#   DEST                    folder to build in; the build ends up in DEST/HFO (use it as HFO_DIR)
#   --hfo-git SRC           git source of HFO        (default https://github.com/LARG/HFO)
#   --rcssserver-git SRC    git source of rcssserver (default https://github.com/mhauskn/rcssserver)
#   --librcsc-git SRC       git source of librcsc    (default https://github.com/mhauskn/librcsc)
#   --hfo-rev REV           commit of HFO to build        (default b8b2a1d)
#   --rcssserver-rev REV    commit of rcssserver to build (default 82212ee)
#   --librcsc-rev REV       commit of librcsc to build    (default d222758)
#   --jobs N                parallel compile jobs (default: $JOBS, else the number of CPUs)
#   --skip-apt              do not install the Debian/Ubuntu packages below (install them yourself)
#   -h, --help              print this help
#
# SRC is anything `git clone` takes: a URL, a local clone or a bare git directory (for machines without GitHub).
# Debian/Ubuntu packages installed with apt-get unless --skip-apt (root or sudo needed):
#   build-essential cmake git flex libfl-dev bison libboost-system-dev libboost-filesystem-dev zlib1g-dev
#   python3 iproute2 util-linux   (the last two: `ip` and `unshare` for tools/real_hfo/loopback.sh)
#
# Result (checked at the end): DEST/HFO/bin/HFO (HFO's launcher), DEST/HFO/bin/rcssserver, the agent2d NPCs in
# DEST/HFO/bin/teams/base, and the ctypes binding DEST/HFO/hfo/hfo.py with DEST/HFO/hfo/libhfo_c.so.
# About 7 CPU-minutes once the packages are in (3-4 minutes with 2 idle cores). Running it again over the same DEST
# reuses the clones and rebuilds only what changed.
set -euo pipefail

usage() { sed -n '2,/^set -euo/p' "$0" | sed -e '$d' -e 's/^# \{0,1\}//'; }
die() { echo "build.sh: $*" >&2; exit 2; }

hfo_git=https://github.com/LARG/HFO
rcssserver_git=https://github.com/mhauskn/rcssserver
librcsc_git=https://github.com/mhauskn/librcsc
hfo_rev=b8b2a1d
rcssserver_rev=82212ee
librcsc_rev=d222758
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
skip_apt=0
dest=""

while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --skip-apt) skip_apt=1; shift ;;
    --hfo-git|--rcssserver-git|--librcsc-git|--hfo-rev|--rcssserver-rev|--librcsc-rev|--jobs)
      [ $# -ge 2 ] || die "$1 needs a value"
      value=$2
      case "$1" in
        --hfo-git) hfo_git=$value ;;
        --rcssserver-git) rcssserver_git=$value ;;
        --librcsc-git) librcsc_git=$value ;;
        --hfo-rev) hfo_rev=$value ;;
        --rcssserver-rev) rcssserver_rev=$value ;;
        --librcsc-rev) librcsc_rev=$value ;;
        --jobs) jobs=$value ;;
      esac
      shift 2 ;;
    -*) die "unknown option $1 (see --help)" ;;
    *) [ -z "$dest" ] || die "one DEST only, got '$dest' and '$1'"; dest=$1; shift ;;
  esac
done
[ -n "$dest" ] || { usage >&2; exit 2; }
case "$jobs" in ''|*[!0-9]*|0) die "--jobs must be a positive integer, got '$jobs'" ;; esac

start_s=$(date +%s)
mkdir -p "$dest"
dest=$(cd "$dest" && pwd)

if [ "$skip_apt" = 0 ]; then
  sudo=""
  [ "$(id -u)" = 0 ] || sudo=sudo
  echo "== apt-get: build tools and libraries (skip with --skip-apt)"
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends \
    build-essential cmake git flex libfl-dev bison libboost-system-dev libboost-filesystem-dev zlib1g-dev \
    python3 iproute2 util-linux
fi
for tool in git cmake make g++ flex bison python3; do
  command -v "$tool" >/dev/null || die "$tool not found; install the packages listed in --help"
done
# rcssserver's coach-language lexer includes flex's C++ header, which Debian ships in libfl-dev, a package that
# `flex` only recommends (so --no-install-recommends, or a minimal image, leaves it out)
echo '#include <FlexLexer.h>' | g++ -x c++ -fsyntax-only - 2>/dev/null \
  || die "FlexLexer.h not found (rcssserver needs flex's C++ header); install libfl-dev"

# clone SRC into DEST/NAME (or reuse an existing clone) and check out REV; prints the full commit id
checkout() {
  local name=$1 src=$2 rev=$3 dir=$dest/$1
  if [ ! -d "$dir/.git" ]; then
    echo "== clone $name from $src" >&2
    git clone -q --no-checkout "$src" "$dir"
  fi
  if ! git -C "$dir" rev-parse -q --verify "$rev^{commit}" >/dev/null; then
    git -C "$dir" fetch -q "$src" || true
  fi
  git -C "$dir" rev-parse -q --verify "$rev^{commit}" >/dev/null || die "$name: no commit '$rev' in $src"
  # HFO's CMakeLists.txt is edited below; restore it so that the checkout never refuses
  git -C "$dir" checkout -q -f --detach "$rev"
  git -C "$dir" rev-parse HEAD
}
hfo_commit=$(checkout HFO "$hfo_git" "$hfo_rev")
rcssserver_commit=$(checkout rcssserver "$rcssserver_git" "$rcssserver_rev")
librcsc_commit=$(checkout librcsc "$librcsc_git" "$librcsc_rev")

# HFO's CMakeLists.txt downloads rcssserver and librcsc itself (CMake ExternalProject, GIT_REPOSITORY on GitHub,
# GIT_TAG "master"). Point both at the clones made above and at the chosen commits, so that the build uses
# exactly those and needs no network.
cmakelists=$dest/HFO/CMakeLists.txt
grep -q 'https://github.com/mhauskn/rcssserver.git' "$cmakelists" \
  && grep -q 'https://github.com/mhauskn/librcsc.git' "$cmakelists" \
  || die "HFO $hfo_commit: CMakeLists.txt does not fetch rcssserver and librcsc as expected; pick another --hfo-rev"
sed -i \
  -e "\\#GIT_REPOSITORY \"https://github.com/mhauskn/rcssserver.git\"#{s#\"https://[^\"]*\"#\"$dest/rcssserver\"#;n;s#GIT_TAG \"[^\"]*\"#GIT_TAG \"$rcssserver_commit\"#}" \
  -e "\\#GIT_REPOSITORY \"https://github.com/mhauskn/librcsc.git\"#{s#\"https://[^\"]*\"#\"$dest/librcsc\"#;n;s#GIT_TAG \"[^\"]*\"#GIT_TAG \"$librcsc_commit\"#}" \
  "$cmakelists"
grep -q "GIT_TAG \"$rcssserver_commit\"" "$cmakelists" && grep -q "GIT_TAG \"$librcsc_commit\"" "$cmakelists" \
  || die "could not pin rcssserver and librcsc in $cmakelists"

echo "== cmake + make -j$jobs (HFO ${hfo_commit:0:7}, rcssserver ${rcssserver_commit:0:7}, librcsc ${librcsc_commit:0:7})"
mkdir -p "$dest/HFO/build"
cd "$dest/HFO/build"
# no soccerwindow2 (needs Qt4) and no extra team binaries (downloaded from GitHub)
cmake -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBUILD_SOCCERWINDOW=OFF -DINSTALL_ADDITIONAL_TEAMS=OFF .. >cmake.log 2>&1 \
  || { tail -30 cmake.log >&2; die "cmake failed (full log: $dest/HFO/build/cmake.log)"; }
make -j"$jobs" >make.log 2>&1 \
  || { grep -E "error|Error" make.log | tail -30 >&2; die "make failed (full log: $dest/HFO/build/make.log)"; }
make install >>make.log 2>&1 || { tail -30 make.log >&2; die "make install failed"; }

hfo_dir=$dest/HFO
for file in bin/HFO bin/rcssserver bin/teams/base/agent bin/teams/base/sample_player hfo/hfo.py hfo/libhfo_c.so; do
  [ -e "$hfo_dir/$file" ] || die "the build lacks $hfo_dir/$file"
done
# the binding loads libhfo_c.so when imported
(cd / && PYTHONPATH="$hfo_dir" python3 -c "import hfo; hfo.HFOEnvironment()") \
  || die "the Python binding in $hfo_dir/hfo does not load"

echo "== built in $(( $(date +%s) - start_s )) s: HFO ${hfo_commit:0:7}, rcssserver ${rcssserver_commit:0:7}, librcsc ${librcsc_commit:0:7}"
echo "export HFO_DIR=$hfo_dir"
