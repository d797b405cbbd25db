#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build Release, run the main job.
# The main job is the paper's reference turbocharger in full-floating-ring bearings (variant I,
# examples/reference_floating_ring.toml), run up from 0 to 150,000 rpm in 4 s (out/reference/runup: spectrograms
# of displacement and bearing force against rotor speed as the paper's Fig. 4, 1x order tracking, orbits,
# timeseries.h5, summary.json), and the Campbell diagram of the same rotor on linear bearings
# (examples/reference_linear.toml, out/reference/modal) whose natural frequencies explain the resonances.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/app/turbodyn modal examples/reference_linear.toml -o out/reference/modal
build/app/turbodyn run examples/reference_floating_ring.toml -j "$(nproc)" -o out/reference/runup
echo "main job: open out/reference/runup/report.html (and out/reference/modal/report.html) in a browser:"
echo "          the key numbers and every picture of each result on one page."
echo "          Pictures in out/reference/runup (spectrogram_*.png, order1x_*.png, orbits_*.png) and"
echo "          out/reference/modal (campbell.png, modes_*.png); numbers in summary.json and modal.json"
