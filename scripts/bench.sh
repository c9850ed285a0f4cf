#!/usr/bin/env bash
# Measures what docs/performance.md reports. Installs, builds (Release) and runs:
#   1. maneuvermap_bench (every case, among them the first 4 s of the 50-vehicle roundabout s6 with
#      1 and 2 planning threads; JSON in out/bench/bench.json) and draws the cost chart
#      docs/figures/performance/cost-growth.png;
#   2. with --full also: the multi-obstacle search agreement (1100 random scenes with 2 and with 3
#      obstacles), the Table 1 sweep with 1, 2, 1 and 2 jobs, wall and CPU time, and the whole 20 s of
#      the roundabout s6 with 2 threads: its real-time factor with the maps, without them, and deciding
#      only the commands (run_options::decision_only, as a sweep)
#      (maneuvermap_bench --whole-roundabout) and its planning cost per simulated second (a run with
#      --timing; the chart docs/figures/performance/s6-cost-per-second.png). Logs in out/bench/. About 10 to 12 minutes on the machines of docs/performance.md.
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
  # timed LABEL COMMAND...: runs COMMAND; appends "LABEL: wall W s, CPU C s" (user + system time of
  # COMMAND and its threads, from bash's own `time`) to sweeps.txt.
  timed() {
    local label=$1 report
    shift
    report=$( { TIMEFORMAT='%R %U %S'; time "$@" >/dev/null; } 2>&1 )
    awk -v l="$label" '{ printf "%s: wall %.1f s, CPU %.1f s\n", l, $1, $2 + $3 }' <<<"$report" | tee -a "$out/sweeps.txt"
  }
  echo "== fast vs exhaustive forecast-time search" >&2
  for k in 2 3; do
    ./build/release/tools/maneuvermap_assignment --scenes 1100 --obstacles "$k" --seed 1 | tee "$out/assignment-$k.txt"
  done
  # The machine's speed can drift by tens of per cent within minutes: 1 and 2 jobs alternate twice,
  # and the CPU times show whether a slow run was the machine (more CPU time for the same work).
  echo "== table1 sweep, 1 and 2 jobs, alternating" >&2
  : >"$out/sweeps.txt"
  for pair in 1 2; do
    for j in 1 2; do
      timed "table1 --jobs $j (pair $pair)" ./build/release/cli/maneuvermap sweep table1 --jobs "$j" \
        --out "$out/table1-jobs$j-pair$pair"
    done
  done
  for run in table1-jobs2-pair1 table1-jobs1-pair2 table1-jobs2-pair2; do
    cmp "$out/table1-jobs1-pair1/runs.csv" "$out/$run/runs.csv"
  done
  echo "runs.csv identical in all four runs" | tee -a "$out/sweeps.txt"
  echo "== the whole roundabout s6, 2 threads: real-time factor, and cost per simulated second" >&2
  ./build/release/benchmarks/maneuvermap_bench --whole-roundabout '--benchmark_filter=busy_roundabout(_decision_only)?/jobs:2/seconds:20' \
    --benchmark_out="$out/whole-roundabout.json" --benchmark_out_format=json | tee "$out/whole-roundabout.txt"
  timed "s6-busy-roundabout --jobs 2 --timing (the maps and the output files included)" \
    ./build/release/cli/maneuvermap run s6-busy-roundabout --jobs 2 --timing --out "$out/s6-timing"
  /usr/bin/python3 tools/many_agents/cost_per_second.py "$out/s6-timing/decisions.csv" \
    --plot docs/figures/performance/s6-cost-per-second.png | tee "$out/s6-per-second.md"
fi
