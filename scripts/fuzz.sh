#!/usr/bin/env bash
# Fuzzes the case loader (YAML text), the ScenarioSpec checks (protobuf bytes) and the server's
# request checks with libFuzzer: builds the `fuzz` preset (clang, AddressSanitizer and
# UndefinedBehaviorSanitizer) into build/fuzz/, then runs each target for SECONDS (default 60).
# Seeds: the case files, the bad-case catalogues (tests/cli/bad_cases, tests/unit/bad_cases), the
# case files as binary specs (fuzz_seed_specs) and fuzz/regressions/TARGET/, where every input that
# once failed is kept, so each run replays them first. Prints each target's executions; exits 1
# on a finding (crash, sanitizer report, uncaught exception, leak, timeout), whose input is left in
# build/fuzz/run/findings/ (add it to fuzz/regressions/TARGET/ with the fix).
#
# usage: bash scripts/fuzz.sh [SECONDS]   (.ci/run: 30; by hand, e.g. 3600)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
seconds="${1:-60}"
targets=(fuzz_case_text fuzz_scenario_spec fuzz_requests)

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$(nproc)" --target "${targets[@]}" fuzz_seed_specs >/dev/null

bin=build/fuzz/bin
work=build/fuzz/run
rm -rf "$work"
mkdir -p "$work/findings" "$work/specs"
"$bin/fuzz_seed_specs" "$work/specs" cases/*.yaml

status=0
for target in "${targets[@]}"; do
  case "$target" in
    fuzz_case_text) seeds=(cases tests/cli/bad_cases tests/unit/bad_cases) ;;
    fuzz_scenario_spec) seeds=("$work/specs") ;;
    fuzz_requests) seeds=() ;;
  esac
  [ -d "fuzz/regressions/$target" ] && seeds+=("fuzz/regressions/$target")
  mkdir -p "$work/corpus/$target"
  log="$work/$target.log"
  # The first folder receives the new inputs; the seed folders are only read.
  if "$bin/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$work/findings/$target-" "$work/corpus/$target" "${seeds[@]}" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    echo "fuzz: $target: $runs executions in ${seconds} s, no finding"
  else
    echo "fuzz: $target: FINDING (log $log, input in $work/findings/):"
    tail -n 40 "$log"
    status=1
  fi
done
exit "$status"
