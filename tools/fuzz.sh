#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, GEARPATH_FUZZ=ON, clang with ASan and UBSan) and
# runs each for SECONDS on its seed corpus tests/fuzz/corpus/<target>.
#
#   bash tools/fuzz.sh [SECONDS] [TARGET...]      # default 60 s each, every target
#   PARALLEL=1 bash tools/fuzz.sh 600             # every target at once: 10 min in all
#
# PARALLEL=1 runs the targets side by side instead of one after the other: each still runs
# SECONDS, but shares the CPU with the others, so it gets fewer executions than alone (they are
# printed either way).
# New inputs go to $BUILD_DIR/corpus/<target> (the seed corpus is not modified); crashes to
# $BUILD_DIR/crashes/<target>-*: turn each into a regression test and a seed. Prints each
# target's executions. Needs clang and libclang-rt-14-dev (Debian 12); BUILD_DIR defaults to
# ./build-fuzz, JOBS to 2.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build-fuzz}
seconds=${1:-60}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(fuzz_daemon_config fuzz_frf_set fuzz_recording fuzz_uff58 fuzz_text_export
           fuzz_block_validation fuzz_machine_state)
fi

cmake -S "$root" -B "$build" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARPATH_FUZZ=ON -DGEARPATH_BUILD_TESTS=OFF \
  -DGEARPATH_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]}"

run() {
  local t=$1
  mkdir -p "$build/corpus/$t" "$build/crashes"
  "$build/tests/fuzz/$t" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 \
    -rss_limit_mb=2048 -artifact_prefix="$build/crashes/$t-" \
    "$build/corpus/$t" "$root/tests/fuzz/corpus/$t" >"$build/$t.log" 2>&1
}
report() {  # target, exit code
  echo "== $1: ${seconds} s"
  if [ "$2" -ne 0 ]; then
    echo "   CRASH (see $build/$1.log and $build/crashes/)"
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/$1.log" | sed 's/^/   /'
}

status=0
if [ "${PARALLEL:-0}" = 1 ]; then
  declare -A pids
  for t in "${targets[@]}"; do
    run "$t" &
    pids[$t]=$!
  done
  for t in "${targets[@]}"; do
    code=0
    wait "${pids[$t]}" || code=$?
    report "$t" "$code"
  done
else
  for t in "${targets[@]}"; do
    code=0
    run "$t" || code=$?
    report "$t" "$code"
  done
fi
exit $status
