#!/usr/bin/env bash
# The demo builds what the fleet script runs: every "$bin/fleetmap-NAME" that
# scripts/fleet_run.sh starts (itself or through scripts/lib/fleet_launch.sh, where the program
# folder is "$1") is in its --programs list, and run_demo.sh builds that list (a
# program started but not built fails the demo on a fresh clone only, where nothing else built it).
#   tests/integration/deploy/demo_programs_test.sh SOURCE_DIR
set -uo pipefail
src=${1:?usage: demo_programs_test.sh SOURCE_DIR}
fleet=$src/scripts/fleet_run.sh
launch=$src/scripts/lib/fleet_launch.sh
fail=0
listed=$("$fleet" --programs) || { echo "FAIL: fleet_run.sh --programs exits $?"; exit 1; }
[[ -n $listed ]] || { echo "FAIL: fleet_run.sh --programs lists nothing"; exit 1; }
started=$(grep -ohE '"\$(bin|1)/fleetmap-[a-z0-9-]+' "$fleet" "$launch" | sed 's|.*/||' | sort -u)
[[ -n $started ]] || { echo "FAIL: found no \"\$bin/fleetmap-...\" command in $fleet"; exit 1; }
for p in $started; do
  grep -qx "$p" <<<"$listed" || { echo "FAIL: fleet_run.sh starts $p, which --programs does not list"; fail=1; }
done
grep -q 'fleet_run.sh --programs' "$src/run_demo.sh" ||
  { echo "FAIL: run_demo.sh does not build the list of fleet_run.sh --programs"; fail=1; }
((fail == 0)) && echo "ok: run_demo.sh builds the $(wc -l <<<"$listed") programs fleet_run.sh runs: $(echo $listed)"
exit "$fail"
