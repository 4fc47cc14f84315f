#!/usr/bin/env bash
# Cross-builds fleetmap-agent and its unit tests for aarch64 with Debian's cross toolchain,
# runs the tests under qemu-user, and prints:
#   arm.tests_passed N         arm.tests_failed N
#   arm.agent_binary_bytes N   (stripped; the unstripped build is larger)
#   arm.agent_rss_mb_emulated N (an idle agent on the LivingLab map: qemu-user and the agent)
#   arm.agent_scan_us_emulated X, x86.agent_scan_us X, arm.scan_time_ratio_emulated R
#     (bench/agent_bench BM_AgentPipeline: one S300 scan through the whole on-board pipeline,
#      under qemu-user emulation on the x86 build host: a ratio, not a promise about a real
#      ARM board)
#   scripts/arm_build.sh [--agent-only]
#     --agent-only: only the cross-built fleetmap-agent, its --version and --help under
#     qemu-user, and arm.agent_binary_bytes (a few minutes: what CI runs on every change).
# Called by ./run_package.sh --arm. Needs root the first time (apt-get): installs
# crossbuild-essential-arm64 and qemu-user-static, and adds the arm64 architecture to dpkg
# so that apt-get can download arm64 packages.
#
# Why a sysroot of unpacked .debs instead of `apt-get install libfoo-dev:arm64`: Debian 12's
# liblcm-dev and libyaml-cpp-dev are not Multi-Arch co-installable; installing their arm64
# versions removes the amd64 ones (and so breaks the x86 build). The arm64 packages are
# downloaded (apt-get download) and unpacked with dpkg -x into out/arm/sysroot instead.
# OpenCV: the agent needs only core and imgproc (not imgcodecs, core/image/); Debian's
# OpenCVConfig.cmake lists every module, so a small config for the two is written here.
set -euo pipefail
cd "$(dirname "$0")/.."
agent_only=0
case ${1:-} in
  "") ;;
  --agent-only) agent_only=1 ;;
  -h | --help) sed -n '2,16p' "$0"; exit 0 ;;
  *) echo "arm_build.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
esac
root=$PWD
work=$root/out/arm
sysroot=$work/sysroot
build=$work/build
jobs=${FLEETMAP_JOBS:-$(nproc)}
triplet=aarch64-linux-gnu

# 1. Toolchain and emulator (amd64 packages).
need=()
for p in crossbuild-essential-arm64 qemu-user-static; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  dpkg --add-architecture arm64
  apt-get update -qq
