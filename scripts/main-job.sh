#!/usr/bin/env bash
# Quick start, command 1: install what is missing, build Release, run the main job.
# The main job is the Campbell diagram of the reference turbocharger on linear bearings (until the run-up lands);
# results and pictures go to out/reference/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
build/app/turbodyn modal examples/reference_linear.toml -o out/reference
echo "main job: pictures in out/reference/ (campbell.png, modes_*.png), numbers in out/reference/modal.json"
