#!/usr/bin/env bash
# Runs the commands of docs/operations.md that can run on a test host (marked
# "[tested: operations_docs_test]" there), with a scratch folder and private multicast ports:
# a short simulated run of one vehicle recorded with fleetmap-record, `fleetmap-aggregator
# --replay` of the recording into a state folder, every fleetmap-mapctl command on it (each
# checked against the map it must give), the troubleshooting checks, and --help/--version
# of every program.
#   tests/integration/deploy/operations_test.sh SOURCE_DIR BIN_DIR [SPEED]   (simulated s per s, default 4)
# Exit status: 0 passed, 1 failed, 77 skipped (no multicast on loopback: needs root once).
set -uo pipefail
src=$(cd "${1:?usage: operations_test.sh SOURCE_DIR BIN_DIR}" && pwd)
# shellcheck source=../../../scripts/lib/fleet_launch.sh
source "$src/scripts/lib/fleet_launch.sh"
bin=$(cd "${2:?usage: operations_test.sh SOURCE_DIR BIN_DIR}" && pwd)
speed=${3:-4}
"$src/scripts/setup_multicast.sh" >/dev/null 2>&1 || { echo "SKIP: no multicast on loopback"; exit 77; }
work=$(mktemp -d "${TMPDIR:-/tmp}/fleetmap_ops.XXXXXX")
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }
mapctl() { "$bin/fleetmap-mapctl" --state-dir "$work/replayed" --map "$map" "$@"; }
same_map() {  # two exported maps hold the same cells (trinary PGMs, byte for byte)
  cmp -s "${1%.yaml}.pgm" "${2%.yaml}.pgm"
}

# --help and --version of every program (the installed ones: package_install_test).
for p in "$bin"/fleetmap-*; do
  name=$(basename "$p")
  "$p" --version | grep -q . || fail "$name --version"
  "$p" --help >/dev/null 2>&1 || fail "$name --help exits $?"
done
for c in export history rollback reset-region promote recover; do
  "$bin/fleetmap-mapctl" "$c" --help | grep -q "Usage: fleetmap-mapctl $c" || fail "mapctl $c --help"
done
pass "--help and --version"

# Options out of range are refused before any work, not run with.
out=$("$bin/fleetmap-carmen-eval" --carmen none.clf --relations none.relations --fine-iterations 0 2>&1)
rc=$?
[[ $rc == 2 && $out == *"scan matcher options out of range"* ]] || fail "carmen-eval took --fine-iterations 0 (exit $rc): $out"
out=$("$bin/fleetmap-eval" --scenario "$src/sim/worlds/livinglab/addition.yaml" --confirmations 3 2>&1)
rc=$?
[[ $rc == 2 && $out == *"--confirmations: 3 not in {1,2}"* ]] || fail "fleetmap-eval took --confirmations 3 (exit $rc): $out"
printf 'aggregator:\n  merge:\n    confirm_gap_s: 5\n' >"$work/bad_aggregator.yaml"
out=$("$bin/fleetmap-eval" --scenario "$src/sim/worlds/livinglab/addition.yaml" --pipeline agents --aggregator-config "$work/bad_aggregator.yaml" 2>&1)
rc=$?
[[ $rc != 0 && $out == *"aggregator.merge.confirm_gap_s: unknown key"* ]] || fail "fleetmap-eval took an aggregator configuration with an unknown key (exit $rc): $out"
out=$("$bin/fleetmap-sick-emulator" --scenario "$src/sim/worlds/livinglab/addition.yaml" --s300-out "$work/s300.bin" --count -5 2>&1)
rc=$?
[[ $rc == 2 && $out == *"--count"* && ! -e $work/s300.bin ]] || fail "sick-emulator took --count -5 (exit $rc): $out"
pass "options out of range refused"

# 2. Configure: the static map, the fleet key.
scenario=$src/sim/worlds/livinglab/addition.yaml
map=$src/sim/worlds/livinglab/livinglab.yaml
"$bin/fleetmap-maptool" info "$map" | grep -q "^cells: " || fail "fleetmap-maptool info"
if [[ -x $bin/fleetmap-keygen ]]; then
  "$bin/fleetmap-keygen" "$work/fleet.key" && [[ $(stat -c %a "$work/fleet.key") == 600 ]] ||
    fail "fleetmap-keygen: the key is not mode 600"
