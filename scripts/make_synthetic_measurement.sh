#!/usr/bin/env bash
# Makes a synthetic "measured" run-up for `turbodyn identify`: runs the model with the true parameter values, then
# turns the probes into what a test bench exports: time [s], rotor speed [rpm], a tacho signal [V] (one pulse per
# revolution, rising edge through 2.5 V at rotor angle 0, edges 1.5 rad wide as from a real key-phasor), and
# displacement channels [um] with Gaussian noise (Box-Muller on awk's seeded rand()). Needs bash and awk only.
#
# Usage: scripts/make_synthetic_measurement.sh TURBODYN MODEL OUT.csv NOISE_UM SEED PROBE[=COLUMN] ... [-- --set ...]
# The example data set examples/data/bench_rotor_runup.csv was made with
#   scripts/make_synthetic_measurement.sh build/app/turbodyn examples/bench_rotor_journal.toml \
#     examples/data/bench_rotor_runup.csv 0.2 2026 disk.mid.x=x_mid disk.mid.y=y_mid
# (the true values are those of the model file; see examples/identify_bench_rotor.toml).
set -euo pipefail
if [ $# -lt 6 ]; then
  sed -n '2,13p' "$0"
  exit 2
fi
exe=$1 model=$2 out=$3 noise=$4 seed=$5
shift 5
probes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do probes+=("$1"); shift; done
[ $# -gt 0 ] && shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$exe" run "$model" --set output.csv=true --no-plots -o "$tmp" "$@" > "$tmp/log" 2>&1 || { cat "$tmp/log"; exit 1; }
spec=""
for p in "${probes[@]}"; do spec="$spec ${p}"; done
awk -F, -v noise="$noise" -v seed="$seed" -v spec="$spec" '
  function clamp(v) { return v < 0 ? 0 : (v > 1 ? 1 : v) }
  function gauss(   u1, u2) { u1 = rand(); if (u1 < 1e-300) u1 = 1e-300; u2 = rand(); return sqrt(-2 * log(u1)) * cos(6.283185307179586 * u2) }
  NR == 1 {
    srand(seed)
    for (i = 1; i <= NF; ++i) col[$i] = i
    n = split(spec, items, " ")
    header = "time [s],speed [rpm],tacho"
    for (k = 1; k <= n; ++k) {
      m = split(items[k], pc, "=")
      probe[k] = pc[1]; name[k] = (m > 1 ? pc[2] : pc[1])
      if (!((probe[k] "_m") in col)) { print "no probe " probe[k] " in the run" > "/dev/stderr"; exit 1 }
      pcol[k] = col[probe[k] "_m"]
      header = header "," name[k] " [um]"
    }
    print "# synthetic run-up made by scripts/make_synthetic_measurement.sh (noise " noise " um, seed " seed ")"
    print header
    next
  }
  {
    t = $col["time_s"]; f = $col["speed_Hz"]; a = $col["spin_angle_rad"]
    w = a - 6.283185307179586 * int(a / 6.283185307179586 + 0.5)   # wrapped to [-pi, pi)
    rise = clamp(0.5 + w / 1.5); fall = clamp(0.5 - (w - 2.0) / 1.5)
    line = sprintf("%.6f,%.3f,%.4f", t, 60 * f, 5 * (rise < fall ? rise : fall))
    for (k = 1; k <= n; ++k) line = line sprintf(",%.5f", 1e6 * $pcol[k] + noise * gauss())
    print line
  }' "$tmp/timeseries.csv" > "$out"
echo "wrote $out ($(($(wc -l < "$out") - 2)) rows)"
