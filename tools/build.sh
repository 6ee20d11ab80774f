#!/usr/bin/env bash
# Installs dependencies, then configures and builds gearpath into ./build (or $BUILD_DIR).
#
# Debug information: full (-g) by default, for gdb. CI (CI=true) builds with line tables only
# (-g1): backtraces and profiles keep their file:line, and the 2-core build takes about a
# quarter less time (docs/performance.md, "Build"), the same code otherwise (-O2 either way).
# DEBUG_INFO=full|lines chooses it explicitly.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
debug_info=${DEBUG_INFO:-$([ "${CI:-}" = true ] && echo lines || echo full)}
case "$debug_info" in
  full) g=-g ;;
  lines) g=-g1 ;;
  *) echo "build.sh: DEBUG_INFO=$debug_info: use full or lines" >&2; exit 2 ;;
esac
bash "$root/tools/install-deps.sh"
# Both flag sets every time, so a build directory configured for one level does not keep it.
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-RelWithDebInfo} \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 $g -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 $g -DNDEBUG" >/dev/null
cmake --build "$build" -j"$(nproc)"
