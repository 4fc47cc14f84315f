#!/usr/bin/env bash
# Installs what is missing, configures, builds and runs the whole test suite with ctest.
# The exit code is the suite's.
#   ./run_tests.sh              RelWithDebInfo build in build/
#   ./run_tests.sh --sanitize   ASan + UBSan build of the tests in build-asan/
# Environment: CI=true turns warnings into errors; FLEETMAP_JOBS sets build parallelism.
set -euo pipefail
cd "$(dirname "$0")"

build_dir=build
ctest_args=()
args=()
if [[ ${1:-} == --sanitize ]]; then
  build_dir=build-asan
  # -O1 -g1: what the sanitizers' own documentation suggests; line tables are all a report
  # needs. Against -O2 -g this compiles each file in half the time (docs/experiments/).
  args+=(-DFLEETMAP_SANITIZE=ON -DFLEETMAP_BUILD_BENCH=OFF -DFLEETMAP_BUILD_JAR=OFF
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")
  # The deploy tests check scripts and packages, not our code's memory, and the lossy fleet run
  # repeats fleet_multicast_test's processes for 2 minutes under ASan: the main suite runs them.
  ctest_args=(-LE 'deploy|lossy')
elif [[ -n ${1:-} ]]; then
  sed -n '2,7p' "$0"
  [[ $1 == --help || $1 == -h ]] && exit 0
  exit 2
fi
jobs=${FLEETMAP_JOBS:-$(nproc)}

scripts/build.sh "$build_dir" "${args[@]}"
# Sanitizers: fail on the first report, and keep leak checking on.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
ctest --test-dir "$build_dir" --output-on-failure -j "$jobs" "${ctest_args[@]}"
