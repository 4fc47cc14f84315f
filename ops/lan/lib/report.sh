# shellcheck shell=bash
# CSV rows, the offline codec sweep and the PNG plots of the LAN experiments (sourced by
# fleetmap-lan-experiment; needs BIN, DURATION).

LAN_CSV_HEADER="vehicles,link,resolution_m,codec,duration_s,wall_s,bytes_per_s_per_vehicle,\
uplink_bytes_per_s_per_vehicle,server_tx_bytes_per_s,server_rx_bytes_per_s,\
packets_per_s_per_vehicle,map_bytes_per_s,occupancy_grid_bytes_per_s,tempmaps_closed,\
tempmaps_delivered,tempmaps_delivered_ratio,tiles_sent,tiles_resent,retry_ratio,changes,\
change_latency_s_median,change_latency_s_p95,changes_not_everywhere,vehicle_maps_equal,\
changed_f1,tc_loss_drops,scans_skipped,sim_realtime_ratio,tempmap_bytes_per_s,sweep"

# A figure of a run (figures_raw.txt), or NaN.
lan_fig() { awk -v k="$2" '$1 == k { v = $2 } END { print (v == "" ? "nan" : v) }' "$1/figures_raw.txt"; }

# lan_csv_row DIR N PROFILE RESOLUTION CODEC: the run's row of summary.csv (the sweep that
# made it last).
lan_csv_row() {
  local dir=$1 f out="$2,$3,$4,$5"
  for f in duration_s wall_s bytes_per_s_per_vehicle uplink_bytes_per_s_per_vehicle \
    tx_bytes_per_s.server rx_bytes_per_s.server packets_per_s_per_vehicle map_bytes_per_s \
    occupancy_grid_bytes_per_s tempmaps_closed tempmaps_delivered tempmaps_delivered_ratio \
    tiles_sent tiles_resent retry_ratio changes.count change_latency_s.median \
    change_latency_s.p95 changes_not_everywhere vehicle_maps_equal changed_f1 tc_loss_drops \
    scans_skipped sim_realtime_ratio channel_bytes_per_s.TEMPMAP_*; do
    out+=",$(lan_fig "$dir" "$f")"
  done
  echo "$out,${SWEEP:-single}"
}

# lan_codec_sweep DIR PREFIX N PROFILE RESOLUTION: the run's map tiles re-encoded with every
# codec variant (fleetmap-lan-tool codec); a summary row per variant whose byte columns are
# the run's, moved by what the variant would have saved or cost (every tile reaches every
# vehicle link: the bridge floods multicast, as a Wi-Fi access point does), and
# `PREFIX.codec.<group>.<variant>.bytes_per_s` lines.
lan_codec_sweep() {
  local dir=$1 prefix=$2 n=$3 profile=$4 res=$5 variant row
  "$BIN/fleetmap-lan-tool" codec "$dir/logs/uplink.lcmlog" "$dir/logs/downlink.lcmlog" >"$dir/codec.txt" || return 1
  awk -v d="$DURATION" -v p="$prefix" '$1 ~ /\.bytes$/ { k = $1; sub(/\.bytes$/, ".bytes_per_s", k)
    printf "%s.%s %.1f B/s\n", p, k, $2 / d }' "$dir/codec.txt" | tee -a "$dir/figures.txt"
  for variant in raw8 none zlib1 zlib6 zlib9 zstd1 zstd3 zstd9 zstd19; do
    row=$(lan_csv_row "$dir" "$n" "$profile" "$res" "$variant")
    awk -v v="$variant" -v d="$DURATION" -v n="$n" -v row="$row" '
      { split($1, k, ".") }
      k[4] == "bytes" && k[3] == "sent" { sent[k[2]] = $2 }
      k[4] == "bytes" && k[3] == v { var[k[2]] = $2 }
      END {
        dt = (var["TEMPMAP"] - sent["TEMPMAP"]) / d
        dm = (var["MAP_DELTA"] + var["MAP_KEYFRAME"] - sent["MAP_DELTA"] - sent["MAP_KEYFRAME"]) / d
        m = split(row, c, ",")
        c[7] += dt + dm; c[8] += dt / n; c[9] += dm; c[10] += dt; c[12] += dm; c[29] += dt
        out = c[1]; for (i = 2; i <= m; ++i) out = out "," c[i]; print out
      }' "$dir/codec.txt"
  done >>"$OUT/summary.rows"
}

