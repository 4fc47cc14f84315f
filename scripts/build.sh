#!/usr/bin/env bash
# The one install-and-build step of every run_*.sh: installs what is missing
# (scripts/install_deps.sh), configures BUILD_DIR with Ninja and builds it, or only the TARGETs
# named after -t (as cmake --build -t takes them).
#   scripts/build.sh BUILD_DIR [-DNAME=VALUE ...] [-t TARGET ...]
# The build type is RelWithDebInfo unless a -DCMAKE_BUILD_TYPE says otherwise, with line tables
# only (-g1: what a backtrace or a sanitizer report needs; full -g costs a third more compile
# time, docs/experiments/2026-12-03-ci-time.md); with CI=true warnings are errors
# (FLEETMAP_WERROR, unless a -DFLEETMAP_WERROR says otherwise).
# FLEETMAP_JOBS sets the build's parallelism (default: every core). The build's progress goes
# to stderr, so that a caller's stdout holds only its figures.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:?usage: scripts/build.sh BUILD_DIR [-DNAME=VALUE ...] [-t TARGET ...]}
shift
# Defaults first: cmake keeps the last of two -D of one name, so the caller's win.
cmake_args=(-G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG")
[[ ${CI:-} == true ]] && cmake_args+=(-DFLEETMAP_WERROR=ON)
targets=()
while (($#)); do
  case $1 in
    -D*) cmake_args+=("$1"); shift ;;
    -t | --target)
      shift
      while (($#)) && [[ $1 != -* ]]; do targets+=("$1"); shift; done
      ((${#targets[@]})) || { echo "build.sh: -t needs at least one target" >&2; exit 2; }
      ;;
    *) echo "build.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
scripts/install_deps.sh
cmake -S . -B "$build_dir" "${cmake_args[@]}" >/dev/null
if ((${#targets[@]})); then
  cmake --build "$build_dir" -j "${FLEETMAP_JOBS:-$(nproc)}" -t "${targets[@]}" >&2
else
  cmake --build "$build_dir" -j "${FLEETMAP_JOBS:-$(nproc)}" >&2
fi
