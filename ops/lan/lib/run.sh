# shellcheck shell=bash
# One LAN experiment run (sourced by fleetmap-lan-experiment; needs net.sh and the globals
# ROOT, BIN, SPEED, SETTLE_S, QUIET).
#
#   lan_run DIR SCENARIO PROFILE PREFIX [STATIC_MAP]
#
# In DIR: logs/ (lcm-logger's uplink.lcmlog and downlink.lcmlog, every process's output),
# maps/ (the aggregator's and every agent's final map), state/, eval/ (fleetmap-eval's
# report), counters.txt (lan0 counters of every host before and after), figures.txt (the run's
# `PREFIX.<figure> value unit` lines, docs/lan_experiments.md; figures_raw.txt without PREFIX).
# STATIC_MAP (default: the scenario's) is what the simulators, agents and aggregator load.

lan_log() { [ "${QUIET:-0}" = 1 ] || echo "lan: $*" >&2; }

# lan_run_processes DIR SCENARIO PROFILE STATIC_MAP: runs the fleet; sets RUN_WALL_S.
lan_run_processes() {
  local dir=$1 scenario=$2 profile=$3 map=$4
  local uplink downlink sensor epoch line id k=0 t0 t1
  local -a vehicles srv loggers=() agents=() sims=() agent_command aggregator_command
  mapfile -t vehicles < <(fleet_vehicles "$BIN" "$scenario" "$map")
  fleet_links 7667 1  # ttl=1: across the bridge, no further (docs/channels.md)
  lan_create "${#vehicles[@]}" || return 1
  lan_shape_all "${#vehicles[@]}" "$profile" || return 1
  srv=(ip netns exec "$(lan_ns srv)")
  epoch=$(date +%s)
  echo "$epoch" >"$dir/logs/epoch.txt"
  "${srv[@]}" lcm-logger -f --lcm-url="$uplink" "$dir/logs/uplink.lcmlog" >"$dir/logs/logger_uplink.txt" 2>&1 &
  loggers+=($!)
  "${srv[@]}" lcm-logger -f --lcm-url="$downlink" "$dir/logs/downlink.lcmlog" >"$dir/logs/logger_downlink.txt" 2>&1 &
  loggers+=($!)
  fleet_aggregator_command "$BIN" "$map" "$dir/state/aggregator"
  "${srv[@]}" "${aggregator_command[@]}" --final-map "$dir/maps/aggregator.yaml" \
    >"$dir/logs/aggregator.txt" 2>&1 &
  local aggregator=$!
  LAN_PIDS=("${loggers[@]}" "$aggregator")
  for line in "${vehicles[@]}"; do
    read -r id _ <<<"$line"
    k=$((k + 1))
    fleet_agent_command "$BIN" "$line" "$map" "$dir/state/$id"
    ip netns exec "$(lan_ns "v$k")" "${agent_command[@]}" --final-map "$dir/maps/$id.yaml" \
      --quiet >"$dir/logs/agent_$id.txt" 2>&1 &
    agents+=($!)
    echo "$id v$k" >>"$dir/hosts.txt"
  done
  LAN_PIDS+=("${agents[@]}")
  sleep 2  # every subscriber has joined its group, every agent has loaded the map
  lan_counters srv $(awk '{ print $2 }' "$dir/hosts.txt") | sed 's/^/before /' >"$dir/counters.txt"
  t0=$(date +%s.%N)
  k=0
  lan_log "${#vehicles[@]} vehicles ($profile): simulating $DURATION s at ${SPEED}x"
  for line in "${vehicles[@]}"; do
    read -r id _ <<<"$line"
    k=$((k + 1))
    local own=$scenario  # the vehicle's own scenario when there is one (lib/scenario.sh)
    [ -f "${scenario%.yaml}_v$k.yaml" ] && own=${scenario%.yaml}_v$k.yaml
    ip netns exec "$(lan_ns "v$k")" "$BIN/fleetmap-sim" --scenario "$own" --map "$map" \
      --vehicles "$id" --speed "$SPEED" --duration "$DURATION" --epoch "$epoch" \
      --lcm-url "$sensor" >"$dir/logs/sim_$id.txt" 2>&1 &
    sims+=($!)
  done
  LAN_PIDS+=("${sims[@]}")
  local failed=0 p
  for p in "${sims[@]}"; do wait "$p" || failed=1; done
  t1=$(date +%s.%N)
  lan_counters srv $(awk '{ print $2 }' "$dir/hosts.txt") | sed 's/^/after /' >>"$dir/counters.txt"
  RUN_WALL_S=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  echo "$RUN_WALL_S" >"$dir/logs/wall_s.txt"
  [ "$failed" = 0 ] || lan_log "a simulator failed (see $dir/logs/sim_*.txt)"
  # Temporary maps closed in the last seconds travel and merge, changes reach the vehicles.
  sleep "$SETTLE_S"
  # The aggregator stops first: its last version is the fleet's final map, and what the
  # agents flush at their stop (a map being built) stays pending, as after a real shutdown.
  date +%s%6N >"$dir/logs/stop_utime.txt"
  kill -INT "$aggregator" 2>/dev/null
  wait "$aggregator" || lan_log "the aggregator exited with $?"
  for p in "${agents[@]}"; do kill -INT "$p" 2>/dev/null; done
  for p in "${agents[@]}"; do wait "$p" || lan_log "an agent exited with $?"; done
  sleep 0.5
  for p in "${loggers[@]}"; do kill -INT "$p" 2>/dev/null; done
  for p in "${loggers[@]}"; do wait "$p" 2>/dev/null; done
  LAN_PIDS=()
  read -r LAN_LOSS_DROPS LAN_RATE_DROPS < <(lan_tc_drops)
  lan_destroy
  return "$failed"
}