fi
pass "static map and key"

# 7. Troubleshoot: the route and the receive buffer (setup_multicast.sh made both right).
ip route show 224.0.0.0/4 | grep -q . || fail "ip route show 224.0.0.0/4 prints nothing"
(($(sysctl -n net.core.rmem_max) >= 8388608)) || fail "net.core.rmem_max below 8 MiB"
pass "route and receive buffer"

# 4. Record: a vehicle passes the pallets of the addition scenario (60 simulated s at SPEED),
# with the aggregator live and fleetmap-record on the uplink.
port=$((20000 + RANDOM % 5000))
fleet_links "$port"
"$bin/fleetmap-record" --quiet --lcm-url "$uplink" "$work/uplink.lcmlog" >"$work/logger.txt" 2>&1 &
logger=$!
pids+=($logger)
fleet_aggregator_command "$bin" "$map" "$work/live"
"${aggregator_command[@]}" --quiet >"$work/aggregator.txt" 2>&1 &
aggregator=$!
pids+=($aggregator)
vehicle=$(fleet_vehicles "$bin" "$scenario" | head -1)
id=${vehicle%% *}
fleet_agent_command "$bin" "$vehicle" "$map" "$work/agent"
"${agent_command[@]}" --quiet >"$work/agent.txt" 2>&1 &
agent=$!
pids+=($agent)
sleep 1
"$bin/fleetmap-sim" --scenario "$scenario" --speed "$speed" --duration 60 --lcm-url "$sensor" >/dev/null 2>&1 ||
  fail "fleetmap-sim"
sleep 3
kill -INT "$agent"
wait "$agent" || fail "agent exit status $?"
sleep 2
kill -INT "$logger"
wait "$logger"
kill -TERM "$aggregator"
wait "$aggregator" || fail "aggregator exit status $?"
live=$(grep '^aggregator: ' "$work/aggregator.txt")
[[ -s $work/uplink.lcmlog ]] || fail "fleetmap-record recorded nothing"
pass "recorded: $live"

# 4. Replay into a state folder of its own.
"$bin/fleetmap-aggregator" --map "$map" --replay "$work/uplink.lcmlog" --state-dir "$work/replayed" \
  --final-map "$work/replayed.yaml" --quiet >"$work/replay.txt" 2>&1 || fail "replay exits $?"
replayed=$(grep '^aggregator: ' "$work/replay.txt")
version=$(awk '{ print $3 }' <<<"$replayed")
((version >= 1)) || { fail "the replay merged nothing: $replayed (live: $live)"; exit 1; }
# A complete recording replays into the live run's map: the same version and hash.
[[ ${live%% merged*} == "${replayed%% merged*}" ]] ||
  fail "the replay differs from the live run: '$replayed' vs '$live'"
pass "replayed: $replayed"

# 5. mapctl history and export: one line per merge; the export is the replay's final map;
# version 0 is the static map.
mapctl history >"$work/history.txt" || fail "mapctl history"
[[ $(sed 1d "$work/history.txt" | wc -l) == "$version" ]] || fail "history: not $version merges"
sed -n 2p "$work/history.txt" | grep -qE "^1 [0-9.]+ $id [0-9]+ [0-9]+ " || fail "history line: $(sed -n 2p "$work/history.txt")"
mapctl export "$work/current.yaml" >/dev/null || fail "mapctl export"
[[ -s $work/current.png ]] || fail "export wrote no PNG"
same_map "$work/current.yaml" "$work/replayed.yaml" || fail "export differs from the replay's final map"
mapctl export "$work/v0.yaml" --at-version 0 >/dev/null || fail "mapctl export --at-version 0"
"$bin/fleetmap-maptool" diff "$map" "$work/v0.yaml" | grep -q . || fail "maptool diff"
before=$((version - 1))
mapctl export "$work/before.yaml" --at-version "$before" >/dev/null || fail "export --at-version $before"
pass "history ($version merges) and export"

# A running aggregator holds the folder: rollback is refused.
fleet_aggregator_command "$bin" "$map" "$work/replayed"
"${aggregator_command[@]}" --duration 4 --quiet >/dev/null 2>&1 &
holder=$!
pids+=($holder)
sleep 2
out=$(mapctl rollback 0 2>&1)
[[ $? == 1 && $out == *"in use"* ]] || fail "rollback while the aggregator runs: $out"
wait "$holder"
pass "rollback refused while the aggregator runs"

