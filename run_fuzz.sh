#!/usr/bin/env bash
# The one way to fuzz: builds the libFuzzer targets (clang, build-fuzz/) and runs each for a
# bounded time, one at a time, niced (fuzz/run_fuzzer.sh, which ctest -L fuzz also uses).
# Prints per target
#   fuzz.<target>.execs N
#   fuzz.<target>.crashes N
# and exits non-zero if any target crashed (its inputs: build-fuzz/fuzz/work/artifacts/).
# Usage: ./run_fuzz.sh [SECONDS | --seconds N | --runs N] [--build-only] [TARGET ...]
#   SECONDS, --seconds N   run each target N seconds (default 30)
#   --runs N               run each target for N executions instead
#   --build-only           configure and build only
#   TARGET                 e.g. cola_b map_codec (default: every target in fuzz/)
# Environment: FLEETMAP_JOBS sets build parallelism (default: all cores);
# FLEETMAP_FUZZ_BUILD_DIR the build folder (default build-fuzz).
# docs/fuzzing.md describes the targets, their seeds and the long campaign.
set -euo pipefail
cd "$(dirname "$0")"

usage() { sed -n '2,15p' "$0"; }
limit=(--seconds 30)
build_only=false
targets=()
while (($#)); do
  case $1 in
    --seconds | --runs)
      [[ ${2:-} =~ ^[1-9][0-9]*$ ]] ||
        { echo "run_fuzz.sh: $1 takes a whole number > 0, not '${2:-}' (see --help)" >&2; exit 2; }
      limit=("$1" "$2"); shift 2 ;;
    [0-9]*)
      [[ $1 =~ ^[1-9][0-9]*$ ]] ||
        { echo "run_fuzz.sh: SECONDS must be a whole number > 0, not '$1' (see --help)" >&2; exit 2; }
      limit=(--seconds "$1"); shift ;;
    --build-only) build_only=true; shift ;;
    -h | --help) usage; exit 0 ;;
    -*) usage >&2; exit 2 ;;
    *) targets+=("$1"); shift ;;
  esac
done

build_dir=${FLEETMAP_FUZZ_BUILD_DIR:-build-fuzz}
# Only the fuzz targets and the libraries they link are built (no tests, benchmarks or jar).
# Warnings stay warnings: clang's set differs from the gcc build that CI holds to -Werror.
scripts/build.sh "$build_dir" -DCMAKE_CXX_COMPILER=clang++-14 -DFLEETMAP_FUZZ=ON \
  -DFLEETMAP_BUILD_TESTS=OFF -DFLEETMAP_BUILD_BENCH=OFF -DFLEETMAP_BUILD_JAR=OFF \
  -DFLEETMAP_WERROR=OFF -t fleetmap_fuzz
$build_only && exit 0

if ((${#targets[@]} == 0)); then
  for source in fuzz/*_fuzz.cc; do
    name=$(basename "$source" .cc)
    targets+=("${name%_fuzz}")
  done
fi
failed=()
for target in "${targets[@]}"; do
  binary=$build_dir/fuzz/${target}_fuzz
  if [[ ! -x $binary ]]; then
    echo "run_fuzz.sh: no target '$target' (fuzz/${target}_fuzz.cc)" >&2
    exit 2
  fi
  fuzz/run_fuzzer.sh "$binary" "${limit[@]}" --seeds "$build_dir/fuzz/seeds/$target" \
    --work "$build_dir/fuzz/work" || failed+=("$target")
done
if ((${#failed[@]} > 0)); then
  echo "run_fuzz.sh: crashes in ${failed[*]}" >&2
  exit 1
fi
