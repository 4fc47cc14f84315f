#!/usr/bin/env bash
# Screenshots of lcm-spy watching the live fleet (docs/lcm_spy.md): the simulator, three
# fleetmap-agent processes and fleetmap-aggregator run in real time over multicast on
# loopback (scripts/fleet_run.sh), one lcm-spy listens to the uplink group and one to the
# downlink group, each under its own Xvfb display, with the viewer of one channel open.
#   scripts/lcm_spy_screenshots.sh [--bin DIR] [--build DIR] [--port P] [--wait S] [--out DIR]
#     --bin DIR    the fleetmap programs                                    [build/bin]
#     --build DIR  the build folder holding lcmtypes/fleetmap-lcmtypes.jar      [build]
#     --port P     uplink port of the run (downlink P+1, sensor P+2)              [7751]
#     --wait S     seconds of the run before the screenshots (merges by then)      [45]
#     --out DIR    where lcm_spy_uplink.png and lcm_spy_downlink.png go          [docs]
# Needs root once for the multicast route (scripts/setup_multicast.sh), Xvfb, ImageMagick's
# import and xdotool (apt-get install xvfb imagemagick xdotool).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$root/build/bin build=$root/build port=7751 wait_s=45 out=$root/docs
while [ $# -gt 0 ]; do
  case $1 in
    --bin) bin=${2:?}; shift 2 ;;
    --build) build=${2:?}; shift 2 ;;
    --port) port=${2:?}; shift 2 ;;
    --wait) wait_s=${2:?}; shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    -h | --help) sed -n '2,13p' "$0"; exit 0 ;;
    *) echo "lcm_spy_screenshots.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
for tool in Xvfb import xdotool lcm-spy; do
  command -v "$tool" >/dev/null ||
    { echo "lcm_spy_screenshots.sh: $tool is missing (apt-get install xvfb imagemagick xdotool liblcm-java)" >&2; exit 1; }
done
"$root/scripts/setup_multicast.sh"
work=$(mktemp -d /tmp/fleetmap-spy.XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT

# shellcheck source=lib/fleet_launch.sh
source "$root/scripts/lib/fleet_launch.sh"
fleet_links "$port"  # the groups fleet_run.sh --port opens
# The run: real time, long enough that the spies see every channel.
"$root/scripts/fleet_run.sh" --scenario "$root/sim/worlds/livinglab/fleet_short.yaml" \
  --speed 1 --duration $((wait_s + 15)) --port "$port" --bin "$bin" --out "$work/run" \
  --name spy >"$work/run.log" 2>&1 &
pids+=($!)
# One display and one spy per group. Rows of the channel table are 16 px apart from y = 27;
# the channels sort by name, so row 0 of the uplink is DIVERGENCE_cts1 (d(t) and the
# likelihoods, plotted live) and row 2 of the downlink is MERGE_REPORT (the line matches).
spy() {  # DISPLAY_NUMBER URL ROW PNG
  Xvfb ":$1" -screen 0 1460x605x24 >"$work/xvfb$1.log" 2>&1 &
  pids+=($!)
  sleep 2
  DISPLAY=":$1" FLEETMAP_BUILD_DIR=$build "$root/ops/spy/fleetmap-spy" --lcm-url "$2" >"$work/spy$1.log" 2>&1 &
  pids+=($!)
}
spy 57 "$uplink"
spy 58 "$downlink"
echo "lcm_spy_screenshots: fleet and spies running; screenshots in $wait_s s"
sleep "$wait_s"
shot() {  # DISPLAY_NUMBER ROW CHANNEL PNG
  DISPLAY=":$1" xdotool mousemove 80 $((27 + 16 * $2)) click --repeat 2 --delay 100 1
  sleep 4
  # Without a window manager the viewer opens over the table: move it to the right half
  # (its title is the channel's name).
  local w
  for w in $(DISPLAY=":$1" xdotool search --onlyvisible --name "$3" 2>/dev/null); do
    DISPLAY=":$1" xdotool windowmove "$w" 805 0 windowsize "$w" 655 605
  done
  sleep 3
  DISPLAY=":$1" import -window root "$4"
  echo "lcm_spy_screenshots: $4"
}
mkdir -p "$out"
shot 57 0 DIVERGENCE_cts1 "$out/lcm_spy_uplink.png"
shot 58 2 MERGE_REPORT "$out/lcm_spy_downlink.png"
