#!/usr/bin/env bash
# Builds in Release and runs every benchmark program in bench/, then prints every figure as
# `name value unit` (the lines our reports read) and writes them to out/bench.json.
#   ./run_bench.sh [--quick]   --quick: shorter runs, noisier figures
set -euo pipefail
cd "$(dirname "$0")"
if [[ ${1:-} == --help || ${1:-} == -h ]]; then sed -n '2,4p' "$0"; exit 0; fi
min_time=0.5
[[ ${1:-} == --quick ]] && min_time=0.05

scripts/install_deps.sh
cmake -S . -B build-release -G Ninja -DCMAKE_BUILD_TYPE=Release -DFLEETMAP_BUILD_TESTS=OFF \
  -DFLEETMAP_BUILD_JAR=OFF >/dev/null
cmake --build build-release -j "$(nproc)" >&2
mkdir -p out/bench
for program in build-release/bench/*_bench; do
  name=$(basename "$program")
  echo "== $name" >&2
  "$program" --benchmark_min_time="$min_time" --benchmark_color=false | tee "out/bench/$name.txt" >&2
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

# Every program ends with "# figures" and then `name value unit` lines.
figures=$(for f in out/bench/*_bench.txt; do sed -n '/^# figures$/,$p' "$f" | sed 1d; done)
echo
echo "$figures"
{
  echo "{"
  echo "$figures" | awk 'NF == 3 { printf "%s  \"%s\": {\"value\": %s, \"unit\": \"%s\"}", sep, $1, $2, $3; sep = ",\n" }'
  echo
  echo "}"
} >out/bench.json
echo "wrote out/bench.json" >&2
