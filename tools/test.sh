#!/usr/bin/env bash
# All set-up, then the whole test suite: install dependencies, build, run ctest.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
bash "$root/tools/build.sh"
cd "$build"
ctest --output-on-failure -j"$(nproc)" --timeout 600
