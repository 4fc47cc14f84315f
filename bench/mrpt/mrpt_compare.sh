#!/usr/bin/env bash
# Side by side with MRPT: MRPT's icp-slam (Debian's mrpt-apps 2.5.8) and our temporary-map
# builder's scan matcher (fleetmap-carmen-eval) on the same CARMEN logs, on the same host, one
# run each. Both trajectories are scored with the same benchmark relations by
# fleetmap-carmen-eval. MRPT reads a rawlog written by fleetmap-bench-carmen2rawlog (the log's
# own time stamps, the same reader as ours), with bench/mrpt/icp-slam.ini. Checks that MRPT's
# run is a working one (its path is as long as the odometry's, every step has a pose) and
# prints no comparison for a log where it is not. Prints, per log L (intel, aces):
#   compare.mrpt.L.speedup X x            MRPT's time per scan over ours
#   compare.mrpt.L.trans_err_ratio X x    our mean translational relation error over MRPT's
#   compare.mrpt.L.{ours,mrpt}_ms_per_scan, .{ours,mrpt}_trans_err_m, .{ours,mrpt}_rot_err_deg
#   compare.mrpt.L.trans_err_ratio_win60 X x   the same over the relations spanning <= 60 s
# Usage: bench/mrpt/mrpt_compare.sh BUILD_DIR [--set KEY=VALUE]... [LOG_NAME...]
#   LOG_NAME: intel, aces (default: both); --set: change a key of icp-slam.ini for this run
#   (docs/performance.md lists the settings tried).
# Needs icp-slam on PATH and BUILD_DIR/bin/fleetmap-bench-carmen2rawlog (built where MRPT's
# development packages are installed). Work files: out/bench/mrpt/<log>/.
set -euo pipefail
if [[ ${1:-} == -h || ${1:-} == --help || $# -lt 1 ]]; then sed -n '2,19p' "$0"; exit 2; fi
build=$(cd "$1" && pwd)
shift
logs=() sets=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --set) sets+=("${2:?--set needs KEY=VALUE}"); shift 2 ;;
    *) logs+=("$1"); shift ;;
  esac
