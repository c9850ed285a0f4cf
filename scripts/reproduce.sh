#!/usr/bin/env bash
# Regenerates the reproduction report docs/reproduction.md and its figures in
# docs/figures/reproduction/ from scratch: installs, builds, runs the paper's experiments
# (the Table 1 sweep, the roundabout sweep, the S3 sensitivity study, example runs and a
# snapshot), draws the figures and fills the report's tables. Raw outputs go to out/reproduction/.
#   bash scripts/reproduce.sh [--jobs N]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=()
if [[ "${1:-}" == "--jobs" ]]; then jobs=(--jobs "$2"); fi
bash scripts/install-deps.sh
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/release -j "$(nproc)"
mm=./build/release/cli/maneuvermap
out=out/reproduction
figures=docs/figures/reproduction
rm -rf "$out" "$figures"
mkdir -p "$out" "$figures"

echo "== Table 1: S3 over the paper's grid (500 runs)" >&2
$mm sweep table1 "${jobs[@]}" --out "$out/table1" --plots >"$out/table1.log"

echo "== The roundabout under every policy" >&2
$mm sweep roundabout "${jobs[@]}" --out "$out/roundabout" --plots >"$out/roundabout.log"
$mm snapshot s2-roundabout --time 1.2 --agent A --out "$out/roundabout/snapshot-1.2s.csv"
$mm plot "$out/roundabout/snapshot-1.2s.csv" >/dev/null

echo "== S3 sensitivity study: B's turn visible for longer" >&2
/usr/bin/python3 tools/reproduction/s3_variants.py >/dev/null
variants=()
for sweep in sweeps/s3-variants/*.sweep.yaml; do
  name=$(basename "$sweep" .sweep.yaml)
  $mm sweep "$sweep" "${jobs[@]}" --out "$out/variants/$name" >"$out/variants-$name.log"
  variants+=("$out/variants/$name")
done

echo "== S3 example runs (A 40 km/h, B 35 km/h, seed 1)" >&2
s3_runs=()
for geometry in s3-left-turn sweeps/s3-variants/s3-left-turn-offset-14m.yaml; do
  label=$([[ "$geometry" == s3-left-turn ]] && echo "built-in" || echo "offset-14m")
  for policy in adj const:1.0 robust; do
    dir="$out/s3/$label-${policy/:/}"
    $mm run "$geometry" --set a_kmh=40 --set b_kmh=35 --policy "$policy" --seed 1 --out "$dir" --plots >/dev/null
    s3_runs+=("$label, ${policy}=$dir")
  done
done

echo "== Figures and report" >&2
cp "$out/table1/table1-comparison.png" "$figures/table1-comparison.png"
cp "$out/roundabout/speed-profiles.png" "$figures/roundabout-speed-profiles.png"
cp "$out/roundabout/runs/adj_rep0/map.png" "$figures/roundabout-map-adj.png"
cp "$out/roundabout/runs/adj_rep0/topdown.png" "$figures/roundabout-topdown-adj.png"
cp "$out/roundabout/runs/const0.5_rep0/map.png" "$figures/roundabout-map-const0.5.png"
cp "$out/roundabout/snapshot-1.2s-sets.png" "$figures/roundabout-sets-1.2s.png"
cp "$out/s3/offset-14m-adj/map.png" "$figures/s3-offset-14m-map-adj.png"
cp "$out/s3/offset-14m-const1.0/map.png" "$figures/s3-offset-14m-map-const1.0.png"
cp "$out/s3/offset-14m-const1.0/topdown.png" "$figures/s3-offset-14m-topdown-const1.0.png"
cp "$out/s3/offset-14m-robust/map.png" "$figures/s3-offset-14m-map-robust.png"
cp "$out/s3/offset-14m-robust/topdown.png" "$figures/s3-offset-14m-topdown-robust.png"
cp "$out/roundabout/runs/robust_rep0/map.png" "$figures/roundabout-map-robust.png"
cp "$out/s3/built-in-adj/topdown.png" "$figures/s3-topdown-adj.png"
/usr/bin/python3 tools/reproduction/report.py --table1 "$out/table1" --roundabout "$out/roundabout" \
  --paper data/paper/table1.csv --template docs/reproduction.template.md --out docs/reproduction.md \
  --variants "${variants[@]}" --s3-runs "${s3_runs[@]}"
echo "written: docs/reproduction.md and $figures/" >&2
