#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build Release, run the main job.
# The main job is the reference turbocharger rotor on linear bearings (until the nonlinear bearings land): its
# Campbell diagram (out/reference/modal) and its run-up to 150,000 rpm in 4 s (out/reference/runup).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/app/turbodyn modal examples/reference_linear.toml -o out/reference/modal
build/app/turbodyn run examples/reference_linear.toml -o out/reference/runup
echo "main job: pictures in out/reference/modal (campbell.png, modes_*.png) and out/reference/runup"
echo "          (spectrogram_*.png, order1x_*.png, orbits_*.png); numbers in modal.json and summary.json"
