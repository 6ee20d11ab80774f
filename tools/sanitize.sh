#!/usr/bin/env bash
# Builds the tree with a sanitizer (GEARPATH_SANITIZE) and runs ctest on it.
#
#   bash tools/sanitize.sh address [CTEST_REGEX]   # ASan + UBSan: the whole suite
#   bash tools/sanitize.sh thread [CTEST_REGEX]    # TSan: the daemon and DDS tests
#
# address: ASan + UBSan (any finding fails the test), every test but the soak tests (their own
# label, hours long) and the valgrind test (valgrind cannot run a sanitized binary).
# thread: TSan, the tests of the DDS layer, the daemon, the tools and the integration tests
# (ctest label dds: tests/idl, daemon, tools, integration; not the soak), built alone. Cyclone
# DDS, its security plugins and OpenSSL are not built with TSan: tools/tsan.supp keeps their
# internal false positives out (each reason there); no suppression names gearpath code.
# CTEST_REGEX (ctest -R) runs a slice instead, e.g. 'Npy|BlockProcessor' (with thread, name its
# executables in TARGETS, or TARGETS=all). LABELS (ctest -L) picks a slice by label instead:
# LABELS=dds bash tools/sanitize.sh address runs the daemon, DDS, tools and integration tests
# under ASan+UBSan and builds only their executables (as thread does), not the core tests.
#
# Every process writes its sanitizer reports to $BUILD_DIR/sanitizer-reports/ (log_path), the
# daemons and tools the tests start included, whose stderr no test reads: the run fails if any
# report is there, and prints them.
# BUILD_DIR defaults to build-asan / build-tsan next to the checkout, TARGETS limits what is
# built (a slice of tests then needs its executables named), JOBS (default 2) is the parallelism
# of the build and of ctest. The compiler is CMake's default (GCC on Debian 12; CXX=clang++ works).
#
# Not in CI by default: on the shared 2-core machine (load 6-8 from other builds) the ASan build
# of the tree took over an hour and the TSan build of the slice about as long (its tests then
# take about 3 min), beyond the CI budget next to tools/test.sh. .ci/run runs one of them after the normal
# suite when GEARPATH_CI_SANITIZE=address or thread.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
mode=${1:-address}
regex=${2:-}
labels=${LABELS:-}
exclude=
# The executables of the daemon and DDS tests (label dds: tests/idl, daemon, tools, integration).
dds_targets='gearpathd gearpath test_idl test_daemon test_daemon_config test_tools test_tools_report
  test_integration'
case "$mode" in
  address)
    short=asan
    if [[ $labels == dds ]]; then
      TARGETS=${TARGETS:-$dds_targets}
      exclude='^test_soak_NOT_BUILT$'
    fi
    ;;
  thread)
    short=tsan
    [[ -z $regex && -z $labels ]] && labels=dds
    # The soak executable (label soak) is not built: its placeholder test is not run either.
    exclude='^test_soak_NOT_BUILT$'
    TARGETS=${TARGETS:-$dds_targets}
    ;;
  *) echo "usage: $0 [address|thread] [CTEST_REGEX]" >&2; exit 2 ;;
esac
[[ ${TARGETS:-} == all ]] && TARGETS=
build=${BUILD_DIR:-$(dirname "$root")/build-$short}
jobs=${JOBS:-2}

start=$SECONDS
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGEARPATH_SANITIZE="$mode" \
  -DGEARPATH_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  -DCMAKE_C_COMPILER_LAUNCHER=ccache >/dev/null
# shellcheck disable=SC2086  # TARGETS is a list of target names
cmake --build "$build" -j"$jobs" ${TARGETS:+--target $TARGETS}
built=$SECONDS

reports=$build/sanitizer-reports
rm -rf "$reports" && mkdir -p "$reports"
# Halt at the first report with a stack, into a file per process; options already in the
# environment come last and win.
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1:check_initialization_order=1:log_path=$reports/asan${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:log_path=$reports/ubsan${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$root/tools/tsan.supp:log_path=$reports/tsan${TSAN_OPTIONS:+:$TSAN_OPTIONS}"
status=0
ctest --test-dir "$build" --output-on-failure -j"$jobs" -LE 'soak|valgrind' ${labels:+-L "$labels"} \
  ${regex:+-R "$regex"} ${exclude:+-E "$exclude"} ||
  status=$?

found=$(find "$reports" -type f | sort)
if [[ -n $found ]]; then
  for f in $found; do
    echo "=== sanitizer report $f"
    cat "$f"
  done
  echo "sanitize.sh: $(echo "$found" | wc -l) process(es) wrote a sanitizer report (above)" >&2
  status=1
fi
echo "sanitize.sh $mode: build $((built - start)) s, ctest $((SECONDS - built)) s, exit $status"
exit "$status"