# Per host rates from counters.txt over RUN_WALL_S: "host tx_Bps rx_Bps tx_pps rx_pps", the
# host named "server" or by its vehicle id.
lan_host_rates() {
  awk -v w="$RUN_WALL_S" '
    FILENAME ~ /hosts.txt$/ { name[$2] = $1; next }
    $1 == "before" { tb[$2] = $3; rb[$2] = $4; tp[$2] = $5; rp[$2] = $6; order[++n] = $2 }
    $1 == "after" { ta[$2] = $3; ra[$2] = $4; pa[$2] = $5; qa[$2] = $6 }
    END { name["srv"] = "server"
          for (i = 1; i <= n; ++i) { h = order[i]
            printf "%s %.1f %.1f %.2f %.2f\n", name[h], (ta[h] - tb[h]) / w, (ra[h] - rb[h]) / w,
                   (pa[h] - tp[h]) / w, (qa[h] - rp[h]) / w } }' "$1/hosts.txt" "$1/counters.txt"
}

# lan_figures DIR PREFIX SCENARIO STATIC_MAP: scores the run, writes figures.txt.
lan_figures() {
  local dir=$1 prefix=$2 scenario=$3 map=$4 epoch stop id
  local -a vehicle_maps=()
  epoch=$(cat "$dir/logs/epoch.txt")
  stop=$(cat "$dir/logs/stop_utime.txt")
  while read -r id _; do vehicle_maps+=(--vehicle-map "$id=$dir/maps/$id.yaml"); done <"$dir/hosts.txt"
  "$BIN/fleetmap-eval" --scenario "$scenario" --map "$map" --lcm-log "$dir/logs/uplink.lcmlog" \
    --lcm-log "$dir/logs/downlink.lcmlog" --epoch "$epoch" --duration "$DURATION" \
    "${vehicle_maps[@]}" --out "$dir/eval" --name lan --quiet >"$dir/eval_figures.txt" 2>"$dir/logs/eval.txt" ||
    lan_log "fleetmap-eval failed (see $dir/logs/eval.txt)"
  "$BIN/fleetmap-lan-tool" status --until-utime "$stop" "$dir/logs/uplink.lcmlog" "$dir/logs/downlink.lcmlog" \
    >"$dir/status.txt" 2>>"$dir/logs/eval.txt"
  "$BIN/fleetmap-lan-tool" changes "$dir/logs/downlink.lcmlog" >"$dir/changes.txt" 2>>"$dir/logs/eval.txt"
  lan_host_rates "$dir" >"$dir/host_rates.txt"
  {
    echo "duration_s $DURATION s"
    echo "wall_s $RUN_WALL_S s"
    # 1: the simulators kept real time (times --speed); below: the machine did not hold them.
    awk -v d="$DURATION" -v s="$SPEED" -v w="$RUN_WALL_S" 'BEGIN { printf "sim_realtime_ratio %.3f ratio\n", d / s / w }'
    echo "vehicles $(wc -l <"$dir/hosts.txt") count"
    echo "tc_loss_drops ${LAN_LOSS_DROPS:-0} packets"
    echo "tc_rate_drops ${LAN_RATE_DROPS:-0} packets"
    awk '{ printf "tx_bytes_per_s.%s %s B/s\nrx_bytes_per_s.%s %s B/s\nbytes_per_s.%s %.1f B/s\n", $1, $2, $1, $3, $1, $2 + $3
           printf "tx_packets_per_s.%s %s 1/s\nrx_packets_per_s.%s %s 1/s\npackets_per_s.%s %.2f 1/s\n", $1, $4, $1, $5, $1, $4 + $5
           if ($1 != "server") { n++; b += $2 + $3; u += $2; p += $4 + $5 } }
         END { if (n) printf "bytes_per_s_per_vehicle %.1f B/s\nuplink_bytes_per_s_per_vehicle %.1f B/s\npackets_per_s_per_vehicle %.2f 1/s\n", b / n, u / n, p / n }' \
      "$dir/host_rates.txt"
    lan_figures_from_eval "$dir/eval_figures.txt" "$(awk '{ printf "%s ", $1 }' "$dir/hosts.txt")"
    lan_figures_from_status "$dir/status.txt"
    awk '{ print "changes." substr($1, 9), $2, $3 }' "$dir/changes.txt"
    awk -v d="$DURATION" '$1 == "changes.count" { c = $2 } $1 == "changes.occupancy_grid_bytes" { g = $2 }
      END { printf "occupancy_grid_bytes_per_s %.1f B/s\n", c * g / d }' "$dir/changes.txt"
  } >"$dir/figures_raw.txt"
  sed "s/^/$prefix./" "$dir/figures_raw.txt" >"$dir/figures.txt"
}

