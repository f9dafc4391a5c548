#!/usr/bin/env bash
# Runs the reader fuzzers of a SCANSURF_FUZZ build, each for SECONDS with its dictionary
# (tests/fuzz/dict), as many at once as there are cores (or JOBS). Each grows its working
# corpus in BUILD/fuzz/corpus/<target> from the seeds in tests/fuzz/corpus/<target>; a crash,
# a sanitizer report, a leak or a timeout (10 s on one input) leaves the input in
# BUILD/fuzz/findings/<target>/ and makes the script fail, printing the fuzzer's log.
# Usage: tests/fuzz/run_fuzzers.sh BUILD SECONDS [TARGET...]   (default: every target)
# Keep a finding: copy it to tests/fuzz/regressions/<target>/ once the reader is fixed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "$1" && pwd)"
seconds="$2"
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(contours_json rtstruct ct_series reconstruct imod)
jobs="${JOBS:-$(nproc)}"
# UBSan's reports are findings too (it would only print them and go on).
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"

run_one() {
  local target="$1" corpus="$build/fuzz/corpus/$1" findings="$build/fuzz/findings/$1" log="$build/fuzz/$1.log"
  mkdir -p "$corpus" "$findings"
  local start=$SECONDS dict=()
  [ -f "$here/dict/$target.dict" ] && dict=(-dict="$here/dict/$target.dict")
  if "$build/tests/fuzz/scansurf_fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 "${dict[@]}" \
      -print_final_stats=1 -artifact_prefix="$findings/" "$corpus" "$here/corpus/$target" >"$log" 2>&1; then
    echo "fuzz $target: ${seconds} s, no finding ($(grep -ao 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$') inputs run, corpus $(ls "$corpus" | wc -l) files, $((SECONDS - start)) s wall)"
  else
    echo "fuzz $target: FINDING in $findings:"; ls -l "$findings"; tail -n 60 "$log"
    return 1
  fi
}
export -f run_one
export build here seconds
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}'
