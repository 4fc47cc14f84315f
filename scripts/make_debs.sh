#!/usr/bin/env bash
# Runs CPack in a configured build folder whose packaged targets are built (target
# fleetmap_packaged) and leaves exactly this version's .deb files in OUT_DIR (older ones of
# these packages are removed). Used by ./run_package.sh and tests/integration/deploy/package_test.sh.
#   scripts/make_debs.sh BUILD_DIR OUT_DIR
set -euo pipefail
build_dir=$(cd "${1:?usage: make_debs.sh BUILD_DIR OUT_DIR}" && pwd)
out_dir=${2:?usage: make_debs.sh BUILD_DIR OUT_DIR}
mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/fleetmap_cpack.XXXXXX")
trap 'rm -rf "$work"' EXIT

# dpkg-shlibdeps (CPACK_DEBIAN_PACKAGE_SHLIBDEPS) and fakeroot (files owned by root).
for tool in dpkg-shlibdeps fakeroot; do
  command -v "$tool" >/dev/null || { echo "make_debs: $tool is missing (scripts/install_deps.sh)" >&2; exit 1; }
done
if ! (cd "$build_dir" && fakeroot cpack -G DEB --config CPackConfig.cmake -B "$work") >"$work.log" 2>&1; then
  cat "$work.log" >&2
  rm -f "$work.log"
  exit 1
fi
rm -f "$work.log"
rm -f "$out_dir"/fleetmap-*.deb
mv "$work"/*.deb "$out_dir"/
