#!/usr/bin/env bash
# The main job, on an embedded default: the simulated LivingLab hall (the paper's 60 m x 18 m
# test hall) with three vehicles, pallets placed and taken away and people walking.
# Installs what is missing, builds, runs, and ends with the updated map as a PNG and a short
# report in out/demo/.
#   ./run_demo.sh [--scenario SCENARIO.yaml]
#
# Stage: the vehicles are simulated and their changes are merged by the oracle pipeline
# (exactly what the scanners saw); the on-board perception, the aggregator and the LCM fleet
# replace the oracle as they land (DESIGN.md).
set -euo pipefail
cd "$(dirname "$0")"

scenario=tools/sim/worlds/livinglab/fleet.yaml
case ${1:-} in
  --scenario) scenario=${2:?--scenario needs a file} ;;
  -h | --help) sed -n '2,11p' "$0"; exit 0 ;;
  "") ;;
  *) echo "run_demo.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
esac

step() { printf '\n== %s\n' "$*"; }

step "1/4 installing missing packages and building"
scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build build -j "$(nproc)" --target fleetmap-eval fleetmap-maptool

out=out/demo
mkdir -p "$out"
step "2/4 simulating $scenario and merging the changes"
build/bin/fleetmap-eval --scenario "$scenario" --out "$out" --name demo | tee "$out/figures.txt"

step "3/4 the map codec on the updated map"
static_map=$(sed -n 's/^map: *//p' "$scenario")
static_map="$(dirname "$scenario")/$static_map"
build/bin/fleetmap-maptool codec "$out/current_map.yaml" | tee "$out/codec.txt"
build/bin/fleetmap-maptool diff "$static_map" "$out/current_map.yaml" | tee -a "$out/codec.txt"

step "4/4 report"
cat "$out/report.md"
cat <<DONE

Results in $out/:
  current_map.png        the updated map          current_map.yaml/.pgm  the same, map_server format
  map_overlay.png        the map against the truth (green ok, red false, blue missed, ...)
  paths.png              the vehicles' paths      divergence.png         d(t), w_avg, w_fast, w_slow
  report.json            every figure (keys: docs/evaluation.md)
DONE
