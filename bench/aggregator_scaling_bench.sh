#!/usr/bin/env bash
# What fleetmap-aggregator costs with many vehicles: one aggregator process (the LivingLab
# map, a state folder as in the fleet) fed over multicast on loopback by
# fleetmap-bench-tempmap-publisher, whose N simulated vehicles each close a temporary map
# every 10 s: real temporary maps, every complete one the agents sent in a recorded fleet run
# (scripts/fleet_run.sh on fleet.yaml, recorded once into out/bench/fleet/ when missing, or
# FLEETMAP_BENCH_UPLINK_LOG). After a 10 s warm-up (every vehicle has sent a map) the
# aggregator's CPU time (/proc/PID/stat utime + stime) is measured over DURATION_S seconds of
# wall time, and its largest resident memory. Prints, for each N:
#   aggregator.cpu_percent_N_vehicles X %    (of one core; goal at 100: < 50)
#   aggregator.rss_mb_N_vehicles Y MB
# and on stderr the maps sent, merged and rejected.
# Usage: bench/aggregator_scaling_bench.sh BUILD_DIR [DURATION_S [N...]]   (60 s; 10 50 100)
# Needs multicast on loopback (scripts/setup_multicast.sh, root).
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help || $# -lt 1 ]]; then sed -n '2,14p' "$0"; exit 2; fi
build=$(cd "$1" && pwd)
duration=${2:-60}
shift $(($# >= 2 ? 2 : 1))
counts=("$@")
[[ ${#counts[@]} -eq 0 ]] && counts=(10 50 100)
root=$(cd "$(dirname "$0")/.." && pwd)
for p in fleetmap-aggregator fleetmap-bench-tempmap-publisher fleetmap-sim; do
  [[ -x $build/bin/$p ]] || { echo "aggregator_scaling_bench: $build/bin/$p is missing: build it first" >&2; exit 1; }
done
"$root/scripts/setup_multicast.sh" >/dev/null ||
  { echo "aggregator_scaling_bench: no multicast on loopback: run scripts/setup_multicast.sh as root" >&2; exit 1; }

uplink_log=${FLEETMAP_BENCH_UPLINK_LOG:-$root/out/bench/fleet/logs/uplink.lcmlog}
if [[ ! -s $uplink_log ]]; then
  echo "aggregator_scaling_bench: recording the temporary maps: scripts/fleet_run.sh into out/bench/fleet" >&2
  # Only the recorded uplink is used: fleet_run.sh's own checks (scores, replay) do not matter.
  mkdir -p "$root/out/bench"
  "$root/scripts/fleet_run.sh" --out "$root/out/bench/fleet" --port 7931 --bin "$build/bin" \
    --name bench_fleet >"$root/out/bench/fleet_run.txt" 2>&1 ||
    echo "aggregator_scaling_bench: fleet_run.sh reported a failure (out/bench/fleet_run.txt); using its uplink log" >&2
  uplink_log=$root/out/bench/fleet/logs/uplink.lcmlog
  [[ -s $uplink_log ]] ||
    { tail -20 "$root/out/bench/fleet_run.txt" >&2; echo "aggregator_scaling_bench: no uplink log recorded" >&2; exit 1; }
fi

# shellcheck source=../scripts/lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
fleet_links 7991 0 239.255.79  # groups and ports of this benchmark only
map=$(fleet_static_map "$build/bin" "$root/sim/worlds/livinglab/fleet.yaml")
work=$(mktemp -d)
aggregator="" publisher=""
cleanup() {
  for p in $publisher $aggregator; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
cpu_ticks() { sed 's/^.*) //' "/proc/$aggregator/stat" | awk '{ print $12 + $13 }'; }  # utime + stime
rss_kb() { awk '$1 == "VmRSS:" { print $2 }' "/proc/$aggregator/status"; }
now() { date +%s.%N; }
hz=$(getconf CLK_TCK)
warmup=10

for n in "${counts[@]}"; do
  rm -rf "$work/state"
  fleet_aggregator_command "$build/bin" "$map" "$work/state"
  "${aggregator_command[@]}" --quiet >"$work/aggregator.txt" 2>&1 &
  aggregator=$!
  sleep 1
  "$build/bin/fleetmap-bench-tempmap-publisher" --log "$uplink_log" --url "$uplink" --vehicles "$n" \
    --period 10 --duration $((warmup + duration)) >"$work/publisher.txt" 2>"$work/publisher_err.txt" &
  publisher=$!
  sleep "$warmup"
  kill -0 "$aggregator" 2>/dev/null || { cat "$work/aggregator.txt" >&2; echo "aggregator_scaling_bench: the aggregator died" >&2; exit 1; }
  t0=$(now) c0=$(cpu_ticks) rss_max=0
  for ((i = 0; i < duration; ++i)); do
    sleep 1
    r=$(rss_kb)
    ((r > rss_max)) && rss_max=$r
  done
  t1=$(now) c1=$(cpu_ticks)
  wait "$publisher" || { cat "$work/publisher_err.txt" >&2; echo "aggregator_scaling_bench: the publisher failed" >&2; exit 1; }
  publisher=""
  sleep 1  # the last map's tiles
  kill -INT "$aggregator"
  wait "$aggregator" || { cat "$work/aggregator.txt" >&2; echo "aggregator_scaling_bench: the aggregator failed" >&2; exit 1; }
  aggregator=""
  echo "aggregator_scaling_bench: $n vehicles: $(sed 's/tempmap-publisher: //' "$work/publisher.txt");" \
    "$(grep -o 'merged [0-9]* rejected [0-9]*' "$work/aggregator.txt" | tail -1)" >&2
  awk -v n="$n" -v c0="$c0" -v c1="$c1" -v t0="$t0" -v t1="$t1" -v hz="$hz" -v rss="$rss_max" 'BEGIN {
    printf "aggregator.cpu_percent_%d_vehicles %.2f %%\n", n, 100 * (c1 - c0) / hz / (t1 - t0)
    printf "aggregator.rss_mb_%d_vehicles %.1f MB\n", n, rss / 1024
  }'
done
