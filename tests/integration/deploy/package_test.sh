#!/usr/bin/env bash
# Builds the Debian packages from a built tree (scripts/make_debs.sh), checks their control
# data (Depends from dpkg-shlibdeps, conffiles, maintainer scripts), unpacks them into a
# scratch root with dpkg -x (nothing is installed on the host), checks every file is
# where docs/deployment.md says, runs every installed program's --version and --help, checks
# the systemd units with systemd-analyze verify, and starts the installed agent and
# aggregator with the installed configuration files for a moment (when multicast works).
#   tests/integration/deploy/package_test.sh SOURCE_DIR BUILD_DIR
# Exit status: 0 passed, 1 failed, 77 skipped (dpkg-deb or fakeroot missing).
set -uo pipefail
src=$(cd "${1:?usage: package_test.sh SOURCE_DIR BUILD_DIR}" && pwd)
build=$(cd "${2:?usage: package_test.sh SOURCE_DIR BUILD_DIR}" && pwd)
for tool in dpkg-deb dpkg-shlibdeps fakeroot; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool missing (scripts/install_deps.sh)"; exit 77; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/fleetmap_pkg.XXXXXX")
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
pass() { echo "ok: $*"; }

version=$(sed -n 's/^project(fleetmap VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
"$src/scripts/make_debs.sh" "$build" "$work/deb" || { echo "FAIL: CPack"; exit 1; }
packages=(fleetmap-common fleetmap-agent fleetmap-aggregator fleetmap-tools fleetmap-lcmtypes-java)
root=$work/root
for p in "${packages[@]}"; do
  deb=$(ls "$work/deb/${p}_${version}_"*.deb 2>/dev/null | head -1)
  [[ -n $deb ]] || { fail "no package $p $version"; continue; }
  dpkg-deb -x "$deb" "$root"
  mkdir -p "$work/control"
  dpkg-deb -e "$deb" "$work/control/$p"
  pass "$p $(stat -c %s "$deb") bytes"
done

# Control data: the runtime libraries from dpkg-shlibdeps, conffiles, maintainer scripts.
depends() { dpkg-deb -f "$work/deb/${1}_${version}_"*.deb Depends; }
expect_depends() {  # package, then package names its Depends must name
  local p=$1 d names
  d=$(depends "$p")
  names=$(tr ',|' '\n\n' <<<"$d" | awk '{ print $1 }')
  shift
  for lib in "$@"; do
    grep -qxF "$lib" <<<"$names" || fail "$p Depends lacks $lib: $d"
  done
}
expect_depends fleetmap-agent liblcm1 libyaml-cpp0.7 libzstd1 libstdc++6 libc6 fleetmap-common
expect_depends fleetmap-aggregator liblcm1 libopencv-imgcodecs406 libyaml-cpp0.7 fleetmap-common
expect_depends fleetmap-tools liblcm1 libopencv-core406
expect_depends fleetmap-common adduser iproute2
expect_depends fleetmap-lcmtypes-java liblcm-java
depends fleetmap-agent | grep -q opencv-imgcodecs && fail "the agent depends on OpenCV's image codecs"
[[ $(dpkg-deb -f "$work/deb/fleetmap-common_${version}_all.deb" Architecture) == all ]] ||
  fail "fleetmap-common is not Architecture: all"
for c in "fleetmap-agent /etc/fleetmap/agent-example.yaml" \
  "fleetmap-aggregator /etc/fleetmap/aggregator.yaml" "fleetmap-aggregator /etc/fleetmap/aggregator.env" \
  "fleetmap-common /etc/fleetmap/multicast.env"; do
  set -- $c
  grep -qx "$2" "$work/control/$1/conffiles" 2>/dev/null || fail "$2 is not a conffile of $1"
done
grep -q "adduser --quiet --system" "$work/control/fleetmap-common/postinst" || fail "postinst creates no system user"
for s in "$work"/control/*/{postinst,postrm,prerm}; do
  [[ -f $s ]] && { sh -n "$s" || fail "$s: syntax"; }
done
pass "control data"

# Files where docs/deployment.md says.
files=(
  usr/bin/fleetmap-agent usr/bin/fleetmap-aggregator usr/bin/fleetmap-mapctl usr/bin/fleetmap-keygen
  usr/bin/fleetmap-record
  usr/bin/fleetmap-sim usr/bin/fleetmap-eval usr/bin/fleetmap-maptool usr/bin/fleetmap-sick-emulator
  usr/bin/fleetmap-sim-candump usr/bin/fleetmap-carmen-eval usr/bin/fleetmap-publish-samples
  usr/bin/fleetmap-lan-tool usr/bin/fleetmap-lan-experiment usr/bin/fleetmap-spy
  usr/share/java/fleetmap-lcmtypes.jar
  lib/systemd/system/fleetmap-agent@.service lib/systemd/system/fleetmap-aggregator.service
  lib/systemd/system/fleetmap-multicast.service usr/lib/fleetmap/fleetmap-multicast-setup
  usr/lib/sysctl.d/60-fleetmap.conf
  etc/fleetmap/agent-example.yaml etc/fleetmap/aggregator.yaml etc/fleetmap/aggregator.env
  etc/fleetmap/multicast.env
  usr/share/fleetmap/sim/worlds/livinglab/livinglab.yaml
  usr/share/fleetmap/ops/lan/fleetmap-lan-experiment usr/share/fleetmap/ops/lan/lib/net.sh
  usr/share/doc/fleetmap-common/operations.md
)
for f in "${files[@]}"; do [[ -e $root/$f ]] || fail "missing /$f"; done
for f in "$root"/usr/bin/*; do [[ -x $f ]] || fail "$f is not executable"; done
file "$root/usr/bin/fleetmap-agent" | grep -q "stripped" && ! file "$root/usr/bin/fleetmap-agent" | grep -q "not stripped" ||
  fail "fleetmap-agent is not stripped"
pass "${#files[@]} files in place"

# Every program answers --version (the project's version) and --help (exit 0, some text).
for f in "$root"/usr/bin/*; do
  name=$(basename "$f")
  out=$(cd "$work" && "$f" --version 2>&1) || fail "$name --version exits $?"
  [[ $out == *"$version"* ]] || fail "$name --version prints '$out'"
  [[ ! -e $work/--version ]] || fail "$name --version wrote a file named --version"
  out=$(cd "$work" && "$f" --help 2>&1) || fail "$name --help exits $?"
  [[ ${#out} -gt 40 ]] || fail "$name --help prints too little: '$out'"
done
pass "--version and --help of $(ls "$root/usr/bin" | wc -l) programs"

# Every program has a manual page and every package its copyright and changelog.
for f in "$root"/usr/bin/*; do
  name=$(basename "$f")
  page=$root/usr/share/man/man1/$name.1.gz
  [[ -s $page ]] || { fail "no manual page for $name"; continue; }
  zcat "$page" | grep -q "^\.SH DESCRIPTION\|^\.SH SYNOPSIS\|^\.SH NAME" || fail "$name.1 has no sections"
done
for p in "${packages[@]}"; do
  [[ -s $root/usr/share/doc/$p/copyright && -s $root/usr/share/doc/$p/changelog.gz ]] ||
    fail "$p lacks /usr/share/doc/$p/copyright or changelog.gz"
done
pass "manual pages, copyright and changelog"

# lintian (Debian's package checker): no error and no warning.
if command -v lintian >/dev/null; then
  out=$(lintian "$work"/deb/*.deb 2>&1 | grep -E '^[EW]: ')
  if [[ -z $out ]]; then
    pass "lintian: 0 errors, 0 warnings"
  else
    fail "lintian: $(grep -c '^E: ' <<<"$out") errors, $(grep -c '^W: ' <<<"$out") warnings:
$out"
  fi
else
  fail "lintian missing (scripts/install_deps.sh installs it)"
fi

# The units: systemd-analyze verify resolves ExecStart= against the scratch root.
if command -v systemd-analyze >/dev/null; then
  units=$work/units
  mkdir -p "$units"
  cp "$root"/lib/systemd/system/*.service "$units/"
  # Instances of the template, and the programs at their installed paths inside the root.
  cp "$units/fleetmap-agent@.service" "$units/fleetmap-agent@cts1.service"
  sed -i "s|/usr/bin/|$root/usr/bin/|g; s|/usr/lib/fleetmap/|$root/usr/lib/fleetmap/|g" "$units"/*.service
  # verify exits 0 on a value it ignores ("Failed to parse ..., ignoring"): any line it
  # prints is a failure.
  out=$(systemd-analyze verify --man=no "$units/fleetmap-agent@cts1.service" \
    "$units/fleetmap-aggregator.service" "$units/fleetmap-multicast.service" 2>&1)
  rc=$?
  [[ $rc == 0 && -z $out ]] && pass "systemd-analyze verify" || fail "systemd-analyze verify ($rc): $out"
  for u in "$root"/lib/systemd/system/fleetmap-{agent@,aggregator}.service; do
    for key in Restart=on-failure After=network-online.target Wants=network-online.target \
      NoNewPrivileges=yes ProtectSystem=strict StateDirectory=fleetmap ReadWritePaths=/var/lib/fleetmap; do
      grep -q "^${key}" "$u" || fail "$(basename "$u") lacks $key"
    done
  done
else
  fail "systemd-analyze missing (scripts/install_deps.sh installs systemd)"
fi

# The installed configuration files load: the installed agent and aggregator, started with
# them on private ports for a moment (multicast on loopback needed; skipped without it).
if "$src/scripts/setup_multicast.sh" >/dev/null 2>&1; then
  map=$root/usr/share/fleetmap/sim/worlds/livinglab/livinglab.yaml
  port=$((17000 + RANDOM % 2000))
  urls=(--uplink-url "udpm://239.255.76.67:$port?ttl=0" --downlink-url "udpm://239.255.76.68:$((port + 1))?ttl=0")
  out=$("$root/usr/bin/fleetmap-aggregator" --config "$root/etc/fleetmap/aggregator.yaml" --map "$map" \
    --state-dir "$work/state" "${urls[@]}" --duration 1 --quiet 2>&1)
  [[ $out == *"aggregator: version 0 "* ]] || fail "installed aggregator with aggregator.yaml: $out"
  out=$("$root/usr/bin/fleetmap-agent" --config "$root/etc/fleetmap/agent-example.yaml" --vehicle-id cts1 \
    --map "$map" --state-dir "$work/agent" --sensor-url "udpm://239.255.76.69:$((port + 2))?ttl=0" \
    "${urls[@]}" --duration 1 --quiet 2>&1)
  [[ $out == *"agent cts1: scans 0"* ]] || fail "installed agent with agent-example.yaml: $out"
  pass "installed agent and aggregator start with the installed configuration"
else
  echo "note: no multicast on loopback (scripts/setup_multicast.sh needs root): configs not started"
fi

if ((failures)); then
  echo "package test: $failures failures"
  exit 1
fi
echo "package test: passed"
