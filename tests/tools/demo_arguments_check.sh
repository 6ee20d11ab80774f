#!/usr/bin/env bash
# tools/demo.sh passes the caller's `gearpath sim` options in place of its own defaults: the
# README's `bash tools/demo.sh --fault chipped --gear G2` used to hand `gearpath sim` two
# --fault options, which it refuses, and the monitor then waited for verdicts that never came.
# Each case takes the demo's dry run (what it would run, one argument a line) and hands the sim
# arguments, less --publish, to the built `gearpath sim`, whose summary names the fault it made.
#   demo_arguments_check.sh <repository root> <gearpath binary>
set -uo pipefail
root=$1
gearpath=$2
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_fault "<summary text>" [demo arguments...]
expect_fault() {
  local expected=$1 out line part=
  shift
  if ! out=$(GEARPATH_DEMO_DRY_RUN=1 bash "$root/tools/demo.sh" "$@"); then
    fail "demo.sh $* refused"
    return
  fi
  local -a monitor=() sim=()
  while IFS= read -r line; do
    case $line in
      monitor | sim) part=$line ;;
      *) if [[ $part == monitor ]]; then monitor+=("$line"); else sim+=("$line"); fi ;;
    esac
  done <<<"$out"
  [[ ${monitor[*]} == "--count 40 --timeout 180" ]] || fail "demo.sh $*: monitor ${monitor[*]}"
  local -a summary_args=()
  for line in "${sim[@]}"; do [[ $line == --publish ]] || summary_args+=("$line"); done
  local summary
  if ! summary=$("$gearpath" sim "${summary_args[@]}" 2>&1); then
    fail "demo.sh $*: gearpath sim ${summary_args[*]} refused: $summary"
    return
  fi
  grep -qF -- "$expected" <<<"$summary" || fail "demo.sh $*: no '$expected' in: $summary"
  echo "ok: demo.sh $* -> gearpath sim ${sim[*]}"
}

expect_fault "fault: fracture on G1"
expect_fault "fault: chipped on G2" --fault chipped --gear G2
expect_fault "fault: wear on G3" --gear=G3 --fault=wear
expect_fault "fault: fracture on G4" --gear G4
expect_fault "noise 0.1 x RMS" --noise 0.1

# The block counts belong to the demo (the monitor waits for exactly that many verdicts).
for own in --blocks --healthy-blocks; do
  if err=$(GEARPATH_DEMO_DRY_RUN=1 bash "$root/tools/demo.sh" "$own" 3 2>&1); then
    fail "demo.sh $own 3 accepted"
  elif ! grep -qF -- "$own is the demo's own" <<<"$err"; then
    fail "demo.sh $own 3: unclear refusal: $err"
  else
    echo "ok: demo.sh $own 3 refused: $err"
  fi
done

exit $((failures > 0))
