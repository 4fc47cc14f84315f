#!/usr/bin/env bash
# Installs the Debian 12 packages fleetmap needs, and only those that are missing, so that
# ./run_tests.sh, ./run_demo.sh and ./run_bench.sh work on a fresh machine. Idempotent.
# Usage: scripts/install_deps.sh [extra-package ...]
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  liblcm-dev liblcm-bin liblcm-java default-jdk-headless libjchart2d-java  # LCM, lcm-spy
  libeigen3-dev libopencv-dev libyaml-cpp-dev libzstd-dev zlib1g-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  iproute2  # ip route for LCM multicast on loopback
  nlohmann-json3-dev  # SICK recordings (.pcapng.json), the world suite's reports
  libcli11-dev  # every program's command line (core/command_line.h)
  qemu-system-x86 linux-image-amd64 busybox-static can-utils cpio  # SocketCAN tests in a VM
  clang-format  # scripts/check_format.sh (ctest format_test)
  clang-14 libclang-rt-14-dev  # libFuzzer targets (scripts/fuzz.sh, docs/fuzzing.md)
  libsodium-dev  # message authentication: HMAC-SHA-256, key derivation (docs/security.md)
  gnuplot-nox  # the LAN experiments' plots (ops/lan, docs/lan_experiments.md)
  dpkg-dev fakeroot file systemd  # Debian packages: dpkg-shlibdeps, systemd-analyze (docs/deployment.md)
  help2man lintian  # the packages' manual pages and their check (tests/integration/deploy/package_test.sh)
  jq  # the figures as JSON (scripts/figures_json.sh: out/bench.json, out/eval.json)
  "$@"
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
((${#missing[@]} == 0)) && exit 0

echo "install_deps: installing ${missing[*]}" >&2
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null; then
    sudo=(sudo)
  else
    echo "install_deps: these packages are missing and we are not root: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
