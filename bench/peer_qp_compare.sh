#!/usr/bin/env bash
# Same-instance comparison of the contact-force QP solver with peer QP solvers (bench/peer_qp).
# PEERS_DIR holds the peers' sources, which you provide (nothing is downloaded or vendored):
#   PEERS_DIR/daqp        git clone https://github.com/darnstrom/daqp
#   PEERS_DIR/eiquadprog  git clone https://github.com/stack-of-tasks/eiquadprog
#   PEERS_DIR/qpOASES     git clone https://github.com/coin-or/qpOASES
# A missing one is skipped. Sets FTSENSE_PEER_QP_SOURCES in BUILD_DIR's cache, builds
# ftsense-peer-qp there (the peers with that build's flags) and runs it; extra arguments go to it
# (--seconds S, --passes P). Usage: bench/peer_qp_compare.sh PEERS_DIR [BUILD_DIR] [ARGS...]
set -eu
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: $0 PEERS_DIR [BUILD_DIR] [--seconds S] [--passes P]" >&2
  exit 2
fi
peers=$(cd "$1" && pwd)
shift
build=build
if [ $# -gt 0 ] && [ "${1#--}" = "$1" ]; then build=$1; shift; fi
root=$(cd "$(dirname "$0")/.." && pwd)
for peer in daqp eiquadprog qpOASES; do
  if [ -d "$peers/$peer/.git" ]; then
    echo "$peer: $(git -C "$peers/$peer" log -1 --format='%h %cs')"
  elif [ -d "$peers/$peer" ]; then
    echo "$peer: $peers/$peer (not a git checkout)"
  else
    echo "$peer: absent, skipped"
  fi
done
cmake -S "$root" -B "$build" -DFTSENSE_PEER_QP_SOURCES="$peers" > /dev/null
cmake --build "$build" --target ftsense_peer_qp -j 2 > /dev/null
type=$(grep -E '^CMAKE_BUILD_TYPE:' "$build/CMakeCache.txt" | cut -d= -f2)
echo "build type $type: C++ and C compiled with" \
     "'$(grep -E "^CMAKE_CXX_FLAGS_${type^^}:" "$build/CMakeCache.txt" | cut -d= -f2)'"
"$build/bin/ftsense-peer-qp" "$@"
