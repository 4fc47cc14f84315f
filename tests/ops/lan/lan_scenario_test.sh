#!/usr/bin/env bash
# The LAN experiment's generated scenarios (ops/lan/lib/scenario.sh, ctest lan_scenario_test):
# for 1 to 20 vehicles, the whole fleet's scenario and each vehicle's own one load in
# fleetmap-sim (whose loader refuses a route through a wall), with the vehicles v1 .. vN, no two
# on the same route at the same start time, and each vehicle's own scenario starts that vehicle where the fleet's
# does. Needs no root.
#   tests/ops/lan/lan_scenario_test.sh BIN_DIR
set -uo pipefail
root=$(cd "$(dirname "$0")/../../.." && pwd)
bin=${1:?BIN_DIR}
# shellcheck source=../../../ops/lan/lib/scenario.sh
source "$root/ops/lan/lib/scenario.sh"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
map=$root/sim/worlds/livinglab/livinglab.yaml
fail=0
for n in 1 2 3 5 10 20; do
  lan_scenario "$n" 60 "$map" "$dir/fleet.yaml"
  if ! "$bin/fleetmap-sim" --scenario "$dir/fleet.yaml" --list-vehicles >"$dir/list.txt" 2>"$dir/err.txt"; then
    echo "FAIL: $n vehicles: $(cat "$dir/err.txt")"; fail=1; continue
  fi
  ids=$(grep -vc '^map ' "$dir/list.txt")
  poses=$(grep -v '^map ' "$dir/list.txt" | awk '{ print $2, $3 }' | sort -u | wc -l)
  [ "$ids" = "$n" ] || { echo "FAIL: $n vehicles: the scenario lists $ids"; fail=1; }
  # No two vehicles on the same route at the same time.
  same=$(awk '/^    route:/ { r = $0 } /^    start_s:/ { print r, $2 }' "$dir/fleet.yaml" | sort | uniq -d)
  [ -z "$same" ] || { echo "FAIL: $n vehicles: two drive '$same'"; fail=1; }
  for ((k = 1; k <= n; ++k)); do
    lan_scenario "$n" 60 "$map" "$dir/own.yaml" "$k"
    own=$("$bin/fleetmap-sim" --scenario "$dir/own.yaml" --vehicles "v$k" --list-vehicles 2>&1 | grep -v '^map ')
    want=$(grep "^v$k " "$dir/list.txt")
    [ "$own" = "$want" ] || { echo "FAIL: $n vehicles: v$k alone is '$own', in the fleet '$want'"; fail=1; }
  done
  echo "$n vehicles: routes clear of the walls, $poses distinct start poses"
done
[ "$fail" = 0 ] && echo "PASS"
exit "$fail"
