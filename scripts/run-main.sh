#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the main job: the roundabout scenario S2 through the
# maneuvermap command line, then prints its summary.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$(nproc)"
./build/release/cli/maneuvermap run s2-roundabout --out out/s2-roundabout
cat out/s2-roundabout/summary.json
