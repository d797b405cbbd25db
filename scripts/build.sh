#!/usr/bin/env bash
# Configures and builds turbodyn (Release) in build/ with all cores. Used by main-job.sh and test-all.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# A unity build (each target's sources compiled in batches of 8) parses the heavy headers (Eigen, GoogleTest, the
# model's) once per batch: a clean build on 2 cores takes half the time (bench/README.md, "Build time"). Names at
# file scope are therefore distinct across a target's sources (README.md, "Building").
if [[ ! -f build/CMakeCache.txt ]]; then
  cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON
fi
cmake --build build --parallel "$(nproc)"
