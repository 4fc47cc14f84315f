#!/usr/bin/env bash
# ./run_fuzz.sh [SECONDS]: builds the fuzz targets (clang, build-fuzz/) and runs every one for
# SECONDS (default 30), one at a time, then reports per target
#   fuzz.<target>.execs N
#   fuzz.<target>.crashes N
# Exits non-zero if a target crashed. scripts/fuzz.sh takes more options; docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")"
case ${1:-30} in
  -h | --help) sed -n '2,6p' "$0"; exit 0 ;;
  *[!0-9]* | 0) echo "run_fuzz.sh: SECONDS must be a whole number > 0, not '$1' (see --help)" >&2; exit 2 ;;
esac
exec scripts/fuzz.sh --seconds "${1:-30}"
