#!/usr/bin/env bash
# Builds fleetmap's Debian packages into out/deb/ and prints one line per package:
#   deb.NAME.bytes N
#   ./run_package.sh          RelWithDebInfo build in build/ (stripped in the packages), CPack
#   ./run_package.sh --arm    cross-builds the agent and its unit tests for aarch64, runs the
#                             tests under qemu-user (scripts/arm_build.sh; prints arm.* lines)
#   ./run_package.sh --arm --agent-only   only the cross-built agent, checked under qemu-user
# Environment: FLEETMAP_BUILD_DIR (default build), FLEETMAP_JOBS (build parallelism).
# Needs no network once scripts/install_deps.sh has run. What is in each package, the
# systemd units and how to install them: docs/deployment.md.
set -euo pipefail
cd "$(dirname "$0")"

case ${1:-} in
  "") ;;
  --arm) shift; exec scripts/arm_build.sh "$@" ;;
  -h | --help) sed -n '2,10p' "$0"; exit 0 ;;
  *) sed -n '2,10p' "$0" >&2; exit 2 ;;
esac

build_dir=${FLEETMAP_BUILD_DIR:-build}
jobs=${FLEETMAP_JOBS:-$(nproc)}
# Only what the packages hold (CMAKE_SKIP_INSTALL_ALL_DEPENDENCY: CPack builds nothing else).
FLEETMAP_JOBS=$jobs scripts/build.sh "$build_dir" -t fleetmap_packaged
scripts/make_debs.sh "$build_dir" out/deb
for deb in out/deb/*.deb; do
  name=$(dpkg-deb -f "$deb" Package)
  echo "deb.${name}.bytes $(stat -c %s "$deb")"
done
