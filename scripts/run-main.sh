#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the main job: the paper's roundabout scenario S2
# through the maneuvermap command line, with its figures:
#   1. S2 under ADJ, with its Maneuverability Map, speed profile and top-down view (paper Fig. 8a);
#   2. a snapshot of A's displacement sets at t = 1.2 s, while it brakes for B (paper Fig. 3);
#   3. the built-in `roundabout` sweep: S2 under constant τ = 0.5, 1.0, 2.0 s and ADJ (and our
#      robust policy), with the speed profiles of the five runs on one chart (paper Fig. 7) and the
#      map of each.
# Then prints the summary of the ADJ run, the sweep's table and where the figures are.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$(nproc)"
mm=./build/release/cli/maneuvermap

$mm run s2-roundabout --out out/s2-roundabout --plots
$mm snapshot s2-roundabout --time 1.2 --agent A --out out/s2-roundabout/snapshot-1.2s.csv
$mm plot out/s2-roundabout/snapshot-1.2s.csv >/dev/null
mkdir -p out/roundabout
$mm sweep roundabout --out out/roundabout --plots >out/roundabout/sweep.log

echo "== S2 roundabout exit under ADJ: out/s2-roundabout/summary.json"
cat out/s2-roundabout/summary.json
echo
echo "== The roundabout sweep: out/roundabout/table.md"
cat out/roundabout/table.md
echo
echo "== Figures (PNG, each with an SVG beside it)"
echo "  Maneuverability Map of A under ADJ (paper Fig. 8a):   out/s2-roundabout/map.png"
echo "  speed of A under ADJ:                                  out/s2-roundabout/speed.png"
echo "  the run from above, closest approach marked:           out/s2-roundabout/topdown.png"
echo "  displacement sets at t = 1.2 s (paper Fig. 3):         out/s2-roundabout/snapshot-1.2s-sets.png"
echo "  speed profiles under every policy (paper Fig. 7):      out/roundabout/speed-profiles.png"
echo "  minimum distance per policy:                           out/roundabout/min-dist.png"
echo "  map, speed and top-down view of each policy's run:     out/roundabout/runs/*/map.png ..."
