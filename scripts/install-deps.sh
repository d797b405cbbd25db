#!/usr/bin/env bash
# Installs the Debian 12 packages turbodyn needs that are not installed yet (apt-get; as root or through sudo).
# Each package and why it is used is listed in README.md ("Dependencies").
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev          # linear algebra
  libtomlplusplus-dev    # model files (TOML, with line/column of every value for error messages)
  nlohmann-json3-dev     # JSON results
  libcli11-dev           # command line
  libsundials-dev        # time integration (CVODE, ARKODE)
  libhdf5-dev            # time-series results (HDF5)
  hdf5-tools             # h5dump: a test reads the time series as other HDF5 readers do
  libtbb-dev             # parallel parameter studies
  gnuplot-nox            # PNG pictures (pngcairo terminal)
  libgtest-dev libgmock-dev  # tests
  libbenchmark-dev       # micro-benchmarks
  libnlopt-cxx-dev       # design optimisation (turbodyn optimize)
  libceres-dev           # parameter identification (turbodyn identify)
  chromium               # a test opens every kind of report.html in a real browser (headless)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
