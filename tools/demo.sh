#!/usr/bin/env bash
# All set-up, then the main job: builds gearpath and runs the numerical validation of the
# method on the seed's Table-1 gearbox (virtual vs physical decoupling, force identification).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
bash "$root/tools/build.sh"
"$build/tools/gearpath" validate
