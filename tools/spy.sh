#!/usr/bin/env bash
# Starts lcm-spy with the fleetmap message types, so every channel is decoded (docs/lcm_spy.md).
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck source=tools/lcm_java_env.sh
source "${repo_dir}/tools/lcm_java_env.sh"
build_dir="${FLEETMAP_BUILD_DIR:-${repo_dir}/build}"
jar="${build_dir}/lcmtypes/fleetmap-lcmtypes.jar"
lcm_url="udpm://239.255.76.67:7667?ttl=0"

usage() {
  cat <<EOF
usage: tools/spy.sh [--lcm-url URL]

Starts lcm-spy with the fleetmap LCM types on its class path.
  --lcm-url URL   LCM URL to listen on (default: ${lcm_url})
  -h, --help      show this help

Environment:
  FLEETMAP_BUILD_DIR  build directory holding lcmtypes/fleetmap-lcmtypes.jar
                      (default: ${repo_dir}/build)
Needs an X display (or xvfb-run) and, for udpm:// URLs, a multicast route
(ip route add 224.0.0.0/4 dev lo for a single host). See docs/lcm_spy.md.
EOF
}

die() {
  echo "spy.sh: $*" >&2
  exit 1
}

while [[ $# -gt 0 ]]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --lcm-url) [[ $# -ge 2 ]] || die "--lcm-url needs a URL"; lcm_url="$2"; shift 2 ;;
    --lcm-url=*) lcm_url="${1#--lcm-url=}"; shift ;;
    *) usage >&2; die "unknown argument: $1" ;;
  esac
done

[[ -f "${jar}" ]] || die "${jar} not found; build first: ./run_tests.sh or cmake --build build
(or set FLEETMAP_BUILD_DIR to your build directory)"
command -v lcm-spy >/dev/null || die "lcm-spy not found: apt-get install liblcm-java liblcm-bin"
# Debian's lcm-spy puts /usr/share/java/jchart2d.jar on its class path itself; it must exist.
if grep -q jchart2d "$(command -v lcm-spy)" && [[ ! -f /usr/share/java/jchart2d.jar ]]; then
  die "lcm-spy needs jchart2d: apt-get install libjchart2d-java"
fi
fleetmap_java_display spy.sh
if [[ "${lcm_url}" =~ ^udpm://([0-9.]+) ]] && ! ip route get "${BASH_REMATCH[1]}" >/dev/null 2>&1; then
  echo "spy.sh: warning: no route to ${BASH_REMATCH[1]}; add one: ip route add 224.0.0.0/4 dev lo" >&2
fi

fleetmap_java_env "${jar}"
exec lcm-spy --lcm-url="${lcm_url}"
