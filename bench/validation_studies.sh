#!/usr/bin/env bash
# The two long validation studies on the paper's ball-bearing variants, with the pictures their documents show:
#   identification of the ball-bearing preload and turbine unbalance (docs/identification.md, ~15 min on 2 cores),
#   damper optimisation of variant III (docs/optimization.md, ~30 min on 2 cores).
# Usage: bench/validation_studies.sh [identify] [optimize]   (default: both). Build first (scripts/build.sh).
# Results in out/validation_studies/; an interrupted optimisation resumes from its cache when run again.
set -euo pipefail
cd "$(dirname "$0")/.."
exe=build/app/turbodyn
[[ -x $exe ]] || { echo "validation_studies: build first (scripts/build.sh)" >&2; exit 1; }
which=("$@")
((${#which[@]})) || which=(identify optimize)
out=out/validation_studies
mkdir -p "$out" docs/images
for w in "${which[@]}"; do
  case $w in
    identify)
      rm -rf "$out/identify_reference_ball"
      "$exe" identify examples/identify_reference_ball.toml -o "$out/identify_reference_ball" | tee "$out/identify.log"
      cp "$out/identify_reference_ball/feature_order1x_x_turb_amplitude.png" \
        docs/images/identify_ball_feature_order1x_x_turb_amplitude.png
      ;;
    optimize)
      "$exe" optimize examples/optimize_reference_ball_sfd.toml -o "$out/optimize_ball_sfd" | tee "$out/optimize.log"
      cp "$out/optimize_ball_sfd/convergence.png" docs/images/optimize_ball_sfd_convergence.png
      cp "$out/optimize_ball_sfd/spectrogram_bearing.compressor.fx_comparison.png" \
        docs/images/optimize_ball_sfd_spectrogram_compressor_force.png
      cp "$out/optimize_ball_sfd/spectrogram_disk.compressor.x_comparison.png" \
        docs/images/optimize_ball_sfd_spectrogram_compressor_x.png
      ;;
    *) echo "validation_studies: unknown study '$w' (identify, optimize)" >&2; exit 2 ;;
  esac
done