done
[[ ${#logs[@]} -eq 0 ]] && logs=(intel aces)
root=$(cd "$(dirname "$0")/../.." && pwd)
data=${FLEETMAP_DATA_DIR:-$root/../shared/data}/real
for p in "$build/bin/fleetmap-bench-carmen2rawlog" "$build/bin/fleetmap-carmen-eval" "$(command -v icp-slam || echo icp-slam)"; do
  [[ -x $p ]] || { echo "mrpt_compare: $p is missing" >&2; exit 1; }
done
ini=$root/out/bench/mrpt/icp-slam.ini
mkdir -p "$root/out/bench/mrpt"
cp "$root/bench/mrpt/icp-slam.ini" "$ini"
for kv in "${sets[@]}"; do
  key=${kv%%=*}
  grep -q "^$key *=" "$ini" || { echo "mrpt_compare: --set $kv: no key $key in icp-slam.ini" >&2; exit 2; }
  sed -i "s|^$key *=.*|$key = ${kv#*=}|" "$ini"
  echo "mrpt_compare: icp-slam.ini: $key = ${kv#*=}" >&2
done

value() { awk -v k="$1" '$1 == k { print $2 }' "$2"; }  # figure name, file

for l in "${logs[@]}"; do
  log=$data/$l/$l.rebuilt.clf rel=$data/$l/$l.relations
  if [[ ! -f $log || ! -f $rel ]]; then echo "mrpt_compare: $log or $rel not found: skipping $l" >&2; continue; fi
  work=$root/out/bench/mrpt/$l
  rm -rf "$work" && mkdir -p "$work"
  "$build/bin/fleetmap-bench-carmen2rawlog" "$log" "$work/$l.rawlog" "$work/stamps.txt" 2>&1 | sed 's/^/mrpt_compare: /' >&2

  # MRPT: icp-slam writes log_times.txt (ms of map building per step), log_estimated_path.txt
  # (step x y phi) and log_odometry_path.txt into icp-slam-out/ of its working folder.
  echo "mrpt_compare: $l: icp-slam $(basename "$ini") ($(wc -l <"$work/stamps.txt") steps)" >&2
  start=$(date +%s.%N)
  (cd "$work" && icp-slam "$ini" "$work/$l.rawlog" </dev/null >icp-slam.txt 2>&1) ||
    { tail -5 "$work/icp-slam.txt" >&2; echo "mrpt_compare: $l: icp-slam failed" >&2; continue; }
  end=$(date +%s.%N)
  out=$work/icp-slam-out
  paste -d' ' "$work/stamps.txt" <(cut -d' ' -f2- "$out/log_estimated_path.txt") >"$work/mrpt_trajectory.txt"
  steps=$(wc -l <"$work/stamps.txt") poses=$(wc -l <"$out/log_estimated_path.txt")
  mrpt_ms=$(awk '{ s += $1; n++ } END { if (n) printf "%.4f", s / n }' "$out/log_times.txt")
  # Path lengths, over every 10th step (less of ICP's jitter): MRPT's estimate and the
  # odometry it was given.
  length() { awk 'NR % 10 != 1 { next } NR > 1 { s += sqrt(($2 - x) ^ 2 + ($3 - y) ^ 2) } { x = $2; y = $3 } END { printf "%.1f", s }' "$1"; }
  mrpt_len=$(length "$out/log_estimated_path.txt") odo_len=$(length "$out/log_odometry_path.txt")
  echo "mrpt_compare: $l: icp-slam $(awk -v a="$start" -v b="$end" 'BEGIN { printf "%.1f", b - a }') s wall," \
    "$mrpt_ms ms per step of map building, $poses poses for $steps steps, path $mrpt_len m (odometry $odo_len m)," \
    "$(grep -c 'Ignoring ICP of low quality' "$work/icp-slam.txt" || true) low-quality ICP results ignored" >&2

  "$build/bin/fleetmap-carmen-eval" --carmen "$log" --relations "$rel" --name mrpt \
    --trajectory "$work/mrpt_trajectory.txt" >"$work/mrpt_figures.txt" 2>"$work/mrpt_eval.txt"
  sed 's/^/mrpt_compare: MRPT /' "$work/mrpt_eval.txt" >&2
  # Ours: the same program as ./run_eval.sh, its defaults.
  "$build/bin/fleetmap-carmen-eval" --carmen "$log" --relations "$rel" --name ours \
    >"$work/ours_figures.txt" 2>"$work/ours_eval.txt"
  sed 's/^/mrpt_compare: ours /' "$work/ours_eval.txt" >&2

  ours_ms=$(value real.ours.ms_per_scan "$work/ours_figures.txt")
  ours_t=$(value real.ours.all.trans_mean_m "$work/ours_figures.txt") mrpt_t=$(value real.mrpt.all.trans_mean_m "$work/mrpt_figures.txt")
  ours_r=$(value real.ours.all.rot_mean_deg "$work/ours_figures.txt") mrpt_r=$(value real.mrpt.all.rot_mean_deg "$work/mrpt_figures.txt")
  ours_tw=$(value real.ours.win60.trans_mean_m "$work/ours_figures.txt") mrpt_tw=$(value real.mrpt.win60.trans_mean_m "$work/mrpt_figures.txt")
  missing() { grep -o '([0-9]* missing)' "$1" | head -1 | tr -dc 0-9; }
  missing=$(missing "$work/mrpt_eval.txt") ours_missing=$(missing "$work/ours_eval.txt")
  # A working run: a pose for every step, the relations found as for ours (a few relations
  # name times that are not in the log), a path about as long as the odometry's (-20 % to
  # +50 %: a path that never moves has length 0, ICP's corrections add some), a finite error.
  if [[ $poses -ne $steps || ${missing:-x} != "${ours_missing:-y}" ]] ||
    ! awk -v a="$mrpt_len" -v b="$odo_len" -v e="$mrpt_t" 'BEGIN { exit !(b > 0 && a > 0.8 * b && a < 1.5 * b && e > 0 && e < 1e3) }'; then
    echo "mrpt_compare: $l: MRPT's run does not pass the checks (poses $poses/$steps, missing relations ${missing:-?}, path $mrpt_len m vs odometry $odo_len m, error $mrpt_t m): no comparison" >&2
    continue
  fi
  awk -v l="$l" -v om="$ours_ms" -v mm="$mrpt_ms" -v ot="$ours_t" -v mt="$mrpt_t" -v or="$ours_r" -v mr="$mrpt_r" \
    -v otw="$ours_tw" -v mtw="$mrpt_tw" 'BEGIN {
    printf "compare.mrpt.%s.speedup %.2f x\n", l, mm / om
    printf "compare.mrpt.%s.trans_err_ratio %.3f x\n", l, ot / mt
    printf "compare.mrpt.%s.trans_err_ratio_win60 %.3f x\n", l, otw / mtw
    printf "compare.mrpt.%s.ours_ms_per_scan %.4f ms\n", l, om
    printf "compare.mrpt.%s.mrpt_ms_per_scan %.4f ms\n", l, mm
    printf "compare.mrpt.%s.ours_trans_err_m %.4f m\n", l, ot
    printf "compare.mrpt.%s.mrpt_trans_err_m %.4f m\n", l, mt
    printf "compare.mrpt.%s.ours_rot_err_deg %.3f deg\n", l, or
    printf "compare.mrpt.%s.mrpt_rot_err_deg %.3f deg\n", l, mr
    printf "compare.mrpt.%s.ours_trans_err_win60_m %.4f m\n", l, otw
    printf "compare.mrpt.%s.mrpt_trans_err_win60_m %.4f m\n", l, mtw
  }'
done
