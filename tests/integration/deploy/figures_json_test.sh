#!/usr/bin/env bash
# scripts/figures_json.sh, which writes out/bench.json and out/eval.json: every figure line in
# order, nan as null, names with quotes escaped, other lines left out.
#   tests/integration/deploy/figures_json_test.sh SOURCE_DIR
set -uo pipefail
src=${1:?usage: figures_json_test.sh SOURCE_DIR}
json=$(printf '%s\n' '# figures' 'eval.fleet.changed_f1 0.981 ratio' 'not a figure line at all' \
  'eval.a"b.static_erased 0 cells' 'suite.changed_f1.min nan ratio' 'bench.x 2.5e-3 s' |
  "$src/scripts/figures_json.sh") || { echo "FAIL: figures_json.sh exited with $?"; exit 1; }
expected='["eval.fleet.changed_f1",0.981,"ratio","eval.a\"b.static_erased",0,"cells","suite.changed_f1.min",null,"ratio","bench.x",0.0025,"s"]'
got=$(jq -c '[to_entries[] | .key, .value.value, .value.unit]' <<<"$json")
[[ $got == "$expected" ]] || { echo "FAIL: got $got, expected $expected"; exit 1; }
echo PASS
