#!/usr/bin/env bash
# The quick world suite as a user runs it (./run_eval.sh --suite --quick) on the programs of
# this build: it fails when a figure of eval/suite/quick_thresholds.txt does not hold, so that
# a change that breaks one kind of building fails the test suite. SKIP (77) without the public
# maps (FLEETMAP_DATA_DIR/worlds).
#   tests/eval/suite/quick_suite_test.sh SOURCE_DIR BIN_DIR DATA_DIR OUT_DIR
set -uo pipefail
src=${1:?usage: quick_suite_test.sh SOURCE_DIR BIN_DIR DATA_DIR OUT_DIR} bin=${2:?} out=${4:?}
data=${FLEETMAP_DATA_DIR:-${3:?}}  # set at test time, it overrides the configured folder
[[ -d $data/worlds ]] || { echo "SKIP: $data/worlds not found (set FLEETMAP_DATA_DIR)"; exit 77; }
mkdir -p "$out" && cd "$out" || exit 1
out=$(pwd)
FLEETMAP_EVAL_BIN_DIR=$bin FLEETMAP_DATA_DIR=$data FLEETMAP_SUITE_OUT=$out/suite-quick \
  "$src/run_eval.sh" --suite --quick >figures.txt
rc=$?
grep -v '^suite\.world\.' figures.txt
exit "$rc"
