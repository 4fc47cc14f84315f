#!/usr/bin/env bash
# Runs the whole fleet on this host over real LCM UDP multicast on loopback, as on vehicles:
# fleetmap-sim publishes every vehicle's SCAN_/ODOM_ (sensor group), one fleetmap-agent per
# vehicle sends temporary maps (uplink group), fleetmap-aggregator merges them and sends the
# changes back (downlink group); fleetmap-record records each group (lcm-logger's format;
# unlike lcm-logger it loses no message when the CPU is busy). Then fleetmap-eval scores the
# recorded run against the simulator's truth, and `fleetmap-aggregator --replay` recomputes
# the final map from the uplink log to show that it is the same, byte for byte.
#
#   scripts/fleet_run.sh [--scenario FILE] [--speed X] [--duration S] [--out DIR]
#                        [--port P] [--bin DIR] [--name NAME] [--loss P] [--key]
#     --scenario FILE  scenario YAML             [sim/worlds/livinglab/fleet.yaml]
#     --speed X        simulated seconds per wall-clock second                     [4]
#     --duration S     simulated seconds                     [the scenario's duration]
#     --out DIR        results folder (its logs/, maps/ and state/ are replaced)   [out]
#     --port P         uplink UDP port; downlink P+1, sensor P+2                 [7667]
#     --bin DIR        where the fleetmap programs are                   [build/bin]
#     --name NAME      name of the figure lines                                 [demo]
#     --loss P         drop a share P (0..1) of the uplink and downlink packets: the
#                      fleet then runs in its own network namespace whose loopback drops
#                      them (tc: HTB + a random classic-BPF filter, for kernels without
#                      netem); the sensor group (on the vehicle) is spared          [0]
#     --key            a new fleet key (fleetmap-keygen, OUT/fleet.key) on every process:
#                      everything sent is signed, only verified messages count, and the
#                      evaluation and the replay check the signatures (docs/security.md)
#     --programs       print the programs this script runs (the build targets run_demo.sh
#                      builds), one a line, and exit
# Needs multicast on loopback: scripts/setup_multicast.sh (root) sets it up and says why.
# Exit status: 0 when every step ran and the replay matched; 1 otherwise.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
# shellcheck source=lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
# Every program run below as "$bin/NAME": the one list (run_demo.sh builds it; fleet_test checks
# it against the script's commands).
programs=(fleetmap-sim fleetmap-agent fleetmap-aggregator fleetmap-eval fleetmap-record fleetmap-keygen)
scenario=$root/sim/worlds/livinglab/fleet.yaml
speed=4 duration="" out=out port=7667 bin=$root/build/bin name=demo loss=0 key=0
while [ $# -gt 0 ]; do
  case $1 in
    --scenario) scenario=${2:?}; shift 2 ;;
    --speed) speed=${2:?}; shift 2 ;;
    --duration) duration=${2:?}; shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    --port) port=${2:?}; shift 2 ;;
    --bin) bin=${2:?}; shift 2 ;;
    --name) name=${2:?}; shift 2 ;;
    --loss) loss=${2:?}; shift 2 ;;
    --programs) printf '%s\n' "${programs[@]}"; exit 0 ;;
    --key) key=1; shift ;;
    -h | --help) sed -n '2,29p' "$0"; exit 0 ;;
    *) echo "fleet_run.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for p in "${programs[@]}"; do
  [ -x "$bin/$p" ] || { echo "fleet_run.sh: $bin/$p is missing: build first" >&2; exit 1; }
done

# Multicast on loopback: LCM needs a route for 224.0.0.0/4 and a receive buffer large enough
# for bursts of map tiles (scripts/setup_multicast.sh says more).
"$root/scripts/setup_multicast.sh" >/dev/null || {
  echo "fleet_run.sh: multicast on loopback is not set up; run scripts/setup_multicast.sh as root" >&2
  exit 1
}
# With --loss, everything runs in a namespace of its own whose loopback loses packets.
netns="" run=()
lossy_namespace() {
  netns=fleetmap-run-$$
  ip netns add "$netns" || { echo "fleet_run.sh: --loss needs root (ip netns)" >&2; exit 1; }
  run=(ip netns exec "$netns")
  "${run[@]}" ip link set lo up
  "${run[@]}" ip link set lo multicast on
  "${run[@]}" ip route add 224.0.0.0/4 dev lo
  # Packets the filter matches go to class 1:20, whose queue holds nothing: dropped. The
  # classic-BPF program: load the UDP destination port (14-byte link header + 20-byte IP
  # header + 2); the sensor port passes; otherwise match when a random 32-bit number is
  # below P * 2^32.
  local threshold
  threshold=$(awk -v p="$loss" 'BEGIN { if (p < 0 || p > 1) exit 1; printf "%.0f", p * 4294967296 }') ||
    { echo "fleet_run.sh: --loss takes a share between 0 and 1" >&2; exit 2; }
  [ "$threshold" -lt 4294967296 ] || threshold=4294967295
  "${run[@]}" tc qdisc add dev lo root handle 1: htb default 10 2>/dev/null
  "${run[@]}" tc class add dev lo parent 1: classid 1:10 htb rate 10gbit 2>/dev/null
  "${run[@]}" tc class add dev lo parent 1: classid 1:20 htb rate 10gbit 2>/dev/null
  "${run[@]}" tc qdisc add dev lo parent 1:20 handle 20: pfifo limit 0
  "${run[@]}" tc filter add dev lo parent 1: prio 1 bpf bytecode \
    "6,40 0 0 36,21 3 0 $((port + 2)),32 0 0 4294963256,53 1 0 $threshold,6 0 0 4294967295,6 0 0 0" \
    classid 1:20
}
dropped_packets() {
  "${run[@]}" tc -s qdisc show dev lo | awk '/^qdisc pfifo 20:/ { getline; for (i = 1; i <= NF; ++i) if ($i == "(dropped") print $(i + 1) }' | tr -d ,
}
[ "$loss" = 0 ] || lossy_namespace

