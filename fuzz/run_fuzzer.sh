#!/usr/bin/env bash
# Runs one libFuzzer target for a bounded time or number of executions, niced, and reports:
#   fuzz.<target>.execs N
#   fuzz.<target>.crashes N     inputs saved as crash-/leak-/timeout-/oom- by this run
# Exit status: 0 without a crash, 1 with one (the fuzzer's log tail goes to stderr), 2 on usage.
# libFuzzer's timeout is wall-clock time, and a niced fuzzer beside a build can wait seconds for
# the CPU: an input saved as timeout- that then runs alone within the timeout is the machine's
# load, not a finding. It is renamed slow-, said on stderr, and the run resumes for what is left
# of its executions or seconds (the corpus is kept), at most 5 times.
# Usage: fuzz/run_fuzzer.sh BINARY (--seconds N | --runs N) [--seeds DIR] [--work DIR]
#                           [-- LIBFUZZER_FLAG ...]
# BINARY is <target>_fuzz. Under --work (default ./fuzz-work): corpus/<target>/ (grows from run
# to run; libFuzzer writes new inputs to the first folder), artifacts/<target>/, logs/<target>.log.
set -uo pipefail

usage() { sed -n '2,13p' "$0" >&2; }
(($# >= 1)) || { usage; exit 2; }
binary=$1
shift
seconds="" runs="" seeds="" work=./fuzz-work
extra=()
while (($#)); do
  case $1 in
    --seconds) seconds=${2:?}; shift 2 ;;
    --runs) runs=${2:?}; shift 2 ;;
    --seeds) seeds=${2:?}; shift 2 ;;
    --work) work=${2:?}; shift 2 ;;
    --) shift; extra=("$@"); break ;;
    *) usage; exit 2 ;;
  esac
done
[[ -x $binary && ( -n $seconds || -n $runs ) ]] || { usage; exit 2; }

name=$(basename "$binary")
name=${name%_fuzz}
corpus=$work/corpus/$name
artifacts=$work/artifacts/$name
log=$work/logs/$name.log
mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"

dirs=("$corpus")
[[ -n $seeds && -d $seeds ]] && dirs+=("$seeds")

count_artifacts() {
  find "$artifacts" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o \
    -name 'timeout-*' -o -name 'oom-*' \) | wc -l
}
# A single input slower than 20 s or a process over 2.5 GB is a finding (timeout-, oom-).
timeout_s=20
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# Long runs keep no allocation stacks: ASan's stack depot keeps every distinct one for good, and
# under yaml-cpp's parser the scenario target grew 1.6 KB per execution (1.3 GB after 570 k),
# towards the 2.5 GB limit, a false out-of-memory long before 1e7. Rerun a saved input to see
# the stacks. ASAN_OPTIONS set by the caller wins.
if [[ -z ${ASAN_OPTIONS:-} ]] && [[ -n $runs || ${seconds:-0} -gt 300 ]]; then
  export ASAN_OPTIONS=malloc_context_size=0
fi

# The timeout- inputs saved since the list in $1 was taken, one per line.
new_timeouts() {
  comm -13 "$1" <(find "$artifacts" -maxdepth 1 -type f -name 'timeout-*' | sort)
}
# True when every input saved by the last segment is a timeout- that runs alone in time; those
# are renamed slow-.
only_load_timeouts() {
  local file fresh
  mapfile -t fresh < <(new_timeouts "$1")
  ((${#fresh[@]} > 0 && $(count_artifacts) - before == ${#fresh[@]})) || return 1
  for file in "${fresh[@]}"; do
    "$binary" -timeout=$timeout_s -rss_limit_mb=2560 "$file" >/dev/null 2>&1 || return 1
  done
  for file in "${fresh[@]}"; do
    mv "$file" "$artifacts/slow-${file##*/timeout-}"
    echo "run_fuzzer: $name: ${file##*/} ran alone within ${timeout_s} s: the machine's load," \
      "not a finding; kept as slow-${file##*/timeout-}; resuming" >&2
  done
}

before=$(count_artifacts)
total_execs=0
started=$SECONDS
: >"$log"
for ((segment = 0; ; ++segment)); do
  limits=()
  if [[ -n $seconds ]]; then
    left=$((seconds - (SECONDS - started)))
    ((left > 0)) || { rc=0; break; }
    limits+=("-max_total_time=$left")
  fi
  if [[ -n $runs ]]; then
    left=$((runs - total_execs))
    ((left > 0)) || { rc=0; break; }
    limits+=("-runs=$left")
  fi
  known=$(mktemp)
  find "$artifacts" -maxdepth 1 -type f -name 'timeout-*' | sort >"$known"
  offset=$(($(stat -c %s "$log") + 1))  # this segment's output starts there (tail -c +N)
  nice -n 19 "$binary" "${limits[@]}" -print_final_stats=1 -timeout=$timeout_s \
    -rss_limit_mb=2560 -artifact_prefix="$artifacts/" "${extra[@]}" "${dirs[@]}" \
    >>"$log" 2>&1
  rc=$?
  execs=$(tail -c +"$offset" "$log" | grep -o 'stat::number_of_executed_units: [0-9]*' |
    tail -n 1 | grep -o '[0-9]*$')
  if [[ -z $execs ]]; then  # no final statistics (killed): the last progress line, "#N ..."
    execs=$(tail -c +"$offset" "$log" | grep -o '^#[0-9]*' | tail -n 1 | tr -d '#')
  fi
  total_execs=$((total_execs + ${execs:-0}))
  if ((rc != 0 && segment < 5)) && only_load_timeouts "$known"; then
    rm -f "$known"
    continue
  fi
  rm -f "$known"
  break
done

crashes=$(($(count_artifacts) - before))
((rc != 0 && crashes == 0)) && crashes=1  # it failed without saving an input: still a failure
echo "fuzz.$name.execs $total_execs"
echo "fuzz.$name.crashes $crashes"
if ((crashes > 0)); then
  echo "run_fuzzer: $name failed (exit $rc); inputs in $artifacts, log $log:" >&2
  tail -n 60 "$log" >&2
  exit 1
fi
exit 0
