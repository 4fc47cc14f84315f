#!/usr/bin/env bash
# Runs every shipped scenario end to end, in-process, scores each against the simulator's
# ground truth, runs the scan matcher over the SLAM benchmark logs, prints every figure as a
# `name value unit` line and writes out/eval.json.
#   ./run_eval.sh                                            everything shipped
#   ./run_eval.sh --scenario SCENARIO.yaml [--map MAP.yaml]   your own world
#   ./run_eval.sh --carmen LOG --relations REL                your own CARMEN log
#   ./run_eval.sh --build-only                 installs and builds, runs nothing (CI checks it)
#   ./run_eval.sh --suite [--quick]            the world suite (docs/world_suite.md): 40
#                  generated buildings and every public map of FLEETMAP_DATA_DIR/worlds, each
#                  with the pipelines agents and truthmaps, suite.* figures, out/suite/suite.md
#                  and suite.png; --quick: 8 small worlds, checked against the thresholds of
#                  eval/suite/quick_thresholds.txt (the test suite runs it)
# Per scenario: eval.S.* is the real system (vehicle pipelines + aggregator, pipeline
# "agents"), eval.S.paper_mode.* the same with the paper's alignment, eval.S.truthmaps.* the
# aggregator alone fed perfect temporary maps with anchor errors up to 0.3 m / 3 deg, and
# eval.S.truthmaps.paper_mode.* the same with the paper's alignment (docs/aggregator.md).
# loc.global.*, loc.kidnapped.*: global localization and kidnapped vehicles on the fleet scenario
# (fleetmap-locate-eval).
# Per CARMEN log, real.L.*: the scan matcher and the log's odometry scored by the benchmark's
# relations, and checks of the relations themselves (real.L.win60.ref_*, .scan_fit_*:
# fleetmap-carmen-eval --audit, docs/localization.md).
# FLEETMAP_EVAL_BUILD_DIR (default build-release) picks the Release build folder;
# FLEETMAP_EVAL_BIN_DIR: use the programs already built there (no install, no build);
# FLEETMAP_SUITE_OUT: the suite's output folder (default out/suite, out/suite-quick);
# FLEETMAP_DATA_DIR (default ../shared/data) holds the real logs, as real/L/L.rebuilt.clf.
# Pictures and report.json per scenario and pipeline: out/eval/.
set -euo pipefail
cd "$(dirname "$0")"

scenario="" map="" carmen="" relations="" build_only=0 suite=0 quick=0
while (($#)); do
  case $1 in
    --scenario) scenario=${2:?--scenario needs a file}; shift 2 ;;
    --map) map=${2:?--map needs a file}; shift 2 ;;
    --carmen) carmen=${2:?--carmen needs a log}; shift 2 ;;
    --relations) relations=${2:?--relations needs a file}; shift 2 ;;
    --build-only) build_only=1; shift ;;
    --suite) suite=1; shift ;;
    --quick) quick=1; shift ;;
    -h | --help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "run_eval.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
[[ -n $map && -z $scenario ]] && { echo "run_eval.sh: --map goes with --scenario" >&2; exit 2; }
[[ -n $carmen && -z $relations ]] && { echo "run_eval.sh: --carmen needs --relations" >&2; exit 2; }
((quick && !suite)) && { echo "run_eval.sh: --quick goes with --suite" >&2; exit 2; }

if [[ -n ${FLEETMAP_EVAL_BIN_DIR:-} ]]; then
  bin=$FLEETMAP_EVAL_BIN_DIR
else
  build=${FLEETMAP_EVAL_BUILD_DIR:-build-release}
  scripts/build.sh "$build" -DCMAKE_BUILD_TYPE=Release -DFLEETMAP_BUILD_TESTS=OFF \
    -DFLEETMAP_BUILD_JAR=OFF -t fleetmap-eval fleetmap-carmen-eval fleetmap-suite \
    fleetmap-locate-eval
  bin=$build/bin
fi
((build_only)) && { echo "run_eval: built ($bin)" >&2; exit 0; }

if ((suite)); then
  args=(--out "${FLEETMAP_SUITE_OUT:-out/suite}" --livinglab sim/worlds/livinglab/fleet.yaml)
  if ((quick)); then
    args=(--out "${FLEETMAP_SUITE_OUT:-out/suite-quick}" --quick
      --livinglab sim/worlds/livinglab/fleet_short.yaml)
    while read -r requirement _; do
      [[ -n $requirement && $requirement != \#* ]] && args+=(--require "$requirement")
    done <eval/suite/quick_thresholds.txt
  fi
  exec "$bin"/fleetmap-suite "${args[@]}" --data-dir "${FLEETMAP_DATA_DIR:-../shared/data}"
fi

worlds=sim/worlds/livinglab
data=${FLEETMAP_DATA_DIR:-../shared/data}/real  # the real logs (FLEETMAP_DATA_DIR)
scenarios=() logs=()
if [[ -n $scenario ]]; then
  scenarios=("$scenario")
elif [[ -z $carmen ]]; then
  scenarios=("$worlds/addition.yaml" "$worlds/removal.yaml" "$worlds/fleet.yaml")
  for l in intel aces fr079; do
    if [[ -f $data/$l/$l.rebuilt.clf ]]; then logs+=("$data/$l/$l.rebuilt.clf:$data/$l/$l.relations")
    else echo "run_eval: $data/$l not found: skipping the real log $l" >&2; fi
  done
fi
[[ -n $carmen ]] && logs=("$carmen:$relations")

mkdir -p out
figures=""
evaluate() {  # scenario, figure-name suffix, fleetmap-eval arguments...
  local s=$1 suffix=$2; shift 2
  local name; name=$(sed -n 's/^name: *//p' "$s"); name=${name:-$(basename "$s" .yaml)}
  local args=(--scenario "$s" --quiet --name "$name$suffix" --out "out/eval/$name$suffix" "$@")
  [[ -n $map ]] && args+=(--map "$map")
  echo "run_eval: $s ($*)" >&2
  figures+=$("$bin"/fleetmap-eval "${args[@]}")$'\n'
}
for s in "${scenarios[@]}"; do
  evaluate "$s" "" --pipeline agents
  evaluate "$s" ".paper_mode" --pipeline agents --align-mode paper
  evaluate "$s" ".truthmaps" --pipeline truthmaps
  evaluate "$s" ".truthmaps.paper_mode" --pipeline truthmaps --align-mode paper
done
# Global localization (vehicles switched on without a pose, 20 starts along the routes):
# loc.global.* and loc.kidnapped.* on the fleet scenario, or on your own.
locate=""
if [[ -n $scenario ]]; then locate=$scenario
elif [[ -z $carmen ]]; then locate=$worlds/fleet.yaml; fi
if [[ -n $locate ]]; then
  echo "run_eval: global localization on $locate" >&2
  locate_args=(--scenario "$locate")
  [[ -n $map ]] && locate_args+=(--map "$map")
  figures+=$("$bin"/fleetmap-locate-eval "${locate_args[@]}")$'\n'
fi
for pair in "${logs[@]}"; do
  log=${pair%%:*} rel=${pair#*:}
  echo "run_eval: $log" >&2
  figures+=$("$bin"/fleetmap-carmen-eval --carmen "$log" --relations "$rel" --audit 1 --png "out/eval/$(basename "$log" .rebuilt.clf).png" 2>/dev/null)$'\n'
done
printf '%s' "$figures"
scripts/figures_json.sh <<<"$figures" >out/eval.json
echo "run_eval: wrote out/eval.json; reports and pictures in out/eval/" >&2
