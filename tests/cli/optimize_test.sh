#!/usr/bin/env bash
# `turbodyn optimize` as a user runs it, for CTest: optimize_test.sh TURBODYN SOURCE_DIR WORK_DIR CASE
set -u
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cli_setup "optimize_" "$@"

case $case in
  run_and_outputs)
    # A tiny run-up optimisation end to end: every output, and best.toml is a model file that loads.
    "$exe" optimize "$src/tests/data/optim/cli_damper_study.toml" -o "$out/opt" > "$out/log" 2>&1 \
      || fail "exit $?: $(cat "$out/log")"
    for f in history.csv evaluations.jsonl result.json best.toml convergence.png \
             spectrogram_bearing.compressor.fx_initial.png spectrogram_bearing.compressor.fx_best.png \
             spectrogram_bearing.compressor.fx_comparison.png; do
      [ -s "$out/opt/$f" ] || fail "missing $f: $(cat "$out/log")"
    done
    [ "$(wc -l < "$out/opt/history.csv")" -eq 4 ] || fail "history.csv: expected 3 evaluations: $(cat "$out/opt/history.csv")"
    grep -q '"nlopt_result": "MAXEVAL_REACHED"' "$out/opt/result.json" || fail "result.json: $(head -20 "$out/opt/result.json")"
    head -1 "$out/opt/best.toml" | grep -q "^# Optimised by \`turbodyn optimize" || fail "best.toml header"
    "$exe" check "$out/opt/best.toml" > "$out/check.log" 2>&1 || fail "best.toml does not load: $(cat "$out/check.log")"
    ;;
  bad_algorithm)
    sed 's/name = "cobyla"/name = "cobila"/' "$src/tests/data/optim/cli_damper_study.toml" > "$out/study.toml"
    "$exe" optimize "$out/study.toml" -o "$out/opt" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "exit $rc, expected 2: $(cat "$out/log")"
    grep -q "study.toml:12:8: algorithm.name: unknown value 'cobila'" "$out/log" || fail "message: $(cat "$out/log")"
    grep -q "did you mean 'cobyla'" "$out/log" || fail "no suggestion: $(cat "$out/log")"
    sed 's/low = "35 um"/low = "95 um"/' "$src/tests/data/optim/cli_damper_study.toml" > "$out/bounds.toml"
    "$exe" optimize "$out/bounds.toml" -o "$out/opt" > "$out/log2" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "bad bounds: exit $rc, expected 2"
    grep -q "bounds.toml:19:7: variables\[0\].low: the lower bound 95 um must be below the upper bound 90 um" "$out/log2" \
      || fail "message: $(cat "$out/log2")"
    ;;
  bad_values)
    # Issue 20: a NaN bound ran; a variable that is not a number of the model changed nothing.
    sed 's/^upper = "1 mm"/upper = nan/' "$src/tests/data/optim/cli_damper_study.toml" > "$out/nan.toml"
    "$exe" optimize "$out/nan.toml" -o "$out/opt" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "upper = nan: exit $rc, expected 2: $(cat "$out/log")"
    grep -q "nan.toml:38:9: constraints\[0\].upper: value is not finite" "$out/log" || fail "message: $(cat "$out/log")"
    sed 's/^low = "35 um"/low = nan/' "$src/tests/data/optim/cli_damper_study.toml" > "$out/nanlow.toml"
    "$exe" optimize "$out/nanlow.toml" -o "$out/opt" > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q "variables\[0\].low: value is not finite" "$out/log" || fail "low = nan: $(cat "$out/log")"
    sed 's/^paths = .*/paths = ["name"]/' "$src/tests/data/optim/cli_damper_study.toml" > "$out/path.toml"
    "$exe" optimize "$out/path.toml" -o "$out/opt" > "$out/log" 2>&1
    [ $? -eq 2 ] && grep -q "variables\[0\].path: 'name' is not a number" "$out/log" \
      || fail "path: $(cat "$out/log")"
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
    pid=$!
    for _ in $(seq 1 1200); do
      [ -f "$out/opt/evaluations.jsonl" ] && [ "$(wc -l < "$out/opt/evaluations.jsonl")" -ge 2 ] && break
      sleep 0.1
    done
    kill -INT $pid
    wait $pid
    rc=$?
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