# lan_figures_from_eval EVAL_FIGURES "ID ...": the fleet.* and eval.lan.* figures of
# fleetmap-eval, renamed; per-vehicle channels also summed over the vehicles (TEMPMAP_*).
lan_figures_from_eval() {
  awk -v ids="$2" '
    BEGIN { n = split(ids, id, " ") }
    $1 ~ /^fleet\.bytes_per_s\./ { ch = substr($1, 19); print "channel_bytes_per_s." ch, $2, $3
      for (i = 1; i <= n; ++i) { s = "_" id[i]
        if (length(ch) > length(s) && substr(ch, length(ch) - length(s) + 1) == s) {
          sum[substr(ch, 1, length(ch) - length(id[i])) "*"] += $2; break } }
      next }
    $1 ~ /^fleet\.change_latency_s\./ { print substr($1, 7), $2, $3; next }
    $1 == "fleet.changes_not_everywhere" || $1 == "fleet.final_version" ||
      $1 == "fleet.vehicles_holding_final_version" || $1 == "fleet.vehicle_maps_equal" { print substr($1, 7), $2, $3; next }
    $1 == "eval.lan.changed_f1" || $1 == "eval.lan.static_erased" || $1 == "eval.lan.merges_accepted" ||
      $1 == "eval.lan.merges_rejected" { print substr($1, 10), $2, $3 }
    END { for (c in sum) printf "channel_bytes_per_s.%s %.1f B/s\n", c, sum[c] }' "$1"
  awk '$1 ~ /^fleet\.bytes_per_s\.(MAP_DELTA|MAP_KEYFRAME)$/ { s += $2 }
       END { printf "map_bytes_per_s %.1f B/s\n", s }' "$1"
}

# Temporary maps and retries from the agents' last heartbeats (status.agents.* sums).
lan_figures_from_status() {
  awk '
    $1 ~ /^status\.agents\./ { v[substr($1, 15)] = $2 }
    $1 ~ /^status\.aggregator\.(maps_merged|maps_rejected|tiles_received|tiles_repeated|duplicates)$/ {
      print "aggregator." substr($1, 19), $2, $3 }
    END {
      closed = v["tempmaps_closed"] + 0
      delivered = v["maps_merged"] + v["maps_rejected"] + v["maps_duplicate"]
      printf "tempmaps_closed %d count\ntempmaps_delivered %d count\n", closed, delivered
      printf "tempmaps_pending %d count\ntempmaps_dropped %d count\n", v["tempmaps_pending"], v["tempmaps_dropped"]
      # A share of nothing is nan (no map closed, no tile sent), never 0 or 1.
      printf "tempmaps_delivered_ratio %s ratio\n", (closed > 0 ? sprintf("%.4f", delivered / closed) : "nan")
      printf "tiles_sent %d count\ntiles_resent %d count\n", v["tiles_sent"], v["tiles_resent"]
      printf "retry_ratio %s ratio\n", (v["tiles_sent"] > 0 ? sprintf("%.4f", v["tiles_resent"] / v["tiles_sent"]) : "nan")
      printf "scans %d count\nscans_skipped %d count\n", v["scans"], v["scans_skipped"]
      printf "agents_reporting %d count\n", v["count"]
    }' "$1"
}
