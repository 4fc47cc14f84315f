#!/usr/bin/env bash
# fuzz/run_fuzzer.sh against a stand-in for a libFuzzer binary whose segments follow a plan:
# a timeout that runs alone in time (the machine's load) is set aside and the run resumes to its
# full count; a timeout that is slow alone, and a crash, stay findings.
# Usage: tests/integration/deploy/run_fuzzer_test.sh SOURCE_DIR
set -uo pipefail
source_dir=${1:?usage: run_fuzzer_test.sh SOURCE_DIR}
runner=$source_dir/fuzz/run_fuzzer.sh
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# The stand-in: with one file argument it reruns that input (slow if the input says "hang");
# otherwise it runs the next segment of $FAKE_PLAN (ok | load | hang | crash, comma separated):
# ok runs every execution asked for; the others run 300, save an input and exit 70 as libFuzzer.
cat >"$tmp/fake_fuzz" <<'EOF'
#!/usr/bin/env bash
runs=0 prefix=""
for arg; do
  case $arg in
    -runs=*) runs=${arg#-runs=} ;;
    -artifact_prefix=*) prefix=${arg#-artifact_prefix=} ;;
  esac
done
if (($# == 3)) && [[ -f ${!#} ]]; then
  grep -q hang "${!#}" && exit 70
  echo "Executed ${!#} in 1 ms"
  exit 0
fi
segment=$(cat "$FAKE_STATE" 2>/dev/null || echo 0)
echo $((segment + 1)) >"$FAKE_STATE"
IFS=, read -ra plan <<<"$FAKE_PLAN"
step=${plan[segment]:-ok}
if [[ $step == ok ]]; then
  echo "stat::number_of_executed_units: $runs"
  exit 0
fi
echo "#300 NEW cov: 1"
kind=timeout
[[ $step == crash ]] && kind=crash
echo "$step" >"${prefix}${kind}-$segment$RANDOM"
exit 70
EOF
chmod +x "$tmp/fake_fuzz"

# Runs the plan with --runs 10000 in a fresh work folder; prints the runner's stdout.
run_plan() {
  rm -rf "$tmp/work" "$tmp/state"
  FAKE_PLAN=$1 FAKE_STATE=$tmp/state "$runner" "$tmp/fake_fuzz" --runs 10000 --work "$tmp/work" \
    2>"$tmp/stderr"
}
artifacts() { find "$tmp/work/artifacts/fake" -name "$1" | wc -l; }

out=$(run_plan load,ok) || fail "a load timeout failed the run: $(cat "$tmp/stderr")"
[[ $out == *"fuzz.fake.execs 10000"* ]] || fail "load then ok: execs not 10000: $out"
[[ $out == *"fuzz.fake.crashes 0"* ]] || fail "load then ok: a crash counted: $out"
(($(artifacts 'slow-*') == 1 && $(artifacts 'timeout-*') == 0)) ||
  fail "the load timeout was not kept as slow-"
grep -q "the machine's load" "$tmp/stderr" || fail "the resume was not said"

out=$(run_plan hang) && fail "a timeout slow alone passed: $out"
[[ $out == *"fuzz.fake.crashes 1"* ]] || fail "hang: not one crash: $out"
(($(artifacts 'timeout-*') == 1)) || fail "hang: the timeout input was not kept"

out=$(run_plan crash) && fail "a crash passed: $out"
[[ $out == *"fuzz.fake.execs 300"* ]] || fail "crash: resumed after a crash: $out"

out=$(run_plan load,load,load,load,load,load,ok) && fail "six load timeouts in a row passed"
(($(artifacts 'slow-*') == 5)) || fail "not five resumes before giving up"

((failures == 0)) && echo "run_fuzzer_test: 4 plans as expected"
exit $((failures > 0))
