#!/usr/bin/env bash
# Builds the whole tree with a sanitizer (GEARPATH_SANITIZE) and runs ctest on it.
#
#   bash tools/sanitize.sh [address|thread] [CTEST_REGEX]    # default: address, every test
#
# address: ASan + UBSan, any finding fails the test; thread: TSan. The soak tests (their own
# label, hours long) and the valgrind test (valgrind cannot run a sanitized binary) are left out;
# CTEST_REGEX (ctest -R) runs a slice, e.g. 'Pipeline|Io'. No TSan suppressions so far: add a
# file (TSAN_OPTIONS=suppressions=...) only for third-party code, each entry with its reason.
# BUILD_DIR defaults to build-asan / build-tsan next to the checkout, TARGETS (default: all)
# limits what is built (a slice of tests then needs its executables named), JOBS (default 2) is
# the parallelism of the build and of ctest. The compiler is CMake's default (GCC on Debian 12; CXX=clang++ works).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=${1:-address}
regex=${2:-}
case "$mode" in
  address) short=asan ;;
  thread) short=tsan ;;
  *) echo "usage: $0 [address|thread] [CTEST_REGEX]" >&2; exit 2 ;;
esac
build=${BUILD_DIR:-$(dirname "$root")/build-$short}
jobs=${JOBS:-2}

cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARPATH_SANITIZE="$mode" \
  -DGEARPATH_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DCMAKE_C_COMPILER_LAUNCHER=ccache >/dev/null
# shellcheck disable=SC2086  # TARGETS is a list of target names
cmake --build "$build" -j"$jobs" ${TARGETS:+--target $TARGETS}

# Halt at the first report with a stack; options already in the environment come last and win.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1${TSAN_OPTIONS:+:$TSAN_OPTIONS}"
ctest --test-dir "$build" --output-on-failure -j"$jobs" -LE 'soak|valgrind' ${regex:+-R "$regex"}
