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

healthy=20
faulty=20
# The demo's own fault, speed and noise, each unless the caller names that option: `gearpath
# sim` takes an option once, so `--fault chipped` on top of the default `--fault fracture` was
# refused and the monitor then waited for verdicts that never came.
defaults=(--fault fracture --gear G1 --noise 0.05 --speed 4)
given() {
  local option=$1 arg
  shift
  for arg in "$@"; do
    [[ $arg == "$option" || $arg == "$option="* ]] && return 0
  done
  return 1
}
for option in --healthy-blocks --blocks --publish; do
  if given "$option" "$@"; then
    echo "demo.sh: $option is the demo's own ($healthy healthy then $faulty faulty blocks," \
      "published); run \`gearpath sim\` directly to change it" >&2
    exit 2
  fi
done
sim_args=(--publish --healthy-blocks "$healthy" --blocks $((healthy + faulty)))
for ((i = 0; i < ${#defaults[@]}; i += 2)); do
  given "${defaults[i]}" "$@" || sim_args+=("${defaults[i]}" "${defaults[i + 1]}")
done
sim_args+=("$@")
monitor_args=(--count $((healthy + faulty)) --timeout 180)
if [[ ${GEARPATH_DEMO_DRY_RUN:-} == 1 ]]; then  # what would run, one argument a line (tests/tools)
  printf 'monitor\n'
  printf '%s\n' "${monitor_args[@]}"
  printf 'sim\n'
  printf '%s\n' "${sim_args[@]}"
  exit 0
fi

bash "$root/tools/build.sh"
log=$(mktemp -d)
"$build/daemon/gearpathd" --log-level warn 2>"$log/gearpathd.log" &
daemon=$!
monitor=
cleanup() {
  [[ -n $monitor ]] && kill -TERM "$monitor" 2>/dev/null || true
  kill -TERM "$daemon" 2>/dev/null || true
  wait 2>/dev/null || true
}
trap cleanup EXIT

"$build/tools/gearpath" monitor "${monitor_args[@]}" &
monitor=$!
"$build/tools/gearpath" sim "${sim_args[@]}" >"$log/sim.log"
wait "$monitor"
monitor=
echo
echo "simulated gearbox:"
sed 's/^/  /' "$log/sim.log"
echo "gearpathd log (warnings and errors): $log/gearpathd.log"
