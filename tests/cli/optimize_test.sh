#!/usr/bin/env bash
# `turbodyn optimize` as a user runs it, for CTest: optimize_test.sh TURBODYN SOURCE_DIR WORK_DIR CASE
set -u
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cli_setup "optimize_" "$@"

# The damper study edited by the sed expression EXPR (written to $out/NAME.toml) is refused: exit 2 and a message
# matching the grep pattern PATTERN.
expect_refused_edit() {  # EXPR NAME PATTERN
  # The study names its model relative to its own folder; the copy names it by its absolute path, so the test does
  # not depend on where the build directory lies.
  sed -e "$1" -e "s|^model = \"\.\./\.\./\.\./|model = \"$src/|" "$src/tests/data/optim/cli_damper_study.toml" > "$out/$2.toml"
  "$exe" optimize "$out/$2.toml" -o "$out/opt" > "$out/$2.log" 2>&1
  local rc=$?
  [ $rc -eq 2 ] || fail "$2: exit $rc, expected 2: $(cat "$out/$2.log")"
  grep -q -- "$3" "$out/$2.log" || fail "$2: message: $(cat "$out/$2.log")"
}

case $case in
  run_and_outputs)
    # A tiny run-up optimisation end to end: every output, and best.toml is a model file that loads.
    "$exe" optimize "$src/tests/data/optim/cli_damper_study.toml" -o "$out/opt" > "$out/log" 2>&1 \
      || fail "exit $?: $(cat "$out/log")"
    expect_files "$out/opt" history.csv evaluations.jsonl result.json best.toml convergence.png \
      spectrogram_bearing.compressor.fx_initial.png spectrogram_bearing.compressor.fx_best.png \
      spectrogram_bearing.compressor.fx_comparison.png
    [ "$(wc -l < "$out/opt/history.csv")" -eq 4 ] || fail "history.csv: expected 3 evaluations: $(cat "$out/opt/history.csv")"
    grep -q '"nlopt_result": "MAXEVAL_REACHED"' "$out/opt/result.json" || fail "result.json: $(head -20 "$out/opt/result.json")"
    grep -q '"turbodyn_version": "' "$out/opt/result.json" || fail "result.json without the program's version"
    grep -Eq '"model_digest": "[0-9a-f]{16}"' "$out/opt/result.json" || fail "result.json without the model's digest"
    head -1 "$out/opt/best.toml" | grep -q "^# Optimised by \`turbodyn optimize" || fail "best.toml header"
    "$exe" check "$out/opt/best.toml" > "$out/check.log" 2>&1 || fail "best.toml does not load: $(cat "$out/check.log")"
    ;;
  bad_algorithm)
    expect_refused_edit 's/name = "cobyla"/name = "cobila"/' study "study.toml:12:8: algorithm.name: unknown value 'cobila'"
    grep -q "did you mean 'cobyla'" "$out/study.log" || fail "no suggestion: $(cat "$out/study.log")"
    expect_refused_edit 's/low = "35 um"/low = "95 um"/' bounds \
      "bounds.toml:19:7: variables\[0\].low: the lower bound 95 um must be below the upper bound 90 um"
    ;;
  bad_values)
    # Issue 20: a NaN bound ran; a variable that is not a number of the model changed nothing.
    expect_refused_edit 's/^upper = "1 mm"/upper = nan/' nan "nan.toml:38:9: constraints\[0\].upper: value is not finite"
    expect_refused_edit 's/^low = "35 um"/low = nan/' nanlow "variables\[0\].low: value is not finite"
    expect_refused_edit 's/^paths = .*/paths = ["name"]/' path "variables\[0\].path: 'name' is not a number"
    ;;
  restart)
    # The same optimisation twice: the second invocation takes every evaluation from evaluations.jsonl.
    study="$src/tests/data/optim/jeffcott_study.toml"
    "$exe" optimize "$study" -o "$out/opt" --no-plots > "$out/log1" 2>&1 || fail "exit $?: $(cat "$out/log1")"
    n=$(($(wc -l < "$out/opt/evaluations.jsonl") - 1))
    [ "$n" -gt 5 ] || fail "only $n evaluations"
    cp "$out/opt/result.json" "$out/result1.json"
    "$exe" optimize "$study" -o "$out/opt" --no-plots > "$out/log2" 2>&1 || fail "exit $?: $(cat "$out/log2")"
    grep -q "(0 run, $n from the cache)" "$out/log2" || fail "not restarted from the log: $(cat "$out/log2")"
    [ "$(($(wc -l < "$out/opt/evaluations.jsonl") - 1))" -eq "$n" ] || fail "evaluations were run again"
    best() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['best']['design_values'])" "$1"; }
    [ "$(best "$out/result1.json")" = "$(best "$out/opt/result.json")" ] || fail "another best design after the restart"
    ;;
  interrupt_and_restart)
    # Ctrl-C after the first evaluation: exit 130, the finished evaluations are kept; the same command continues.
    study="$src/tests/data/optim/cli_damper_study.toml"
    "$exe" optimize "$study" -o "$out/opt" --no-plots > "$out/log1" 2>&1 &
    wait_until has_lines "$out/opt/evaluations.jsonl" 2
    stop INT $!
    [ $rc -eq 130 ] || fail "exit $rc, expected 130: $(cat "$out/log1")"
    grep -q "interrupted" "$out/log1" || fail "no reason given: $(cat "$out/log1")"
    done_before=$(($(wc -l < "$out/opt/evaluations.jsonl") - 1))
    [ "$done_before" -ge 1 ] && [ "$done_before" -lt 3 ] || fail "expected a partial optimisation, found $done_before"
    "$exe" optimize "$study" -o "$out/opt" --no-plots > "$out/log2" 2>&1 || fail "restart: exit $?: $(cat "$out/log2")"
    grep -q "after 3 evaluations ($((3 - done_before)) run, $done_before from the cache)" "$out/log2" \
      || fail "not continued from the log: $(cat "$out/log2")"
    ;;
  example)
    # The example study reads, checks against its model and runs its first design (the whole study takes minutes).
    # That first guess violates the rub limit on purpose: exit 4, and the least infeasible design is still written.
    "$exe" optimize "$src/examples/optimize_reference_damper.toml" --maxeval 1 --no-plots -o "$out/opt" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 4 ] || fail "exit $rc, expected 4 (no feasible design): $(cat "$out/log")"
    grep -q "after 1 evaluation (1 run, 0 from the cache)" "$out/log" || fail "$(cat "$out/log")"
    grep -q "no feasible design; least infeasible" "$out/log" || fail "$(cat "$out/log")"
    "$exe" check "$out/opt/best.toml" > "$out/check.log" 2>&1 || fail "best.toml does not load: $(cat "$out/check.log")"
    ;;
  *) fail "unknown case" ;;
esac
echo "PASS (optimize_$case)"
