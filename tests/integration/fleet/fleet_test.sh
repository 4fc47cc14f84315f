#!/usr/bin/env bash
# The fleet's integration test (ctest fleet_*): the simulator, three fleetmap-agent processes
# and fleetmap-aggregator over real LCM UDP multicast on loopback (scripts/fleet_run.sh), on
# sim/worlds/livinglab/fleet_short.yaml (a pallet added, one added and taken away, a
# person walking). Checks, from fleetmap-eval's report of the recorded run, that the change
# detection is right (F1 of changed cells >= MIN_F1, no static cell erased), that every
# vehicle ends holding exactly the fleet's final map, and that replaying the uplink log gives
# the same map byte for byte.
#   tests/integration/fleet/fleet_test.sh BIN_DIR OUT_DIR PORT [--loss P] [--min-f1 F] [--speed X]
#                             [--replay-speeds "1 4 10"]
# Exits 77 (ctest: skipped) with the reason when multicast on loopback cannot be set up.
set -uo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
# shellcheck source=../../../scripts/lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
bin=${1:?BIN_DIR}; out=${2:?OUT_DIR}; port=${3:?PORT}; shift 3
loss=0 min_f1=0.95 speed=4 replay_speeds="1 4 10"
while [ $# -gt 0 ]; do
  case $1 in
    --loss) loss=$2; shift 2 ;;
    --min-f1) min_f1=$2; shift 2 ;;
    --speed) speed=$2; shift 2 ;;
    --replay-speeds) replay_speeds=$2; shift 2 ;;
    *) echo "fleet_test.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if ! "$root/scripts/setup_multicast.sh" >/dev/null 2>&1; then
  echo "SKIP: multicast on loopback cannot be set up here (scripts/setup_multicast.sh needs root)"
  exit 77
fi
if [ "$loss" != 0 ] && ! ip netns add fleetmap-probe-$$ 2>/dev/null; then
  echo "SKIP: network namespaces are not available (needed to drop packets)"
  exit 77
fi
ip netns del fleetmap-probe-$$ 2>/dev/null || true

rm -rf "$out"
"$root/scripts/fleet_run.sh" --scenario "$root/sim/worlds/livinglab/fleet_short.yaml" \
  --speed "$speed" --out "$out" --port "$port" --bin "$bin" --name fleet --loss "$loss"
rc=$?
[ -f "$out/figures.txt" ] || { echo "FAIL: the run wrote no figures (fleet_run.sh exit $rc)"; exit 1; }
cat "$out/figures.txt"
fail=0
figure() { awk -v k="$1" '$1 == k { print $2 }' "$out/figures.txt"; }
check() {  # NAME OP VALUE
  local v
  v=$(figure "$1")
  if [ -z "$v" ] || ! awk -v a="$v" -v b="$3" "BEGIN { exit !(a $2 b) }"; then
    echo "FAIL: $1 is '${v:-missing}', expected $2 $3"
    fail=1
  fi
}
check eval.fleet.changed_f1 '>=' "$min_f1"
check eval.fleet.static_erased '==' 0
check fleet.vehicle_maps_equal '==' 3
# Every vehicle's final map (written at its exit) equals the fleet's: the exact check that
# the added pallet is in every vehicle's map and the removed one gone. (The POSE_-based
# fleet.changes_not_everywhere also counts merges made after the vehicles' last scans.)
check replay.same_map '==' 1
# A lossy run must really have lost packets, or it proves nothing about loss.
[ "$loss" = 0 ] || check loss.dropped_packets '>' 0
[ "$rc" = 0 ] || { echo "FAIL: fleet_run.sh exited with $rc"; fail=1; }

# lcm-logplayer replaying the recorded uplink into a live aggregator, at the log's own speed
# and 4 and 10 times faster (lossless run only: the replay goes over loopback without loss),
# ends with the live run's map: a replay never resends, so no map may be dropped for coming
# too fast (vehicle_limits.h, held_maps.h).
if [ "$loss" = 0 ]; then
  fleet_links $((port + 5))  # the replays' own uplink and downlink
  static_map=$(fleet_static_map "$bin" "$root/sim/worlds/livinglab/fleet_short.yaml")
  live=$(grep '^aggregator: version' "$out/logs/aggregator.txt" | tail -1)
  live_merged=$(sed -n 's/.* merged \([0-9]*\) .*/\1/p' <<<"$live")
  for s in $replay_speeds; do
    fleet_aggregator_command "$bin" "$static_map"
    "${aggregator_command[@]}" >"$out/logs/logplayer_$s.txt" 2>&1 &
    aggregator=$!
    sleep 1
    lcm-logplayer -s "$s" -e 'TEMPMAP_.*|MAP_REQUEST|CANDIDATES_FREE_.*|CANDIDATES_HELD_.*' -l "$uplink" "$out/logs/uplink.lcmlog"
    # The aggregator may still be merging what came fastest (a sanitizer build is slow): stop
    # it once its progress line counts as many merges as the live run, or after 60 s.
    for _ in $(seq 120); do
      grep -q ": version [0-9]*, merged $live_merged, " "$out/logs/logplayer_$s.txt" && break
      sleep 0.5
    done
    kill -INT "$aggregator"
    wait "$aggregator"
    played=$(grep '^aggregator: version' "$out/logs/logplayer_$s.txt" | tail -1)
    if [ -n "$live" ] && [ "${live%% merged*}" = "${played%% merged*}" ]; then
      echo "logplayer -s $s: a live aggregator fed by lcm-logplayer ends with the same map ($played)"
    else
      echo "FAIL: lcm-logplayer -s $s into a live aggregator: '$played', the live run: '$live'"
      fail=1
    fi
  done
fi
for f in "$out"/logs/aggregator.txt "$out"/logs/agent_*.txt; do
  if grep -qiE 'sanitizer|runtime error|Assertion|terminate called' "$f"; then
    echo "FAIL: $f reports a crash or sanitizer error"; fail=1
  fi
done
[ "$fail" = 0 ] && echo "PASS"
exit "$fail"
