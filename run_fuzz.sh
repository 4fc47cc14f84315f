#!/usr/bin/env bash
# ./run_fuzz.sh [SECONDS]: builds the fuzz targets (clang, build-fuzz/) and runs every one for
# SECONDS (default 30), one at a time, then reports per target
#   fuzz.<target>.execs N
#   fuzz.<target>.crashes N
# Exits non-zero if a target crashed. scripts/fuzz.sh takes more options; docs/fuzzing.md.
set -euo pipefail
cd "$(dirname "$0")"
exec scripts/fuzz.sh --seconds "${1:-30}"
