#!/usr/bin/env bash
# Instructions executed by one scansurf run, counted by valgrind's callgrind: a cost measure
# that does not drift with the machine's load, for comparing two builds of a CPU stage where
# wall times on a shared VM vary by 10-25 % between runs. Prints the total, then the heaviest
# functions. Under valgrind a run takes about 60 times as long: use a small case, e.g.
#
#   tests/bench/count_instructions.sh build/cli/scansurf examples/phantom.json \
#       --voxel-size 2 --interpolate off --remesh --threads 1
#
# (valgrind is a Debian package, not a test dependency.)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 SCANSURF INPUT [OPTIONS...]" >&2; exit 2; }
command -v valgrind > /dev/null || { echo "$0: valgrind is not installed (apt-get install valgrind)" >&2; exit 1; }
binary="$1"
shift
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
valgrind --tool=callgrind --callgrind-out-file="$work/callgrind.out" "$binary" "$@" -o "$work/out" > "$work/log" 2>&1 ||
  { cat "$work/log" >&2; exit 1; }
grep -E "^==[0-9]+== I +refs:" "$work/log" | sed 's/^==[0-9]*== //'
callgrind_annotate "$work/callgrind.out" 2> /dev/null | grep -E "^ *[0-9,]+ +\([ 0-9.]+%\)" | sed -n '2,16p' | cut -c1-150