fleet_links "$port"  # ttl=0: nothing leaves this host

mkdir -p "$out"
rm -rf "$out/logs" "$out/maps" "$out/state"
mkdir -p "$out/logs" "$out/maps" "$out/state"
static_map=$(fleet_static_map "$bin" "$scenario")
keyed=()  # --key-file for every process, with --key
if ((key)); then
  rm -f "$out/fleet.key"
  "$bin/fleetmap-keygen" "$out/fleet.key" >/dev/null
  keyed=(--key-file "$out/fleet.key")
fi
mapfile -t vehicles < <(fleet_vehicles "$bin" "$scenario")

declare -a loggers agents
aggregator=""
cleanup() {
  for p in "${agents[@]}" $aggregator "${loggers[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  [ -z "$netns" ] || ip netns del "$netns" 2>/dev/null || true
}
trap cleanup EXIT
trap 'echo "fleet_run.sh: interrupted" >&2; exit 130' INT TERM

epoch=$(date +%s)
echo "$epoch" >"$out/logs/epoch.txt"  # fleetmap-eval --epoch: message stamps - epoch = simulated s
for group in sensor uplink downlink; do
  "${run[@]}" "$bin/fleetmap-record" --force --quiet --lcm-url "${!group}" \
    "$out/logs/$group.lcmlog" >"$out/logs/logger_$group.txt" 2>&1 &
  loggers+=($!)
done
fleet_aggregator_command "$bin" "$static_map" "$out/state/aggregator"
"${run[@]}" "${aggregator_command[@]}" "${keyed[@]}" --final-map "$out/maps/aggregator.yaml" \
  >"$out/logs/aggregator.txt" 2>&1 &
aggregator=$!
vehicle_maps=()
for line in "${vehicles[@]}"; do
  read -r id _ <<<"$line"
  fleet_agent_command "$bin" "$line" "$static_map" "$out/state/$id"
  "${run[@]}" "${agent_command[@]}" --final-map "$out/maps/$id.yaml" --quiet "${keyed[@]}" \
    >"$out/logs/agent_$id.txt" 2>&1 &
  agents+=($!)
  vehicle_maps+=(--vehicle-map "$id=$out/maps/$id.yaml")
done
sleep 1  # every subscriber has joined its group before the first scan
echo "fleet: aggregator and ${#vehicles[@]} agents up; simulating at ${speed}x (progress every 10 simulated s)"
"${run[@]}" "$bin/fleetmap-sim" --scenario "$scenario" --speed "$speed" --epoch "$epoch" \
  ${duration:+--duration "$duration"} --lcm-url "$sensor" 2>&1 | sed 's/^/  /'
[ -n "$duration" ] || duration=$(sed -n 's/^duration_s: *//p' "$scenario")

# Let the last temporary maps and changes travel, then stop the agents (each writes the map
# it holds), then the aggregator (it writes the current map), then the loggers. On a lossy
# link the last tiles take a few resend rounds (one a second while tiles get through).
if [ "$loss" = 0 ]; then sleep 3; else sleep 8; fi
for p in "${agents[@]}"; do kill -INT "$p" 2>/dev/null || true; done
for p in "${agents[@]}"; do wait "$p" || echo "fleet_run.sh: an agent exited with $?" >&2; done
agents=()
sleep 1
kill -INT "$aggregator"
wait "$aggregator" || echo "fleet_run.sh: the aggregator exited with $?" >&2
aggregator=""
sleep 0.5
for p in "${loggers[@]}"; do kill -INT "$p" 2>/dev/null || true; done
wait
loggers=()
live=$(grep '^aggregator: version' "$out/logs/aggregator.txt" | tail -1 || true)
echo "fleet: stopped; $live"
[ -z "$netns" ] || echo "loss.dropped_packets $(dropped_packets) packets" | tee -a "$out/logs/loss.txt"

echo "fleet: scoring the recorded run"
"$bin/fleetmap-eval" --scenario "$scenario" --lcm-log "$out/logs/sensor.lcmlog" \
  --lcm-log "$out/logs/uplink.lcmlog" --lcm-log "$out/logs/downlink.lcmlog" \
  --epoch "$epoch" --duration "$duration" "${vehicle_maps[@]}" "${keyed[@]}" --out "$out" \
  --name "$name" --quiet >"$out/figures.txt"
[ -z "$netns" ] || cat "$out/logs/loss.txt" >>"$out/figures.txt"

echo "fleet: replaying the uplink log into a fresh aggregator"
"$bin/fleetmap-aggregator" --map "$static_map" --replay "$out/logs/uplink.lcmlog" "${keyed[@]}" \
  --final-map "$out/maps/replay.yaml" --quiet >"$out/logs/replay.txt" 2>&1
replayed=$(grep '^aggregator: version' "$out/logs/replay.txt" | tail -1 || true)
if [ -n "$live" ] && [ "${live%% merged*}" = "${replayed%% merged*}" ]; then
  echo "replay.same_map 1 bool" >>"$out/figures.txt"
  echo "fleet: the replay gives the same map ($replayed)"
else
  echo "replay.same_map 0 bool" >>"$out/figures.txt"
  echo "fleet: the replay DIFFERS: live '$live', replay '$replayed'" >&2
  exit 1
fi
