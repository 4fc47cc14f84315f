#!/usr/bin/env bash
# The main job, on an embedded default: the simulated LivingLab hall (the paper's 60 m x 18 m
# test hall) with three vehicles, pallets placed and taken away, people walking. Each vehicle
# runs its own fleetmap-agent, the server fleetmap-aggregator, all talking over real LCM UDP
# multicast on loopback, recorded by fleetmap-record (lcm-logger's file format, docs/channels.md);
# then the run is scored against the truth.
# Installs what is missing, builds the programs the fleet script runs (fleetmap-sim,
# fleetmap-agent, fleetmap-aggregator, fleetmap-record, fleetmap-eval, fleetmap-keygen: the
# list scripts/fleet_run.sh --programs prints), runs (a few minutes on 2 cores), and prints where the
# results are: out/current_map.png, out/report.json, out/report.md, out/divergence.png, the
# logs in out/logs/.
#   ./run_demo.sh [--scenario FILE] [--speed X] [--duration S]
#     --speed X: simulated seconds per wall-clock second [4]; see scripts/fleet_run.sh.
set -euo pipefail
cd "$(dirname "$0")"

args=()
while [ $# -gt 0 ]; do
  case $1 in
    --scenario | --speed | --duration) args+=("$1" "${2:?$1 needs a value}"); shift 2 ;;
    -h | --help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "run_demo.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done

step() { printf '\n== %s\n' "$*"; }

step "1/4 installing missing packages and building"
# Exactly the programs the fleet script runs: it keeps the one list (scripts/fleet_run.sh --programs).
mapfile -t programs < <(scripts/fleet_run.sh --programs)
scripts/build.sh build -t "${programs[@]}"

step "2/4 multicast on loopback (LCM needs a route for 224.0.0.0/4 and a large receive buffer)"
scripts/setup_multicast.sh

step "3/4 the fleet: simulator, three agents and the aggregator over LCM multicast"
scripts/fleet_run.sh --out out "${args[@]}"

step "4/4 report"
cat out/report.md
echo
grep -E '^(eval\.demo\.(changed_f1|static_erased|actor_mapped|merges_accepted|merges_rejected)|fleet\.(change_latency_s\.median|vehicle_maps_equal|final_version|bytes_per_s\.(TEMPMAP|MAP_DELTA|MAP_KEYFRAME|POSE|DIVERGENCE))|replay)' \
  out/figures.txt || true
cat <<DONE

Results in out/:
  current_map.png        the updated map (what every vehicle holds at the end)
  map_overlay.png        the map against the truth (green ok, red false, blue missed, ...)
  divergence.png         d(t), w_avg, w_fast, w_slow per vehicle (the paper's Fig. 3)
  paths.png              the vehicles' paths (estimated and true)
  report.json            every figure (keys: docs/evaluation.md), report.md the summary
  merges.md              every temporary map: accepted or rejected, residual, reason
  figures.txt            the figures as 'name value unit' lines
  logs/*.lcmlog          the recorded run (lcm-logplayer, lcm-spy; docs/channels.md)
  maps/                  the aggregator's and each vehicle's final map (map_server YAML)
DONE
