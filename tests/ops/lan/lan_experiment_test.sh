#!/usr/bin/env bash
# The LAN experiment's short version (ctest lan_experiment_test): 2 vehicle hosts and a server
# in network namespaces over a bridge, the wired profile, 20 simulated seconds
# (ops/lan/fleetmap-lan-experiment). Checks that temporary maps were delivered, that every
# vehicle ends holding the fleet's final map, that every host's interface counters moved, that
# the experiment refuses to run without root, and that it removes its namespaces when it is
# stopped by a signal half way.
#   tests/ops/lan/lan_experiment_test.sh BIN_DIR OUT_DIR
# Exits 77 (ctest: skipped) with the reason when namespaces, veth pairs or tc are not available.
set -uo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
bin=${1:?BIN_DIR}; out=${2:?OUT_DIR}
experiment=$root/ops/lan/fleetmap-lan-experiment
[ "$(id -u)" = 0 ] || { echo "SKIP: needs root (network namespaces, veth pairs, tc)"; exit 77; }
probe=fmlan-probe-$$
if ! ip netns add "$probe" 2>/dev/null; then
  echo "SKIP: network namespaces are not available here (ip netns add failed)"; exit 77
fi
trap 'ip netns del "$probe" 2>/dev/null' EXIT
if ! ip -n "$probe" link add name br0 type bridge 2>/dev/null ||
   ! ip -n "$probe" link add name p0 type veth peer name p1 2>/dev/null ||
   ! ip netns exec "$probe" tc qdisc add dev p0 root handle 1: htb default 10 2>/dev/null; then
  echo "SKIP: bridges, veth pairs or tc htb are not available in a namespace here"; exit 77
fi
ip netns del "$probe"
fail=0
no_namespaces_left() {  # PID
  if ip netns list | grep -q "^fmlan-$1-"; then
    echo "FAIL: namespaces of run $1 are left: $(ip netns list | grep "^fmlan-$1-" | tr '\n' ' ')"
    fail=1
  fi
}

# 1. Without root: a clear refusal (only where an unprivileged user can read the script).
if command -v setpriv >/dev/null && setpriv --reuid=65534 --regid=65534 --clear-groups test -r "$experiment"; then
  msg=$(setpriv --reuid=65534 --regid=65534 --clear-groups "$experiment" --bin "$bin" 2>&1)
  rc=$?
  if [ "$rc" != 1 ] || ! grep -q "needs root" <<<"$msg"; then
    echo "FAIL: without root: exit $rc, '$msg'"; fail=1
  fi
fi

# 2. The short experiment.
rm -rf "$out"
"$experiment" --vehicles 2 --duration 20 --profile wired --out "$out" --bin "$bin" >"$out.figures.txt" &
pid=$!
wait "$pid"
rc=$?
cat "$out.figures.txt"
no_namespaces_left "$pid"
[ "$rc" = 0 ] || { echo "FAIL: fleetmap-lan-experiment exited with $rc"; fail=1; }
figure() { awk -v k="lan.wired.v2.$1" '$1 == k { print $2 }' "$out.figures.txt"; }
check() {  # FIGURE OP VALUE
  local v
  v=$(figure "$1")
  if [ -z "$v" ] || ! awk -v a="$v" -v b="$3" "BEGIN { exit !(a $2 b) }"; then
    echo "FAIL: lan.wired.v2.$1 is '${v:-missing}', expected $2 $3"; fail=1
  fi
}
check tempmaps_delivered '>=' 1
check aggregator.maps_merged '>=' 1
check final_version '>=' 1
check vehicle_maps_equal '==' 2  # every agent's final map is the fleet's final map
check agents_reporting '==' 2
for host in server v1 v2; do
  for f in tx_bytes_per_s rx_bytes_per_s tx_packets_per_s rx_packets_per_s; do check "$f.$host" '>' 0; done
done
check channel_bytes_per_s.TEMPMAP_* '>' 0
check channel_bytes_per_s.MAP_DELTA '>' 0
check changes.occupancy_grid_bytes '>' 0
[ -s "$out/summary.csv" ] || { echo "FAIL: no $out/summary.csv"; fail=1; }
logs=$out/single/wired_v2/logs
[ -s "$logs/aggregator.txt" ] || { echo "FAIL: no aggregator output in $logs"; fail=1; }
for f in "$logs"/aggregator.txt "$logs"/agent_*.txt; do
  [ -f "$f" ] || continue
  if grep -qiE 'sanitizer|runtime error|Assertion|terminate called' "$f"; then
    echo "FAIL: $f reports a crash or sanitizer error"; fail=1
  fi
done

# 3. Stopped half way (SIGTERM: a background job ignores SIGINT): the namespaces go too.
"$experiment" --vehicles 1 --duration 30 --out "$out/interrupted" --bin "$bin" --quiet >/dev/null 2>&1 &
pid=$!
for _ in $(seq 100); do ip netns list | grep -q "^fmlan-$pid-v1" && break; sleep 0.1; done
ip netns list | grep -q "^fmlan-$pid-v1" || { echo "FAIL: the interrupted run never made its LAN"; fail=1; }
sleep 2
kill -TERM "$pid"
wait "$pid"
rc=$?
[ "$rc" = 130 ] || { echo "FAIL: the interrupted run exited with $rc, not 130"; fail=1; }
no_namespaces_left "$pid"

[ "$fail" = 0 ] && echo "PASS"
exit "$fail"
