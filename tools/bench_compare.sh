#!/usr/bin/env bash
# The reference workload in C++ and in NumPy, in the same run: ms per block and precompute for
# both, and the ratio NumPy / C++.
#
#   bash tools/bench_compare.sh [--reps N] [--rounds N] [BENCHMARK_ARG...]
#
# C++: build/tests/bench/bench_reference (BUILD_DIR overrides build/; it is not built here:
# `cmake --build build --target bench_reference`), its 12-channel, 16 000-sample constant-speed
# block (BM_ReferenceBlock/channels:12/samples:16000/tracking:0/drift:0) and its Create +
# Prepare (BM_ReferencePrecompute). NumPy: tests/bench/numpy_peer.py, the same chain on the same
# shapes (its docstring lists the stages and what it leaves out), median of --reps blocks
# (default 20). The two never run at once: each round runs the C++ then the NumPy side, and
# --rounds (default 3) rounds give a ratio per round and their median, since on a shared machine
# the load moves both figures between one minute and the next. Extra arguments go to the
# benchmark binary, e.g. --benchmark_repetitions=5 (its median aggregate is then used). Both
# wall-clock and CPU time are shown: preemption by other work inflates the first, not the second.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD_DIR:-$root/build}
reps=20
rounds=3
while [ $# -gt 0 ]; do
  case "$1" in
    --reps) reps=${2:?--reps needs a number}; shift 2 ;;
    --rounds) rounds=${2:?--rounds needs a number}; shift 2 ;;
    *) break ;;
  esac
done
bench=$build/tests/bench/bench_reference
if [ ! -x "$bench" ]; then
  echo "bench_compare: $bench is not built (cmake --build $build --target bench_reference," \
       "or BUILD_DIR=another build tree)" >&2
  exit 1
fi
# The interpreter the peer's ctest uses: /usr/bin/python3 if it has NumPy, else python3.
python=""
for candidate in /usr/bin/python3 python3; do
  if command -v "$candidate" >/dev/null && "$candidate" -c "import numpy" 2>/dev/null; then
    python=$candidate
    break
  fi
done
if [ -z "$python" ]; then
  echo "bench_compare: no python3 with NumPy (Debian: apt-get install python3-numpy)" >&2
  exit 1
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "C++ $bench; NumPy tests/bench/numpy_peer.py --reps $reps ($python); rounds: $rounds"
# Both sides inherit it; the systemd unit sets glibc.malloc.hugetlb=1 (docs/performance.md).
echo "GLIBC_TUNABLES=${GLIBC_TUNABLES:-(unset)}"
filter='ReferenceBlock/channels:12/samples:16000/tracking:0/drift:0$|ReferencePrecompute'
for ((r = 1; r <= rounds; r++)); do
  cut -d' ' -f1 /proc/loadavg >"$work/load$r"
  "$bench" --benchmark_filter="$filter" --benchmark_format=json "$@" >"$work/cpp$r.json"
  "$python" "$root/tests/bench/numpy_peer.py" --reps "$reps" --json "$work/numpy$r.json" >/dev/null
done

"$python" - "$work" "$rounds" <<'EOF'
import json
import os
import statistics
import sys

work, rounds = sys.argv[1], int(sys.argv[2])


def cpp_ms(doc, prefix, field):
    """real_time or cpu_time in ms of the benchmark named prefix*: its median aggregate when
    there are repetitions, else its single run."""
    runs = [b for b in doc["benchmarks"] if b["name"].startswith(prefix)]
    pick = [b for b in runs if b.get("aggregate_name") == "median"] or \
           [b for b in runs if b.get("run_type") == "iteration"]
    if not pick:
        sys.exit(f"bench_compare: no {prefix} in the benchmark output")
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[pick[0]["time_unit"]]
    return pick[0][field] * scale


rows, stages = [], []
for r in range(1, rounds + 1):
    cpp = json.load(open(os.path.join(work, f"cpp{r}.json")))
    peer = json.load(open(os.path.join(work, f"numpy{r}.json")))
    load = float(open(os.path.join(work, f"load{r}")).read())
    block = "BM_ReferenceBlock/channels:12/samples:16000/tracking:0/drift:0"
    rows.append(dict(
        load=load,
        block=(cpp_ms(cpp, block, "real_time"), peer["per_block_ms"],
               cpp_ms(cpp, block, "cpu_time"), peer["per_block_cpu_ms"]),
        precompute=(cpp_ms(cpp, "BM_ReferencePrecompute", "real_time"), peer["precompute_ms"],
                    cpp_ms(cpp, "BM_ReferencePrecompute", "cpu_time"),
                    peer["precompute_cpu_ms"])))
    stages.append(peer["stages_ms"])

for what, title, fmt in (("block", "per block", "10.1f"), ("precompute", "precompute", "10.0f")):
    print(f"\n{title}, ms{'wall clock':>25}{'CPU time':>32}")
    print(f"{'round':8}{'C++':>10}{'NumPy':>10}{'NumPy/C++':>11}{'C++':>11}{'NumPy':>10}"
          f"{'NumPy/C++':>11}{'load':>7}")
    for i, row in enumerate(rows, 1):
        cw, pw, cc, pc = row[what]
        print(f"{i:<8}{cw:{fmt}}{pw:{fmt}}{pw / cw:11.2f} {cc:{fmt}}{pc:{fmt}}{pc / cc:11.2f}"
              f"{row['load']:7.2f}")
    med = [statistics.median(row[what][k] for row in rows) for k in range(4)]
    rw = statistics.median(row[what][1] / row[what][0] for row in rows)
    rc = statistics.median(row[what][3] / row[what][2] for row in rows)
    print(f"{'median':8}{med[0]:{fmt}}{med[1]:{fmt}}{rw:11.2f} {med[2]:{fmt}}{med[3]:{fmt}}"
          f"{rc:11.2f}")
print("\nNumPy per stage, ms (median over rounds of the per-round medians):")
for k in stages[0]:
    print(f"  {k:<18}{statistics.median(s[k] for s in stages):8.2f}")
print(f"(NumPy {peer['numpy']}, Python {peer['python']}; the load column is the 1-minute "
      "load average when the round started, on a machine of "
      f"{os.cpu_count()} cores)")
EOF
