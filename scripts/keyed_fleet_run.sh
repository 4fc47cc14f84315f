#!/usr/bin/env bash
# The fleet over multicast on loopback with a fleet key on every process (docs/security.md):
# a new key (fleetmap-keygen), fleetmap-aggregator and one fleetmap-agent per vehicle with
# --key-file, fleetmap-sim at 4x, the three groups recorded; then fleetmap-eval scores the
# signed logs and `fleetmap-aggregator --replay --key-file` recomputes the map from them.
# The commands are those of scripts/fleet_run.sh (without packet loss), plus the key.
#   scripts/keyed_fleet_run.sh [BIN_DIR] [OUT_DIR] [PORT]      (defaults: build/bin out/keyed 7931)
# Prints the aggregator's final line, each agent's, the evaluation's figures and the replay's
# final line: the replay's map_hash equals the live one.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/bin}; out=${2:-$root/out/keyed}; port=${3:-7931}
"$root/scripts/setup_multicast.sh" >/dev/null || { echo "keyed_fleet_run.sh: no multicast on loopback (run as root)" >&2; exit 1; }
scenario=$root/tools/sim/worlds/livinglab/fleet_short.yaml
rm -rf "$out"; mkdir -p "$out"
url() { echo "udpm://$1:$2?ttl=0&recv_buf_size=8388608"; }
uplink=$(url 239.255.76.67 $port); downlink=$(url 239.255.76.68 $((port + 1))); sensor=$(url 239.255.76.69 $((port + 2)))
"$bin/fleetmap-keygen" "$out/fleet.key"
static_map=$("$bin/fleetmap-sim" --scenario "$scenario" --list-vehicles | sed -n 's/^map //p')
mapfile -t vehicles < <("$bin/fleetmap-sim" --scenario "$scenario" --list-vehicles | grep -v '^map ')
epoch=$(date +%s); loggers=()
for group in sensor uplink downlink; do
  "$bin/fleetmap-record" --force --quiet --lcm-url "${!group}" "$out/$group.lcmlog" >"$out/logger_$group.txt" 2>&1 &
  loggers+=($!)
done
"$bin/fleetmap-aggregator" --map "$static_map" --key-file "$out/fleet.key" --uplink-url "$uplink" --downlink-url "$downlink" > "$out/aggregator.txt" 2>&1 &
agg=$!
pids=()
for line in "${vehicles[@]}"; do
  read -r id x y theta mx my mtheta <<<"$line"
  "$bin/fleetmap-agent" --vehicle-id "$id" --map "$static_map" --initial-pose "$x,$y,$theta" --scanner-mount "$mx,$my,$mtheta" \
    --sensor-url "$sensor" --uplink-url "$uplink" --downlink-url "$downlink" --key-file "$out/fleet.key" --final-map "$out/$id.yaml" > "$out/agent_$id.txt" 2>&1 &
  pids+=($!)
  vehicle_maps+=(--vehicle-map "$id=$out/$id.yaml")
done
sleep 1
"$bin/fleetmap-sim" --scenario "$scenario" --speed 4 --epoch "$epoch" --lcm-url "$sensor" > "$out/sim.txt" 2>&1
sleep 5
for p in "${pids[@]}"; do kill -INT "$p"; done; wait "${pids[@]}"
kill -INT $agg; wait $agg
for p in "${loggers[@]}"; do kill -INT "$p"; done; wait "${loggers[@]}"
duration=$(sed -n 's/^duration_s: *//p' "$scenario")
"$bin/fleetmap-eval" --scenario "$scenario" --lcm-log "$out/sensor.lcmlog" --lcm-log "$out/uplink.lcmlog" --lcm-log "$out/downlink.lcmlog" \
  --epoch "$epoch" --duration "$duration" --key-file "$out/fleet.key" "${vehicle_maps[@]}" --out "$out" --name keyed --quiet > "$out/figures.txt"
grep -E "f1|malformed|merged|same|equal" "$out/figures.txt" | head -20
"$bin/fleetmap-aggregator" --map "$static_map" --key-file "$out/fleet.key" --replay "$out/uplink.lcmlog" --quiet | tail -1
tail -2 "$out/aggregator.txt"; for f in "$out"/agent_*.txt; do echo "$f: $(tail -1 "$f")"; done
