#!/usr/bin/env bash
# What the downlink costs on a large site: fleetmap-aggregator on a generated racked hall of
# about 12M and 44M cells (fleetmap-worldgen, 150 m x 80 m at 0.03 m and 150 m x 110 m at
# 0.02 m; kept in out/bench/scale/), over multicast on loopback, and three vehicles joining
# without a map (fleetmap-agent without --map, no sensors), 2 s apart, each asking for the whole
# map, while three others send a temporary map every 5 s each (fleetmap-bench-tempmap-publisher:
# the recorded temporary maps of a LivingLab fleet run, as bench/aggregator_scaling_bench.sh,
# so on this hall they are answered, mostly REJECTED, not merged). Both links are recorded
# (fleetmap-record) and read back (fleetmap-lan-tool status, acks). Prints, for each size S
# (12m, 40m):
#   scale.S.map_cells N cells
#   scale.S.aggregator_start_s X s        launch -> "listening" (the map loaded, tiled)
#   scale.S.aggregator_rss_mb X MB        after the vehicles joined
#   scale.S.new_agent_full_map_s X s      agent launch -> "map version V held" (its replica
#                                         complete), the slowest of the three
#   scale.S.new_agent_map_in_use_s X s    agent launch -> "map version V in use" (its scan
#                                         models built too), the slowest; three agents on two
#                                         cores share them while building
#   scale.S.downlink_bytes_per_s X B/s    bytes the aggregator sent / seconds it ran
#   scale.S.downlink_dropped N count      messages its downlink queue refused
#   scale.S.ack_delay_p95_s X s           a temporary map's last tile -> its final ack, p95
#                                         (and .ack_delay_max_s), while the keyframes go out
# and on stderr each agent's time. The agents' own cost is not measured here.
# FLEETMAP_BENCH_KEEP=DIR keeps the logs (the last size's) there.
# Usage: bench/downlink_scale_bench.sh BUILD_DIR [S...]   (12m 40m)
# Needs multicast on loopback (scripts/setup_multicast.sh, root).
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help || $# -lt 1 ]]; then sed -n '2,26p' "$0"; exit 2; fi
build=$(cd "$1" && pwd)
shift
sizes=("$@")
[[ ${#sizes[@]} -eq 0 ]] && sizes=(12m 40m)
root=$(cd "$(dirname "$0")/.." && pwd)
for p in fleetmap-aggregator fleetmap-agent fleetmap-worldgen fleetmap-record fleetmap-lan-tool \
  fleetmap-bench-tempmap-publisher; do
  [[ -x $build/bin/$p ]] || { echo "downlink_scale_bench: $build/bin/$p is missing: build it first" >&2; exit 1; }
done
"$root/scripts/setup_multicast.sh" >/dev/null ||
  { echo "downlink_scale_bench: no multicast on loopback: run scripts/setup_multicast.sh as root" >&2; exit 1; }
uplink_log=${FLEETMAP_BENCH_UPLINK_LOG:-$root/out/bench/fleet/logs/uplink.lcmlog}
[[ -s $uplink_log ]] || { echo "downlink_scale_bench: no temporary maps to send: $uplink_log is missing (bench/aggregator_scaling_bench.sh records it)" >&2; exit 1; }
# shellcheck source=../scripts/lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
fleet_links 7995 0 239.255.79  # groups and ports of this benchmark only
maps=$root/out/bench/scale
mkdir -p "$maps"
work=$(mktemp -d)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  [[ -n ${FLEETMAP_BENCH_KEEP:-} ]] && cp -r "$work/." "$FLEETMAP_BENCH_KEEP/"
  rm -rf "$work"
}
trap cleanup EXIT
now() { date +%s.%N; }
rss_kb() { awk '$1 == "VmRSS:" { print $2 }' "/proc/$1/status"; }
# stamped: every line of stdin with the time it was read in front.
stamped() { while IFS= read -r line; do printf '%s %s\n' "$(now)" "$line"; done; }
# wait_for FILE PATTERN TIMEOUT_S: the stamp of the first line of FILE (written by stamped)
# that matches, or nothing after the timeout.
wait_for() {
  local deadline
  deadline=$(awk -v t="$(now)" -v d="$3" 'BEGIN { printf "%.3f", t + d }')
  while awk -v t="$(now)" -v d="$deadline" 'BEGIN { exit !(t < d) }'; do
    if grep -q "$2" "$1" 2>/dev/null; then grep -m1 "$2" "$1" | cut -d' ' -f1; return 0; fi
    sleep 0.05
  done
  return 1
}

for size in "${sizes[@]}"; do
  case $size in
    12m) dims=(--length 150 --width 80 --resolution 0.03) ;;
    40m) dims=(--length 150 --width 110 --resolution 0.02) ;;
    *) echo "downlink_scale_bench: unknown size '$size' (12m or 40m)" >&2; exit 2 ;;
  esac
  map=$maps/hall_$size.yaml
  if [[ ! -s $map ]]; then
    echo "downlink_scale_bench: generating $map" >&2
    "$build/bin/fleetmap-worldgen" --style racked_warehouse --seed 1 "${dims[@]}" --no-png \
      --vehicles 1 "$map" >"$work/worldgen.txt" 2>&1 || { cat "$work/worldgen.txt" >&2; exit 1; }
  fi
  cells=$(awk 'NR == 2 { print $1 * $2 }' "${map%.yaml}.pgm")
  rm -f "$work"/*.txt "$work"/*.lcmlog
  "$build/bin/fleetmap-record" --lcm-url "$downlink" --quiet "$work/downlink.lcmlog" \
    >"$work/record.txt" 2>&1 &
  recorder=$!
  "$build/bin/fleetmap-record" --lcm-url "$uplink" --quiet \
    "$work/uplink.lcmlog" >"$work/record_uplink.txt" 2>&1 &
  recorder_uplink=$!
  pids=("$recorder" "$recorder_uplink")
  sleep 0.5
  fleet_aggregator_command "$build/bin" "$map" ""
  t_launch=$(now)
  "${aggregator_command[@]}" > >(stamped >"$work/aggregator.txt") 2>&1 &
  aggregator=$!
  pids+=("$aggregator")
  t_ready=$(wait_for "$work/aggregator.txt" "listening on" 120) ||
    { cat "$work/aggregator.txt" >&2; echo "downlink_scale_bench: the aggregator did not start" >&2; exit 1; }
  "$build/bin/fleetmap-bench-tempmap-publisher" --log "$uplink_log" --url "$uplink" --vehicles 3 \
    --period 5 --duration 40 >"$work/publisher.txt" 2>&1 &
  publisher=$!
  pids+=("$publisher")
  agents=()
  launched=()
  for i in 1 2 3; do
    launched+=("$(now)")
    "$build/bin/fleetmap-agent" --vehicle-id "scale$i" --uplink-url "$uplink" --downlink-url "$downlink" \
      --sensor-url "$sensor" > >(stamped >"$work/agent$i.txt") 2>&1 &
    agents+=($!)
    pids+=($!)
    sleep 2
  done
  held=0 in_use=0
  for i in 1 2 3; do
    t=$(wait_for "$work/agent$i.txt" "map version [0-9]* held" 120) ||
      { tail -5 "$work/agent$i.txt" >&2; echo "downlink_scale_bench: agent $i never held the map" >&2; exit 1; }
    took=$(awk -v a="${launched[i - 1]}" -v b="$t" 'BEGIN { printf "%.2f", b - a }')
    held=$(awk -v a="$held" -v b="$took" 'BEGIN { print (b > a ? b : a) }')
    t=$(wait_for "$work/agent$i.txt" "map version [0-9]* in use" 120) ||
      { tail -5 "$work/agent$i.txt" >&2; echo "downlink_scale_bench: agent $i never used the map" >&2; exit 1; }
    used=$(awk -v a="${launched[i - 1]}" -v b="$t" 'BEGIN { printf "%.2f", b - a }')
    in_use=$(awk -v a="$in_use" -v b="$used" 'BEGIN { print (b > a ? b : a) }')
    echo "downlink_scale_bench: $size: agent $i held the map $took s after its start, used it after $used s" >&2
  done
  rss=$(rss_kb "$aggregator")
  wait "$publisher" || { cat "$work/publisher.txt" >&2; echo "downlink_scale_bench: the publisher failed" >&2; exit 1; }
  sleep 2  # the last map's answer, a last STATUS
  kill -INT "$aggregator"
  wait "$aggregator" || true
  t_end=$(now)
  for a in "${agents[@]}"; do kill -INT "$a" 2>/dev/null || true; done
  for a in "${agents[@]}"; do wait "$a" 2>/dev/null || true; done
  kill -INT "$recorder" "$recorder_uplink"
  wait "$recorder" "$recorder_uplink" || true
  pids=()
  "$build/bin/fleetmap-lan-tool" status "$work/downlink.lcmlog" "$work/uplink.lcmlog" >"$work/status.txt"
  "$build/bin/fleetmap-lan-tool" acks "$work/uplink.lcmlog" "$work/downlink.lcmlog" >"$work/acks.txt"
  ack() { awk -v k="acks.$1" '$1 == k { print $2; f = 1 } END { if (!f) print "nan" }' "$work/acks.txt"; }
  echo "downlink_scale_bench: $size: $(tr '\n' ' ' <"$work/acks.txt")" >&2
  counter() { awk -v k="status.aggregator.$1" '$1 == k { print $2; f = 1 } END { if (!f) print "nan" }' "$work/status.txt"; }
  awk -v s="$size" -v cells="$cells" -v l="$t_launch" -v r="$t_ready" -v e="$t_end" -v rss="$rss" \
    -v ack_p95="$(ack delay_s.p95)" -v ack_max="$(ack delay_s.max)" \
    -v held="$held" -v in_use="$in_use" -v bytes="$(counter bytes_sent)" -v dropped="$(counter publish_failures)" 'BEGIN {
    printf "scale.%s.map_cells %d cells\n", s, cells
    printf "scale.%s.aggregator_start_s %.2f s\n", s, r - l
    printf "scale.%s.aggregator_rss_mb %.1f MB\n", s, rss / 1024
    printf "scale.%s.new_agent_full_map_s %.2f s\n", s, held
    printf "scale.%s.new_agent_map_in_use_s %.2f s\n", s, in_use
    printf "scale.%s.downlink_bytes_per_s %.0f B/s\n", s, bytes / (e - r)
    printf "scale.%s.downlink_dropped %s count\n", s, dropped
    printf "scale.%s.ack_delay_p95_s %s s\n", s, ack_p95
    printf "scale.%s.ack_delay_max_s %s s\n", s, ack_max
  }'
done
