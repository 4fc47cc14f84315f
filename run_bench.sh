#!/usr/bin/env bash
# Builds in Release and runs every benchmark program in bench/, then prints every figure as
# `name value unit` (the lines our reports read) and writes them to out/bench.json.
#   ./run_bench.sh [--quick]   --quick: shorter runs, noisier figures, MRPT on intel only
#   ./run_bench.sh --build-only   installs and builds, runs nothing (what CI checks)
# Also installs Debian's MRPT (mrpt-apps, libmrpt-obs-dev) for the comparison with MRPT's
# icp-slam: for this benchmark only, never a dependency of fleetmap (docs/performance.md).
set -euo pipefail
cd "$(dirname "$0")"
min_time=0.5 scaling_s=60 mrpt_logs=(intel aces) build_only=0
case ${1:-} in
  "") ;;
  --quick) min_time=0.05 scaling_s=15 mrpt_logs=(intel) ;;
  --build-only) build_only=1 ;;
  -h | --help) sed -n '2,7p' "$0"; exit 0 ;;
  *) echo "run_bench.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
esac

scripts/install_deps.sh  # first: the archive's package lists, which MRPT needs too
if ! command -v icp-slam >/dev/null || [[ ! -d /usr/lib/x86_64-linux-gnu/cmake/mrpt-obs ]]; then
  echo "run_bench: installing MRPT for the comparison (mrpt-apps libmrpt-obs-dev)" >&2
  { [[ $(id -u) == 0 ]] && DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends \
      mrpt-apps libmrpt-obs-dev >/dev/null; } ||
    echo "run_bench: MRPT could not be installed (needs root and Debian's archive): the MRPT comparison will be skipped" >&2
fi
# BENCH=ON said, not assumed: the folder is shared with run_eval.sh and by hand, and a cached
# OFF would leave this with no benchmark programs to run.
scripts/build.sh build-release -DCMAKE_BUILD_TYPE=Release -DFLEETMAP_BUILD_TESTS=OFF \
  -DFLEETMAP_BUILD_BENCH=ON -DFLEETMAP_BUILD_JAR=OFF
((build_only)) && { echo "run_bench: built (build-release/bench)" >&2; exit 0; }
mkdir -p out/bench
failed=()  # a program that fails loses its figures, not the others'; the exit status says so
for program in build-release/bench/*_bench; do
  name=$(basename "$program")
  echo "== $name" >&2
  "$program" --benchmark_min_time="$min_time" --benchmark_color=false | tee "out/bench/$name.txt" >&2 ||
    failed+=("$name")
done

# A running agent process: 1 vehicle at 25 Hz in real time over multicast on loopback.
echo "== agent_process_bench" >&2
if scripts/setup_multicast.sh >/dev/null 2>&1; then
  { echo "# figures"; bench/agent_process_bench.sh build-release 30 | grep -E '^agent\.'; } \
    >out/bench/agent_process_bench.txt
else
  echo "agent_process_bench: skipped: no multicast on loopback (scripts/setup_multicast.sh needs root)" >&2
  echo "# figures" >out/bench/agent_process_bench.txt
fi

# The aggregator with 10, 50 and 100 simulated vehicles over multicast on loopback.
echo "== aggregator_scaling_bench" >&2
if scripts/setup_multicast.sh >/dev/null 2>&1; then
  { echo "# figures"; bench/aggregator_scaling_bench.sh build-release "$scaling_s" | grep -E '^aggregator\.'; } \
    >out/bench/aggregator_scaling_bench.txt || failed+=(aggregator_scaling_bench)
else
  echo "aggregator_scaling_bench: skipped: no multicast on loopback (scripts/setup_multicast.sh needs root)" >&2
  echo "# figures" >out/bench/aggregator_scaling_bench.txt
fi

# The downlink on generated halls of 14M and 44M cells: three vehicles joining without a map.
echo "== downlink_scale_bench" >&2
if scripts/setup_multicast.sh >/dev/null 2>&1; then
  { echo "# figures"; bench/downlink_scale_bench.sh build-release | grep -E '^scale\.'; } \
    >out/bench/downlink_scale_bench.txt || failed+=(downlink_scale_bench)
else
  echo "downlink_scale_bench: skipped: no multicast on loopback (scripts/setup_multicast.sh needs root)" >&2
  echo "# figures" >out/bench/downlink_scale_bench.txt
fi

# MRPT's icp-slam against our scan matcher on the intel and aces logs.
echo "== mrpt_compare" >&2
if command -v icp-slam >/dev/null && [[ -x build-release/bin/fleetmap-bench-carmen2rawlog ]]; then
  { echo "# figures"; bench/mrpt/mrpt_compare.sh build-release "${mrpt_logs[@]}" | grep -E '^compare\.'; } \
    >out/bench/mrpt_compare_bench.txt || failed+=(mrpt_compare)
else
  echo "mrpt_compare: skipped: MRPT is not installed (icp-slam, libmrpt-obs-dev)" >&2
  echo "# figures" >out/bench/mrpt_compare_bench.txt
fi

# Every program ends with "# figures" and then `name value unit` lines.
figures=$(for f in out/bench/*_bench.txt; do sed -n '/^# figures$/,$p' "$f" | sed 1d; done)
echo
echo "$figures"
scripts/figures_json.sh <<<"$figures" >out/bench.json
echo "wrote out/bench.json" >&2
if [[ ${#failed[@]} -gt 0 ]]; then echo "run_bench: FAILED: ${failed[*]} (their figures are missing)" >&2; exit 1; fi
