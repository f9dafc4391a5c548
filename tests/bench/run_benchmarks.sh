#!/usr/bin/env bash
# One command for the benchmark table (issue 6): installs the tools of the 3D Slicer route
# (Debian's plastimatch and python3-vtk9; not test dependencies), builds scansurf in
# Release, generates the synthetic structure sets, runs scansurf and the Slicer route on
# each on the same grid, prints the table and writes docs/benchmarks.md.
#
#   tests/bench/run_benchmarks.sh [SET...]      (default: pelvis head-neck em-cells)
#
# Each set runs BENCH_RUNS times (default 3), the two routes interleaved (ours, Slicer's, ours,
# ...), so that load on the machine slows both alike; the table quotes the median run and the
# median and range of the ratio pair by pair.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
build="$root/build-bench"
py=/usr/bin/python3  # Debian's Python, where python3-vtk9 installs
work="$build/bench-work"

./cmake/install-deps.sh
missing=()
for p in plastimatch python3-vtk9; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=(); [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --target scansurf_bench -j2
mkdir -p "$work"
sets=("$@")
[ ${#sets[@]} -gt 0 ] || sets=(pelvis head-neck em-cells)
"$build/tests/scansurf_bench" generate "$work" "${sets[@]}"

results="$work/results.jsonl"
: > "$results"
runs=${BENCH_RUNS:-3}
for set in "${sets[@]}"; do
  for run in $(seq 1 "$runs"); do
    echo "== $set, run $run of $runs: scansurf" >&2
    ours=$("$build/tests/scansurf_bench" run "$work/$set.json" 512)
    echo "$ours" >&2
    read -r nx ny nz ox oy vs <<< "$("$py" -c 'import json,sys; d=json.loads(sys.argv[1]); print(int(d["nx"]), int(d["ny"]), int(d["nz"]), d["origin_x"], d["origin_y"], d["voxel_size"])' "$ours")"
    read -r oz sz <<< "$("$py" -c 'import json,sys; zs=sorted({s["z"] for f in json.load(open(sys.argv[1]))["features"] for s in f["slices"]}); d=zs[1]-zs[0]; print(zs[0]-d, d)' "$work/$set.json")"
    echo "== $set, run $run of $runs: Slicer route (plastimatch + VTK) on the same ${nx}x${ny}x${nz} grid" >&2
    slicer=$("$py" tests/bench/slicer_route.py "$work/$set.json" "$nx" "$ny" "$nz" "$ox" "$oy" "$oz" "$vs" "$sz" "$work/slicer-$set")
    echo "$slicer" >&2
    "$py" -c 'import json,sys; print(json.dumps({"set": sys.argv[1], "run": int(sys.argv[4]), "ours": json.loads(sys.argv[2]), "slicer": json.loads(sys.argv[3])}))' "$set" "$ours" "$slicer" "$run" >> "$results"
  done
done

# Scaling: pelvis and head-neck whole at 1 and 2 threads (scansurf's CPU stages and lavapipe's),
# the thread counts interleaved run by run.
scaling="$work/scaling.jsonl"
: > "$scaling"
for set in pelvis head-neck; do
  [ -f "$work/$set.json" ] && [[ " ${sets[*]} " == *" $set "* ]] || continue
  for run in $(seq 1 "$runs"); do
    for threads in 1 2; do
      echo "== $set, run $run of $runs: scansurf on $threads thread(s)" >&2
      ours=$(SCANSURF_THREADS=$threads LP_NUM_THREADS=$threads "$build/tests/scansurf_bench" run "$work/$set.json" 512)
      "$py" -c 'import json,sys; print(json.dumps({"set": sys.argv[1], "threads": int(sys.argv[2]), "run": int(sys.argv[3]), "ours": json.loads(sys.argv[4])}))' "$set" "$threads" "$run" "$ours" >> "$scaling"
    done
  done
done

"$py" tests/bench/make_table.py "$results" "$(git rev-parse --short HEAD)" "$scaling" > docs/benchmarks.md

# Where the time goes: a perf profile of scansurf on pelvis (when perf works on this machine).
if command -v perf > /dev/null && [ -f "$work/pelvis.json" ] && perf stat -e task-clock true > /dev/null 2>&1; then
  perf record -g -F 499 -o "$work/perf.data" "$build/tests/scansurf_bench" run "$work/pelvis.json" 512 > /dev/null 2>&1 || true
  {
    echo
    echo "## Profile: scansurf on pelvis (perf record, self time by symbol, top 10)"
    echo
    echo '```'
    perf report -i "$work/perf.data" --no-children -g none --sort dso,symbol --stdio > "$work/perf.txt" 2> /dev/null || true
    grep -E '^ +[0-9]' "$work/perf.txt" | sed -n '1,10p' | cut -c1-170 | sed 's/ *$//'
    echo '```'
  } >> docs/benchmarks.md
fi
cat docs/benchmarks.md
