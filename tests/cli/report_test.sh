#!/usr/bin/env bash
# report.html of every kind of output directory, opened in headless Chromium (check_report.py: it renders, every
# image loads, the numbers on the page are those of the result JSON), for CTest:
#   report_test.sh TURBODYN SOURCE_DIR WORK_DIR CASE
# Most cases check the directory an earlier command-line case wrote (a CTest fixture, tests/CMakeLists.txt), so no
# example runs twice; `sweep` runs the small two-parameter study of tests/data/studies with its pictures.
set -u
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cli_setup "report_" "$@"
check() { python3 "$src/tests/cli/check_report.py" "$@" || fail "report of $1"; }

case $case in
  run) check "$work/run_short" run 20 ;;
  run_incomplete)
    # A run the integrator gave up on: the page says so at the top, and still shows what was computed.
    check "$work/run_integrator_gives_up" run 20
    grep -q 'class="warn" data-alert>INCOMPLETE: the run-up' "$work/run_integrator_gives_up/report.html" \
      || fail "no incomplete marker on the page"
    ;;
  plot)
    # turbodyn plot rewrites the page: it names the redrawing command and shows the redrawn pictures.
    check "$work/plot_redraws/run" run 20
    grep -q "Pictures redrawn by" "$work/plot_redraws/run/report.html" || fail "report.html not rewritten by plot"
    ;;
  modal) check "$work/modal_friswell" modal 10 ;;
  response) check "$work/response_reference" response 4 ;;
  bearing) check "$work/bearing_reference_ball" bearing 20 ;;
  bearing_floating_ring) check "$work/bearing_floating_ring" bearing 20 ;;
  modal_floating_ring) check "$work/modal_floating_ring" modal 10 ;;
  stability) check "$work/stability_reference_ball" stability 10 ;;
  sweep)
    "$exe" sweep "$src/tests/data/studies/two_parameter_study.toml" -o "$out/study" -j 2 > "$out/log" 2>&1 \
      || fail "sweep: exit $?: $(cat "$out/log")"
    expect_files "$out/study" sensitivity_compressor_max.png map_compressor_max.png \
      metric_compressor_max_vs_bearings.compressor.k.png
    check "$out/study" sweep 40
    ;;
  merge) check "$work/sweep_shards_merge/merged" merge 40 ;;
  optimize) check "$work/optimize_run_and_outputs/opt" optimize 8 ;;
  identify) check "$work/identify_example" identify 10 ;;
  *) fail "unknown case" ;;
esac
