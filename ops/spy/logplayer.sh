#!/usr/bin/env bash
# Starts lcm-logplayer-gui with the fleetmap message types on its class path, to replay a
# recorded log (out/logs/*.lcmlog) into a live system with a play/pause/seek window
# (docs/lcm_spy.md).
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
# shellcheck source=ops/spy/lcm_java_env.sh
source "${repo_dir}/ops/spy/lcm_java_env.sh"
build_dir="${FLEETMAP_BUILD_DIR:-${repo_dir}/build}"
jar="${build_dir}/lcmtypes/fleetmap-lcmtypes.jar"

usage() {
  cat <<EOF
usage: ops/spy/logplayer.sh [lcm-logplayer-gui options] [LOG.lcmlog]

Starts lcm-logplayer-gui with the fleetmap LCM types on its class path. Every argument goes
to lcm-logplayer-gui; its options:
  -l, --lcm-url=URL       LCM URL to replay into (default: LCM's own,
                          udpm://239.255.76.67:7667?ttl=0, which is fleetmap's uplink group)
  -p, --paused            start paused
  -f, --filter=CHAN       disable the channels matching the regular expression CHAN
  -v, --invert-filter     enable only the channels matching CHAN
  -h, --help              show this help

Example: ops/spy/logplayer.sh out/logs/uplink.lcmlog

Environment:
  FLEETMAP_BUILD_DIR  build directory holding lcmtypes/fleetmap-lcmtypes.jar
                      (default: ${repo_dir}/build)
Needs an X display (or xvfb-run) and, for udpm:// URLs, a multicast route
(ip route add 224.0.0.0/4 dev lo for a single host). Debian's lcm-logplayer-gui passes its
arguments on unquoted: a path or URL with spaces does not work. See docs/lcm_spy.md.
EOF
}

die() {
  echo "logplayer.sh: $*" >&2
  exit 1
}

for arg in "$@"; do
  case "${arg}" in
    -h | --help) usage; exit 0 ;;
  esac
done

command -v lcm-logplayer-gui >/dev/null || die "lcm-logplayer-gui not found: apt-get install liblcm-java liblcm-bin"
fleetmap_java_display logplayer.sh
if [[ ! -f "${jar}" ]]; then
  echo "logplayer.sh: warning: ${jar} not found (build first, or set FLEETMAP_BUILD_DIR);" \
    "replaying does not need it" >&2
fi

fleetmap_java_env "${jar}"
exec lcm-logplayer-gui "$@"
