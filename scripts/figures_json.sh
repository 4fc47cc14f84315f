#!/usr/bin/env bash
# Reads `name value unit` figure lines on stdin and writes them as one JSON object on stdout:
#   {"eval.fleet.changed_f1": {"value": 0.98, "unit": "ratio"}, ...}
# in the order read. Other lines are ignored; a value that is not a number (nan, a figure
# computed over nothing) becomes null. jq builds the JSON, so every name is escaped.
#   ./run_bench.sh's and ./run_eval.sh's figures | scripts/figures_json.sh > out/x.json
set -euo pipefail
[[ ${1:-} == -h || ${1:-} == --help ]] && { sed -n '2,6p' "$0"; exit 0; }
exec jq -Rn '[inputs | [splits(" +")] | select(length == 3 and (.[0] | startswith("#") | not))
  | {key: .[0], value: {value: (.[1] | tonumber? // null), unit: .[2]}}] | from_entries'