# lan_summary OUT KIND: this invocation's rows into OUT/summary.csv (a row of the same
# vehicles, link, resolution, codec and sweep is replaced), OUT/sweep_KIND.csv, and its plots.
lan_summary() {
  local out=$1 kind=$2
  [ -s "$out/summary.rows" ] || return 0
  { echo "$LAN_CSV_HEADER"; cat "$out/summary.rows"; } >"$out/sweep_$kind.csv"
  local old=""
  [ -f "$out/summary.csv" ] && old=$(tail -n +2 "$out/summary.csv")
  {
    echo "$LAN_CSV_HEADER"
    awk -F, 'NR == FNR { new[$1 FS $2 FS $3 FS $4 FS $NF] = 1; next } !(($1 FS $2 FS $3 FS $4 FS $NF) in new)' \
      "$out/summary.rows" <(printf '%s\n' "$old" | sed '/^$/d')
    cat "$out/summary.rows"
  } >"$out/summary.csv.new" && mv "$out/summary.csv.new" "$out/summary.csv"
  rm -f "$out/summary.rows"
  lan_log "wrote $out/summary.csv and $out/sweep_$kind.csv"
  if command -v gnuplot >/dev/null; then
    lan_plot "$out" "$kind" && lan_log "wrote $out/sweep_$kind.png"
  else
    lan_log "gnuplot is missing (scripts/install_deps.sh installs gnuplot-nox): no plots"
  fi
}

# lan_plot OUT KIND: OUT/sweep_KIND.png from OUT/sweep_KIND.csv.
lan_plot() {
  local out=$1 kind=$2 csv=$1/sweep_$2.csv
  local common="set datafile separator ','; set key top left; set grid;
    set terminal pngcairo size 1000,420 font ',10'; set output '$out/sweep_$kind.png'"
  case $kind in
    vehicles)
      gnuplot -e "$common; set multiplot layout 1,2;
        set xlabel 'vehicles'; set ylabel 'bytes/s'; set logscale y;
        set title 'Traffic per host (interface counters) vs a ROS OccupancyGrid per change';
        plot '$csv' skip 1 using 1:7 with linespoints title 'per vehicle link (tx+rx)',
             '' skip 1 using 1:8 with linespoints title 'per vehicle uplink (tx)',
             '' skip 1 using 1:9 with linespoints title 'server tx (downlink)',
             '' skip 1 using 1:(\$12 + \$29) with linespoints lc rgb 'black' title 'our maps (TEMPMAP + MAP_*)',
             '' skip 1 using 1:13 with linespoints lc rgb 'red' title 'OccupancyGrid on every change';
        unset logscale y; set ylabel 'seconds / ratio';
        set title 'Change latency (temporary map closed -> every vehicle holds it), F1';
        plot '' skip 1 using 1:21 with linespoints title 'latency median [s]',
             '' skip 1 using 1:22 with linespoints title 'latency p95 [s]',
             '' skip 1 using 1:25 with linespoints title 'changed-cell F1';
        unset multiplot" ;;
    links | resolution | single)
      local x=2
      [ "$kind" = resolution ] && x=3
      gnuplot -e "$common; set multiplot layout 1,2; set style data histograms;
        set style fill solid 0.8 border -1; set boxwidth 0.8; set key below horizontal;
        set title 'Traffic (bytes/s)'; set logscale y;
        plot '$csv' skip 1 using 7:xtic($x) title 'per vehicle link',
             '' skip 1 using 9 title 'server tx', '' skip 1 using (\$12 + \$29) title 'our maps',
             '' skip 1 using 13 title 'OccupancyGrid per change';
        unset logscale y; set title 'Delivery and latency'; set yrange [0:*];
        plot '' skip 1 using 16:xtic($x) title 'tempmaps delivered ratio',
             '' skip 1 using 19 title 'resends per tile',
             '' skip 1 using 21 title 'latency median [s]', '' skip 1 using 25 title 'changed F1';
        unset multiplot" ;;
    codec)
      gnuplot -e "$common; set style data histograms; set style fill solid 0.8 border -1;
        set key below horizontal; set logscale y; set ylabel 'bytes/s'; set title 'The run re-encoded with each codec';
        plot '$csv' skip 1 using 8:xtic(4) title 'per vehicle uplink',
             '' skip 1 using 9 title 'server tx (map changes + keyframes)',
             '' skip 1 using (\$12 + \$29) title 'our maps (TEMPMAP + MAP_*)',
             '' skip 1 using 13 title 'OccupancyGrid on every change'" ;;
  esac
}
