#!/usr/bin/env bash
# Runs every shipped scenario end to end, in-process, scores each against the simulator's
# ground truth, prints the figures as `name value unit` lines and writes out/eval.json.
#   ./run_eval.sh                                        every shipped LivingLab scenario
#   ./run_eval.sh --scenario SCENARIO.yaml [--map MAP.yaml]   your own world
# Pictures and report.json per scenario: out/eval/<scenario>/.
set -euo pipefail
cd "$(dirname "$0")"

scenario="" map=""
while (($#)); do
  case $1 in
    --scenario) scenario=${2:?--scenario needs a file}; shift 2 ;;
    --map) map=${2:?--map needs a file}; shift 2 ;;
    -h | --help) sed -n '2,7p' "$0"; exit 0 ;;
    *) echo "run_eval.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ -n $map && -z $scenario ]] && { echo "run_eval.sh: --map goes with --scenario" >&2; exit 2; }

scripts/install_deps.sh
cmake -S . -B build-release -G Ninja -DCMAKE_BUILD_TYPE=Release -DFLEETMAP_BUILD_TESTS=OFF \
  -DFLEETMAP_BUILD_JAR=OFF >/dev/null
cmake --build build-release -j "$(nproc)" --target fleetmap-eval >&2

# The pipeline that exists today. The oracle merges exactly what the scanners saw; once the
# vehicle agent and aggregator libraries land, they replace it here.
pipeline=oracle
echo "run_eval: pipeline '$pipeline' (merges the true observed change: a reference, not the system)" >&2

worlds=tools/sim/worlds/livinglab
if [[ -n $scenario ]]; then
  scenarios=("$scenario")
else
  scenarios=("$worlds/addition.yaml" "$worlds/removal.yaml" "$worlds/fleet.yaml")
fi

mkdir -p out
figures=""
for s in "${scenarios[@]}"; do
  args=(--scenario "$s" --pipeline "$pipeline")
  [[ -n $map ]] && args+=(--map "$map")
  figures+=$(build-release/bin/fleetmap-eval "${args[@]}")$'\n'
done
printf '%s' "$figures"
{
  echo "{"
  printf '%s' "$figures" | awk 'NF == 3 { printf "%s  \"%s\": {\"value\": %s, \"unit\": \"%s\"}", sep, $1, ($2 == "nan" ? "null" : $2), $3; sep = ",\n" }'
  echo
  echo "}"
} >out/eval.json
echo "run_eval: wrote out/eval.json; reports and pictures in out/eval/" >&2
