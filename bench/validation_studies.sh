#!/usr/bin/env bash
# The long validation studies on the paper's variants, with the pictures their documents show:
#   identification of the ball-bearing preload and turbine unbalance (docs/identification.md, ~2 min on 2 cores),
#   damper optimisation of variant III to convergence (docs/optimization.md, ~4-6 min on 2 cores; after a change of
#   its model file remove out/validation_studies/optimize_ball_sfd first, or the cache is refused),
#   the same over clearance, centring spring and end seals from rest to 45,000 rpm (optimize_seals, afresh each
#   time; docs/optimization.md, ~7 min on 2 cores), and with the dampers fed through a central groove
#   (optimize_seals_groove, ~27 min),
#   the 32-run design of experiments on variant I's clearances, unbalance and oil temperature, with the onset of
#   the outer-film whirl and the films' thinnest points (docs/studies.md, ~8-13 min on 2 cores, 2026-12-07),
#   the 16-run design on variant II's preload, contact angle and unbalance, full run-ups (docs/studies.md, 20 min on
#   2 cores since a run-up takes 1.7-2.9 min; 34 min on 2026-12-04, 2 h before),
#   the 20-design map of where variant II's ball-set whirl starts over preload and contact angle, 48 designs of
#   eight bearing parameters and 30 outer-ring mounts, stability analyses without run-ups (docs/studies.md, ~32 s,
#   ~75 s and ~41 s on 2 cores),
#   the 16-run sweep of variant III's damper clearance, centring spring and end seals (docs/studies.md, ~1.5 min).
#   identification of variant I's clearances and oil temperature with model error, and its held-out check
#   (docs/identification.md, ~12 min on 2 cores).
# Usage: bench/validation_studies.sh [identify] [identify_floating_ring] [optimize] [optimize_seals]
#   [optimize_seals_groove] [floating_ring] [ball] [ball_stability] [ball_sfd]
#   (default: all).
# Build first (scripts/build.sh).
# Results in out/validation_studies/; an interrupted optimisation resumes from its cache when run again.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=build/app/turbodyn
[[ -x $exe ]] || { echo "validation_studies: build first (scripts/build.sh)" >&2; exit 1; }
which=("$@")
((${#which[@]})) ||
  which=(identify identify_floating_ring optimize optimize_seals optimize_seals_groove floating_ring ball ball_stability
         ball_sfd)
out=out/validation_studies
mkdir -p "$out" docs/images
# Runs COMMAND..., its output also into $out/LOG, and appends its wall time under LABEL: run_timed LABEL LOG COMMAND...
run_timed() {
  local label=$1 log=$2 start
  shift 2
  start=$(date +%s)
  "$@" | tee "$out/$log"
  echo "$label: $(($(date +%s) - start)) s of wall time on $(nproc) cores" | tee -a "$out/$log"
}
# Runs examples/study_reference_NAME.toml afresh into $out/study_NAME and logs its wall time to $out/NAME.log.
run_study() {
  rm -rf "$out/study_$1"
  run_timed "study_$1" "$1.log" "$exe" sweep "examples/study_reference_$1.toml" -o "$out/study_$1"
}
for w in "${which[@]}"; do
  case $w in
    identify)
      rm -rf "$out/identify_reference_ball"
      "$exe" identify examples/identify_reference_ball.toml -o "$out/identify_reference_ball" | tee "$out/identify.log"
      cp "$out/identify_reference_ball/feature_order1x_x_turb_amplitude.png" \
        docs/images/identify_ball_feature_order1x_x_turb_amplitude.png
      ;;
    identify_floating_ring)
      rm -rf "$out/identify_floating_ring" "$out/identify_floating_ring_heldout"
      "$exe" identify examples/identify_reference_floating_ring.toml -o "$out/identify_floating_ring" \
        | tee "$out/identify_floating_ring.log"
      cp "$out/identify_floating_ring/feature_subsync_x_comp_frequency.png" \
        docs/images/identify_floating_ring_subsync_x_comp_frequency.png
      # The held-out file's start values are the fitted values documented in docs/identification.md.
      "$exe" identify examples/identify_reference_floating_ring_heldout.toml -o "$out/identify_floating_ring_heldout" \
        | tee "$out/identify_floating_ring_heldout.log"
      cp "$out/identify_floating_ring_heldout/feature_order1x_x_turb_amplitude.png" \
        docs/images/identify_floating_ring_heldout_order1x_x_turb_amplitude.png
      ;;
    optimize)
      "$exe" optimize examples/optimize_reference_ball_sfd.toml -o "$out/optimize_ball_sfd" | tee "$out/optimize.log"
      cp "$out/optimize_ball_sfd/convergence.png" docs/images/optimize_ball_sfd_convergence.png
      cp "$out/optimize_ball_sfd/spectrogram_bearing.compressor.fx_comparison.png" \
        docs/images/optimize_ball_sfd_spectrogram_compressor_force.png
      cp "$out/optimize_ball_sfd/spectrogram_disk.compressor.x_comparison.png" \
        docs/images/optimize_ball_sfd_spectrogram_compressor_x.png
      ;;
    optimize_seals)
      rm -rf "$out/optimize_ball_sfd_seals"
      run_timed optimize_ball_sfd_seals optimize_seals.log \
        "$exe" optimize examples/optimize_reference_ball_sfd_seals.toml -o "$out/optimize_ball_sfd_seals"
      cp "$out/optimize_ball_sfd_seals/convergence.png" docs/images/optimize_ball_sfd_seals_convergence.png
      cp "$out/optimize_ball_sfd_seals/spectrogram_bearing.compressor.fx_comparison.png" \
        docs/images/optimize_ball_sfd_seals_spectrogram_compressor_force.png
      ;;
    optimize_seals_groove)
      # The same dampers fed through a central feed groove instead of the top hole (docs/optimization.md).
      rm -rf "$out/optimize_ball_sfd_seals_groove"
      run_timed optimize_ball_sfd_seals_groove optimize_seals_groove.log \
        "$exe" optimize examples/optimize_reference_ball_sfd_seals_groove.toml \
        -o "$out/optimize_ball_sfd_seals_groove"
      ;;
    floating_ring)
      run_study floating_ring
      for f in sensitivity_max_compressor_orbit.png map_max_compressor_orbit.png \
               map_max_compressor_bearing_force.png; do
        cp "$out/study_floating_ring/$f" "docs/images/study_floating_ring_$f"
      done
      cp "$out/study_floating_ring/metric_subsync_frequency_vs_bearings.compressor.outer_clearance.png" \
        docs/images/study_floating_ring_subsync_frequency_vs_outer_clearance.png
      for f in map_outer_whirl_amplitude.png map_min_inner_film_compressor.png map_min_outer_film_turbine.png; do
        cp "$out/study_floating_ring/$f" "docs/images/study_floating_ring_$f"
      done
      cp "$out/study_floating_ring/metric_outer_whirl_onset_vs_bearings.compressor.outer_clearance.png" \
        docs/images/study_floating_ring_outer_whirl_onset_vs_outer_clearance.png
      ;;
    ball)
      run_study ball
      cp "$out/study_ball/metric_resonance_force_compressor_vs_bearings.compressor.preload.png" \
        docs/images/study_ball_resonance_force_vs_preload.png
      cp "$out/study_ball/metric_resonance_speed_compressor_vs_bearings.compressor.preload.png" \
        docs/images/study_ball_resonance_speed_vs_preload.png
      cp "$out/study_ball/map_force_at_window_end.png" docs/images/study_ball_map_force_at_window_end.png
      cp "$out/study_ball/map_force_at_top_speed_compressor.png" docs/images/study_ball_map_force_at_top_speed.png
      ;;
    ball_stability)
      run_study ball_stability
      cp "$out/study_ball_stability/map_onset_speed.png" docs/images/study_ball_stability_map_onset_speed.png
      run_study ball_stability_global
      run_study ball_stability_mount
      ;;
    ball_sfd)
      run_study ball_sfd
      cp "$out/study_ball_sfd/map_force_1x_compressor.png" docs/images/study_ball_sfd_map_force_1x_compressor.png
      cp "$out/study_ball_sfd/map_max_damper_eccentricity.png" docs/images/study_ball_sfd_map_max_damper_eccentricity.png
      ;;
    *) echo "validation_studies: unknown study '$w' (identify, identify_floating_ring, optimize, optimize_seals," \
            "optimize_seals_groove, floating_ring, ball, ball_stability, ball_sfd)" >&2; exit 2 ;;
  esac
done