fi
if ((${#need[@]})); then
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" >/dev/null
fi

# 2. The arm64 libraries the agent, its tests and the benchmark link, with what they need.
arm_packages=(
  liblcm-dev liblcm1 libglib2.0-0 libpcre2-8-0 libffi8 libmount1 libblkid1 libselinux1
  zlib1g zlib1g-dev libzstd-dev libzstd1 libyaml-cpp-dev libyaml-cpp0.7
  libgtest-dev libgmock-dev libbenchmark-dev libbenchmark1debian
  libopencv-core-dev libopencv-core406 libopencv-imgproc-dev libopencv-imgproc406
  libtbb12 liblapack3 libblas3 libgfortran5
  libglx0 libglvnd0 libx11-6 libxcb1 libxau6 libxdmcp6 libbsd0 libmd0 libxext6
  libsodium-dev libsodium23
)
mkdir -p "$work/debs"
if [[ ! -f $sysroot/.complete ]]; then
  (cd "$work/debs" && apt-get download "${arm_packages[@]/%/:arm64}" >/dev/null 2>&1) || {
    apt-get update -qq
    (cd "$work/debs" && apt-get download "${arm_packages[@]/%/:arm64}" >/dev/null)
  }
  rm -rf "$sysroot"
  mkdir -p "$sysroot"
  for deb in "$work"/debs/*.deb; do dpkg -x "$deb" "$sysroot"; done
  touch "$sysroot/.complete"
fi
libdir=$sysroot/usr/lib/$triplet

# 3. OpenCV core + imgproc as imported targets (imgcodecs is declared but never linked).
mkdir -p "$work/opencv"
cat >"$work/opencv/OpenCVConfig.cmake" <<EOF
# Written by scripts/arm_build.sh: OpenCV core and imgproc of the arm64 sysroot.
set(OpenCV_INCLUDE_DIRS "$sysroot/usr/include/opencv4")
foreach(m core imgproc imgcodecs)
  add_library(opencv_\${m} SHARED IMPORTED)
  set_target_properties(opencv_\${m} PROPERTIES IMPORTED_LOCATION "$libdir/libopencv_\${m}.so"
                        INTERFACE_INCLUDE_DIRECTORIES "$sysroot/usr/include/opencv4")
endforeach()
set(OpenCV_LIBS opencv_core opencv_imgproc)
set(OpenCV_FOUND TRUE)
EOF

# 4. qemu-user runs the tests (ctest and gtest discovery go through it).
cat >"$work/qemu-run" <<EOF
#!/bin/sh
export LD_LIBRARY_PATH="$libdir:$libdir/blas:$libdir/lapack:$sysroot/lib/$triplet"
exec qemu-aarch64-static -L /usr/$triplet "\$@"
EOF
chmod +x "$work/qemu-run"

# Warnings are errors in the x86 builds; the cross compiler's inlining differs and GCC 12
# reports a -Wuninitialized false positive in tests/lcmtypes (a gtest typed test), so here
# they stay warnings.
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_TOOLCHAIN_FILE="$root/cmake/aarch64-linux-gnu.cmake" -DFLEETMAP_ARM_SYSROOT="$sysroot" \
  -DCMAKE_CROSSCOMPILING_EMULATOR="$work/qemu-run" -DOpenCV_DIR="$work/opencv" \
  -DEigen3_DIR=/usr/share/eigen3/cmake -Dnlohmann_json_DIR=/usr/share/cmake/nlohmann_json \
  -DCLI11_DIR=/usr/share/cmake/CLI11 \
  -DFLEETMAP_BUILD_JAR=OFF -DFLEETMAP_WERROR=OFF >"$work/configure.log"
tests=(fleetmap_vehicle_agent_test fleetmap_agent_node_test fleetmap_sick_test fleetmap_can_test
       fleetmap_lcmtypes_test)
targets=(fleetmap-agent)
((agent_only)) || targets+=("${tests[@]}" agent_bench)
cmake --build "$build" -j "$jobs" --target "${targets[@]}" >"$work/build.log" 2>&1 || {
  tail -n 30 "$work/build.log" >&2
  echo "arm: the cross build failed (whole log: $work/build.log)" >&2
  exit 1
}
file "$build/bin/fleetmap-agent" | grep -q 'ARM aarch64' || { echo "arm: not an aarch64 binary" >&2; exit 1; }
${triplet}-strip -o "$work/fleetmap-agent" "$build/bin/fleetmap-agent"
if ((agent_only)); then
  "$work/qemu-run" "$build/bin/fleetmap-agent" --version | grep -q . ||
    { echo "arm: fleetmap-agent --version printed nothing under qemu" >&2; exit 1; }
  "$work/qemu-run" "$build/bin/fleetmap-agent" --help >/dev/null ||
    { echo "arm: fleetmap-agent --help failed under qemu" >&2; exit 1; }
  echo "arm.agent_binary_bytes $(stat -c %s "$work/fleetmap-agent")"
  exit 0
fi

# 5. The unit tests under qemu (gtest's discovery and ctest run them through qemu-run).
# AgentProcessTest starts the fleetmap-agent binary with exec(): an aarch64 binary runs only
# where binfmt_misc hands it to qemu, which a host without binfmt_misc mounted does not;
# those tests are left out. Not built here: NOT_BUILT placeholders, and the scripts' tests
# (vcan VMs, fleets, LAN experiments, packages), which are x86 runs.
excluded='AgentProcessTest|NOT_BUILT|vcan|fleet_|lan_|package_|operations_'
ctest --test-dir "$build" -j "$jobs" --timeout 900 -E "$excluded" >"$work/ctest.log" 2>&1 || true
passed=$(grep -cE 'Test +#[0-9]+: .* Passed' "$work/ctest.log" || true)
failed=$(grep -cE 'Test +#[0-9]+: .*(\*\*\*|Failed|Exception|Timeout)' "$work/ctest.log" || true)
echo "arm.tests_passed $passed"
echo "arm.tests_failed $failed"
((passed + failed > 0)) || { echo "arm: no test ran under qemu ($work/ctest.log)" >&2; exit 1; }
echo "arm.agent_binary_bytes $(stat -c %s "$work/fleetmap-agent")"

# 6. Resident memory of an idle agent holding the LivingLab map (peak VmHWM after 6 s). Under
# qemu-user the process is the emulator with the agent inside: an upper bound for the agent.
idle_rss_mb() {  # command...
  "$@" --vehicle-id rss --map sim/worlds/livinglab/livinglab.yaml --initial-pose 5,4,0 \
    --sensor-url 'udpm://239.255.76.69:17969?ttl=0' --uplink-url 'udpm://239.255.76.67:17967?ttl=0' \
    --downlink-url 'udpm://239.255.76.68:17968?ttl=0' --duration 8 --quiet >/dev/null 2>&1 &
  local pid=$!
  sleep 6
  awk '/^VmHWM/ { printf "%.0f\n", $2 / 1024 }' "/proc/$pid/status"
  wait "$pid"
}
if scripts/setup_multicast.sh >/dev/null 2>&1; then
  echo "arm.agent_rss_mb_emulated $(idle_rss_mb "$work/qemu-run" "$build/bin/fleetmap-agent")"
fi

# 7. Time per scan: the same benchmark on x86 (build/) and under qemu.
scan_us() {  # the benchmark's CPU time per iteration, microseconds
  "$@" --benchmark_filter='^BM_AgentPipeline$' --benchmark_min_time=1 2>/dev/null |
    sed 's/\x1b\[[0-9;]*m//g' | awk '$1 == "BM_AgentPipeline" { print $4 }'
}
x86_build=${FLEETMAP_BUILD_DIR:-build}
[[ -f $x86_build/build.ninja ]] || cmake -S . -B "$x86_build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$x86_build" -j "$jobs" --target agent_bench >/dev/null
x86=$(scan_us "$x86_build/bench/agent_bench")
arm=$(scan_us "$work/qemu-run" "$build/bench/agent_bench")
[[ -n $x86 && -n $arm ]] || { echo "arm: BM_AgentPipeline gave no time (x86 '$x86', arm '$arm')" >&2; exit 1; }
echo "x86.agent_scan_us $x86"
echo "arm.agent_scan_us_emulated $arm"
awk -v a="$arm" -v x="$x86" 'BEGIN { if (x > 0) printf "arm.scan_time_ratio_emulated %.1f\n", a / x }'
((failed == 0))
