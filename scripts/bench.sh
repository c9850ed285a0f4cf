#!/usr/bin/env bash
# Measures what docs/performance.md reports. Installs, builds (Release) and runs:
#   1. maneuvermap_bench (every case, among them the first 4 s of the 50-vehicle roundabout s6 with
#      1 and 2 planning threads; JSON in out/bench/bench.json) and draws the cost chart
#      docs/figures/performance/cost-growth.png;
#   2. with --full also: the multi-obstacle search agreement (1100 random scenes with 2 and with 3
#      obstacles) and the Table 1 sweep with 1 and 2 jobs, timed. Logs in out/bench/.
#   bash scripts/bench.sh [--full]
# Run it on an otherwise idle machine: the timings are wall-clock.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$(nproc)"
out=out/bench
mkdir -p "$out" docs/figures/performance

echo "== maneuvermap_bench" >&2
./build/release/benchmarks/maneuvermap_bench --benchmark_out="$out/bench.json" --benchmark_out_format=json \
  | tee "$out/bench.txt"
/usr/bin/python3 tools/plot/performance_chart.py "$out/bench.json" docs/figures/performance/cost-growth.png \
  | tee "$out/cost-growth.csv"

if [[ "${1:-}" == "--full" ]]; then
  # seconds FILE COMMAND...: runs COMMAND, writes its wall time [s] to FILE.
  seconds() {
    local start end
    start=$(date +%s.%N)
    "${@:2}"
    end=$(date +%s.%N)
    awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f\n", b - a }' >"$1"
  }
  echo "== fast vs exhaustive forecast-time search" >&2
  for k in 2 3; do
    ./build/release/tools/maneuvermap_assignment --scenes 1100 --obstacles "$k" --seed 1 | tee "$out/assignment-$k.txt"
  done
  echo "== table1 sweep, 1 and 2 jobs" >&2
  for j in 1 2; do
    seconds "$out/table1-jobs$j.seconds" ./build/release/cli/maneuvermap sweep table1 --jobs "$j" \
      --out "$out/table1-jobs$j" >/dev/null
    echo "table1 --jobs $j: $(cat "$out/table1-jobs$j.seconds") s" | tee -a "$out/sweeps.txt"
  done
  cmp "$out/table1-jobs1/runs.csv" "$out/table1-jobs2/runs.csv" && echo "runs.csv identical for 1 and 2 jobs" | tee -a "$out/sweeps.txt"
fi
