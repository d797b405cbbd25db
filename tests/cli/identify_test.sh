#!/usr/bin/env bash
# `turbodyn identify` as a user runs it, run by CTest: identify_test.sh TURBODYN SOURCE_DIR WORK_DIR CASE
set -u
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cli_setup "identify_" "$@"

case $case in
  example)
    # The example study recovers the true values of its synthetic measurement within 3 standard deviations, and
    # the fitted model file runs.
    "$exe" identify "$src/examples/identify_bench_rotor.toml" -o "$out" -j 2 > "$out/log" 2>&1 || fail "exit $?: $(cat "$out/log")"
    expect_files "$out" estimates.json ceres_summary.txt fitted.toml features.csv \
      feature_order1x_x_mid_amplitude.png spectrogram_measured_x_mid.png spectrogram_fitted_x_mid.png
    grep -Eq "Termination: +CONVERGENCE" "$out/ceres_summary.txt" || fail "not converged: $(head -40 "$out/ceres_summary.txt")"
    # |error_in_std_devs| < 3 for every parameter (the JSON is indented two spaces per level).
    n=$(grep -c '"error_in_std_devs"' "$out/estimates.json")
    [ "$n" -eq 3 ] || fail "expected 3 parameters with true values, found $n"
    bad=$(grep '"error_in_std_devs"' "$out/estimates.json" | awk -F: '{ v = $2 + 0; if (v < -3 || v > 3) print }')
    [ -z "$bad" ] || fail "estimates off by more than 3 sigma: $bad"
    "$exe" run "$out/fitted.toml" --no-plots -o "$out/fitted_run" > "$out/run.log" 2>&1 || fail "fitted.toml does not run: $(cat "$out/run.log")"
    grep -q '"complete": true' "$out/fitted_run/summary.json" || fail "fitted run incomplete"
    ;;
  interrupted_keeps_the_last_iteration)
    # Issue 20: after Ctrl-C, estimates.json held the start values although the message promised the last finished
    # iteration (and the log showed iteration 2 elsewhere), and the run count included the cancelled runs.
    "$exe" identify "$src/examples/identify_bench_rotor.toml" -o "$out" -j 2 --no-plots > "$out/log" 2>&1 &
    wait_until grep -q "^iteration   2 " "$out/log"
    stop INT $!
    [ $rc -eq 130 ] || fail "exit $rc, expected 130: $(cat "$out/log")"
    grep -q "interrupted: the results are those of the last finished iteration" "$out/log" || fail "$(cat "$out/log")"
    python3 - "$out/log" "$out/estimates.json" <<'PY' || fail "estimates are not those of the last iteration: $(cat "$out/log")"
import json, re, sys
last = [l for l in open(sys.argv[1]) if l.startswith("iteration ")][-1]
logged = {m.group(1): float(m.group(2)) for m in re.finditer(r"(\w+) = ([-+0-9.eE]+)", last)}
est = {p["name"]: p["estimate"] for p in json.load(open(sys.argv[2]))["parameters"]}
starts = {p["name"]: p["start"] for p in json.load(open(sys.argv[2]))["parameters"]}
assert est != starts, "the start values"
for name, v in est.items():
    assert abs(v - logged[name]) <= 1e-5 * abs(v), (name, v, logged[name])
PY
    ;;
  bad_measured_file)
    # A NaN in the measured file: exit code 2 and a message naming file, line, field and column.
    sed 's/^0.010000,\([^,]*\),\([^,]*\),\([^,]*\),.*$/0.010000,\1,\2,\3,nan/' "$src/examples/data/bench_rotor_runup.csv" \
      > "$out/bench_rotor_runup.csv"
    sed "s|^model = \"bench_rotor_journal.toml\"|model = \"$src/examples/bench_rotor_journal.toml\"|; s|^file = \"data/bench_rotor_runup.csv\"|file = \"bench_rotor_runup.csv\"|" \
      "$src/examples/identify_bench_rotor.toml" > "$out/study.toml"
    "$exe" identify "$out/study.toml" -o "$out/res" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "exit $rc, expected 2: $(cat "$out/log")"
    grep -q "bench_rotor_runup.csv:53:[0-9]*: column 'y_mid': 'nan' is not a finite number" "$out/log" \
      || fail "message: $(cat "$out/log")"
    ;;
  bad_study)
    # A misspelt key in the study file: exit code 2, file:line:column and a suggestion.
    sed 's/^n_speeds = 18$/n_speed = 18/' "$src/examples/identify_bench_rotor.toml" > "$out/study.toml"
    sed -i "s|^model = \"bench_rotor_journal.toml\"|model = \"$src/examples/bench_rotor_journal.toml\"|" "$out/study.toml"
    "$exe" identify "$out/study.toml" -o "$out/res" > "$out/log" 2>&1
    rc=$?
    [ $rc -eq 2 ] || fail "exit $rc, expected 2: $(cat "$out/log")"
    grep -q "study.toml:[0-9]*:[0-9]*: features\[0\].n_speed: unknown key; did you mean 'n_speeds'?" "$out/log" \
      || fail "message: $(cat "$out/log")"
    ;;
  *)
    fail "unknown case"
    ;;
esac
echo "ok ($case)"
