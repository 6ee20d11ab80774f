#!/usr/bin/env bash
# All set-up, then the main job: gearpathd on its embedded default configuration (the seed's
# Table-1 gearbox, FRFs virtually decoupled by Eq. 22), fed by a simulated gearbox over
# loopback DDS: 20 healthy blocks for the daemon to learn its baseline, then a tooth fracture on
# gear G1. `gearpath monitor` shows the fault topics (suspected gear, dominant path, envelope
# indicators) and the daemon's status as they arrive.
#
#   bash tools/demo.sh                              # tooth fracture on G1
#   bash tools/demo.sh --fault chipped --gear G2    # any `gearpath sim` fault options
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${BUILD_DIR:-$root/build}
bash "$root/tools/build.sh"

healthy=20
faulty=20
log=$(mktemp -d)
"$build/daemon/gearpathd" --log-level warn 2>"$log/gearpathd.log" &
daemon=$!
cleanup() {
  kill -TERM "$daemon" 2>/dev/null || true
  wait "$daemon" 2>/dev/null || true
}
trap cleanup EXIT

"$build/tools/gearpath" monitor --count $((healthy + faulty)) --timeout 180 &
monitor=$!
"$build/tools/gearpath" sim --publish --healthy-blocks $healthy --blocks $((healthy + faulty)) \
  --fault fracture --gear G1 --noise 0.05 --speed 4 "$@" >"$log/sim.log"
wait "$monitor"
echo
echo "simulated gearbox:"
sed 's/^/  /' "$log/sim.log"
echo "gearpathd log (warnings and errors): $log/gearpathd.log"
