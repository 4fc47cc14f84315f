#!/usr/bin/env bash
# What fleetmap-agent costs on a vehicle: one simulated vehicle (the addition scenario's S300
# at 25 Hz, pallets and parked robots in view, so temporary maps are built) published by
# fleetmap-sim in real time on private multicast ports, one fleetmap-agent on it. After a
# 5 s warm-up the agent's CPU time (/proc/PID/stat utime + stime) and resident memory
# (/proc/PID/status VmRSS, sampled every second, the largest kept) are measured over
# DURATION_S seconds of wall time. Prints exactly:
#   agent.cpu_percent_25hz X %      (of one core; goal < 5)
#   agent.rss_mb Y MB               (goal < 50)
# Usage: bench/agent_process_bench.sh BUILD_DIR [DURATION_S]   (default 30 s)
# Needs multicast on loopback (scripts/setup_multicast.sh, root).
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help || $# -lt 1 ]]; then sed -n '2,11p' "$0"; exit 2; fi
build=$(cd "$1" && pwd)
duration=${2:-30}
root=$(cd "$(dirname "$0")/.." && pwd)
for p in fleetmap-sim fleetmap-agent; do
  [[ -x $build/bin/$p ]] || { echo "agent_process_bench: $build/bin/$p is missing: build it first" >&2; exit 1; }
done
"$root/scripts/setup_multicast.sh" >/dev/null ||
  { echo "agent_process_bench: no multicast on loopback: run scripts/setup_multicast.sh as root" >&2; exit 1; }

scenario=$root/sim/worlds/livinglab/addition.yaml
# shellcheck source=../scripts/lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
# Groups and ports of this benchmark only, so that a running demo or test does not interfere.
fleet_links 7981 0 239.255.78
work=$(mktemp -d)
agent="" sim=""
cleanup() {
  for p in $sim $agent; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

map=$(fleet_static_map "$build/bin" "$scenario")
vehicle=$(fleet_vehicles "$build/bin" "$scenario" | head -1)
id=${vehicle%% *}
fleet_agent_command "$build/bin" "$vehicle" "$map" "$work/state"
"${agent_command[@]}" --quiet >"$work/agent.txt" 2>&1 &
agent=$!
sleep 1
"$build/bin/fleetmap-sim" --scenario "$scenario" --speed 1 --duration $((duration + 10)) --no-truth \
  --lcm-url "$sensor" >"$work/sim.txt" 2>&1 &
sim=$!

cpu_ticks() { sed 's/^.*) //' "/proc/$agent/stat" | awk '{ print $12 + $13 }'; }  # utime + stime
rss_kb() { awk -v key="${1:-VmRSS}:" '$1 == key { print $2 }' "/proc/$agent/status"; }
now() { date +%s.%N; }

echo "agent_process_bench: $id on $(basename "$scenario"), 5 s warm-up, then ${duration} s" >&2
sleep 5
kill -0 "$agent" 2>/dev/null || { cat "$work/agent.txt" >&2; echo "agent_process_bench: the agent died" >&2; exit 1; }
t0=$(now) c0=$(cpu_ticks) rss_max=0 anon_max=0 file_max=0
for ((i = 0; i < duration; ++i)); do
  sleep 1
  r=$(rss_kb) a=$(rss_kb RssAnon) f=$(rss_kb RssFile)
  ((r > rss_max)) && rss_max=$r
  ((a > anon_max)) && anon_max=$a
  ((f > file_max)) && file_max=$f
done
t1=$(now) c1=$(cpu_ticks)
hz=$(getconf CLK_TCK)
kill -INT "$agent"
wait "$agent" || { cat "$work/agent.txt" >&2; echo "agent_process_bench: the agent failed" >&2; exit 1; }
agent=""
echo "agent_process_bench: $(tail -1 "$work/agent.txt")" >&2
# RSS is anonymous memory plus the file pages of the shared libraries it maps (OpenCV's image
# codecs alone bring about 140 libraries): both on stderr, for the record.
echo "agent_process_bench: largest RssAnon $((anon_max / 1024)) MB, RssFile $((file_max / 1024)) MB" >&2
awk -v c0="$c0" -v c1="$c1" -v t0="$t0" -v t1="$t1" -v hz="$hz" -v rss="$rss_max" 'BEGIN {
  printf "agent.cpu_percent_25hz %.2f %%\n", 100 * (c1 - c0) / hz / (t1 - t0)
  printf "agent.rss_mb %.1f MB\n", rss / 1024
}'
