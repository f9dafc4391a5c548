#!/usr/bin/env bash
# Remeshing's time against two references on one input: scansurf's smoothing (the bound issue
# 11 sets) and CGAL's isotropic remeshing (Botsch & Kobbelt, like scansurf's) of the same
# smoothed surfaces with none of scansurf's checks, each structure on its own, serial, same
# edge length, same 4 iterations. Installs libcgal-dev (Debian; not a test dependency) and
# builds in build-bench.
#
#   tests/bench/cgal_reference.sh INPUT [SCANSURF OPTIONS...]
#   e.g. tests/bench/cgal_reference.sh /tmp/bench/pelvis.json --grid 512 350
#        (sets from: build-bench/tests/scansurf_bench generate /tmp/bench pelvis head-neck)
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: $0 INPUT [SCANSURF OPTIONS...]" >&2; exit 2; }
root="$(cd "$(dirname "$0")/../.." && pwd)"
input="$(realpath "$1")"
shift
cd "$root"
build="$root/build-bench"

if ! dpkg-query -W -f='${Status}' libcgal-dev 2> /dev/null | grep -q "install ok installed"; then
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends libcgal-dev
fi
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --target scansurf_cli scansurf_cgal_remesh -j2

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
"$build/cli/scansurf" "$input" "$@" -q -o "$work/smoothed" --report "$work/smoothed.json"
"$build/cli/scansurf" "$input" "$@" -q --remesh -o "$work/remeshed" --report "$work/remeshed.json"
stage() { python3 -c 'import json,sys; print(next(t["seconds"] for t in json.load(open(sys.argv[1]))["timings"] if t["stage"] == sys.argv[2]))' "$@"; }
length=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["remeshing"]["edge_length"])' "$work/remeshed.json")
surfaces=()
for f in "$work/smoothed"/*.ply; do [ "$(basename "$f")" = multilabel.ply ] || surfaces+=("$f"); done
cgal=$("$build/tests/scansurf_cgal_remesh" "$length" 4 "${surfaces[@]}")
python3 - "$work/remeshed.json" "$(stage "$work/smoothed.json" smoothing)" "$(stage "$work/remeshed.json" remeshing)" "$cgal" << 'EOF'
import json, sys
report, smoothing, remeshing, cgal = json.load(open(sys.argv[1])), float(sys.argv[2]), float(sys.argv[3]), json.loads(sys.argv[4])
r = report["remeshing"]
print(f"edge length {r['edge_length']:.4g}; threads {report['parameters']['threads']:g} (0: all cores)")
print(f"smoothing (scansurf):                 {smoothing:8.2f} s")
print(f"remeshing (scansurf, every check):    {remeshing:8.2f} s  {r['triangles_before']} -> {r['triangles_after']} triangles "
      f"(multi-label mesh), smallest angle {r['smallest_angle_after']['min']:.1f}, 5th percentile {r['smallest_angle_after']['p5']:.1f}")
print(f"isotropic remeshing (CGAL, no check): {cgal['seconds']:8.2f} s  {cgal['triangles_before']} -> {cgal['triangles_after']} triangles "
      f"({cgal['surfaces']} surfaces, serial), smallest angle {cgal['min_angle']:.1f}, 5th percentile {cgal['p5_angle']:.1f}")
EOF