# Promote every standing obstacle: the new static map with the rewritten history is the
# same map.
mapctl promote --since-version "$version" --out-map "$work/static2.yaml" >/dev/null || fail "mapctl promote"
"$bin/fleetmap-mapctl" --state-dir "$work/replayed" --map "$work/static2.yaml" export "$work/promoted.yaml" >/dev/null ||
  fail "export after promote"
same_map "$work/promoted.yaml" "$work/current.yaml" || fail "promote changed the map"
ls "$work"/replayed/backup/promote-* >/dev/null 2>&1 || fail "promote kept no backup"
# Put the pre-promote state back (what an operator does with backup/), for the next steps.
cp "$work"/replayed/backup/promote-*/snapshot.fms "$work/replayed/snapshot.fms"
pass "promote"

# Roll back one version: the current map is the one exported at that version.
mapctl rollback "$before" >/dev/null || fail "mapctl rollback $before"
mapctl export "$work/rolled.yaml" >/dev/null
same_map "$work/rolled.yaml" "$work/before.yaml" || fail "rollback then export is not version $before"
pass "rollback to $before"

# Reset the whole hall: the static map again, one version more.
mapctl reset-region -1 -1 100 100 >/dev/null || fail "mapctl reset-region"
mapctl export "$work/reset.yaml" >/dev/null
same_map "$work/reset.yaml" "$work/v0.yaml" || fail "reset-region of the whole hall is not the static map"
[[ $(mapctl history | tail -1 | awk '{ print $1, $3 }') == "$version mapctl" ]] || fail "reset-region made no version"
pass "reset-region"

# A corrupt state file is named, not crashed on.
cp -r "$work/replayed" "$work/corrupt"
printf '\x55' | dd of="$work/corrupt/snapshot.fms" bs=1 seek=40 conv=notrunc 2>/dev/null
out=$("$bin/fleetmap-mapctl" --state-dir "$work/corrupt" --map "$map" history 2>&1)
[[ $? == 1 && $out == *DATA_LOSS* && $out == *snapshot.fms* ]] || fail "corrupt snapshot: $out"
pass "corrupt state named"

# The aggregator refuses that folder; mapctl recover keeps what can still be read (here
# nothing: the snapshot held every merge), keeps the damaged files in backup/, and the
# aggregator starts again on it. The maps sent again (the recorded uplink replayed, as the
# vehicles would resend them) bring back the live run's map.
out=$("$bin/fleetmap-aggregator" --map "$map" --state-dir "$work/corrupt" --replay "$work/uplink.lcmlog" --quiet 2>&1)
[[ $? == 1 && $out == *DATA_LOSS* ]] || fail "the aggregator on a damaged folder: $out"
out=$("$bin/fleetmap-mapctl" --state-dir "$work/corrupt" --map "$map" recover 2>&1)
[[ $? == 0 && $out == *"snapshot: damaged"* && $out == *"recovered: version 0"* ]] || fail "mapctl recover: $out"
ls "$work"/corrupt/backup/recover-*/snapshot.fms >/dev/null 2>&1 || fail "recover kept no backup"
[[ -s $work/corrupt/recovery ]] || fail "recover left no recovery marker"
fleet_aggregator_command "$bin" "$map" "$work/corrupt"
out=$("${aggregator_command[@]}" --duration 1 --quiet 2>&1)
[[ $out == *"was recovered at version 0: asking the vehicles"* ]] || fail "the aggregator after recover: $out"
resent=$("$bin/fleetmap-aggregator" --map "$map" --state-dir "$work/corrupt" --replay "$work/uplink.lcmlog" --quiet)
[[ ${resent%% merged*} == "${live%% merged*}" ]] || fail "after recover, the maps sent again: '$resent' vs '$live'"
out=$("$bin/fleetmap-mapctl" --state-dir "$work/corrupt" --map "$map" recover 2>&1)
[[ $? == 0 && $out == *"nothing damaged"* ]] || fail "recover on a sound folder: $out"
pass "recover"

if ((failures)); then
  echo "operations test: $failures failures"
  exit 1
fi
echo "operations test: passed"
