#!/usr/bin/env bash
# Reproduces the whole-run figures of docs/validation.md and the run-up timings of bench/README.md with one
# command: the paper's three bearing variants (examples/reference_floating_ring.toml, reference_ball.toml,
# reference_ball_sfd.toml), each run up from 0 to 150,000 rpm in 4 s at its default fidelity, single thread.
#
# Usage: bench/reproduce_validation.sh [N] [VARIANT ...]     (after scripts/build.sh)
#   N        runs per variant (default 1; 3 for the medians quoted in bench/README.md). The pictures of the last
#            run are copied into docs/images/ under the names docs/validation.md uses.
#   VARIANT  any of floating_ring ball ball_sfd (default: all three)
# Output: out/validation/<variant>/ (time series, summary.json, all pictures), a timing table on stdout, and
# out/validation/timings.txt. Expect tens of minutes per variant on a 2-core machine; run variants on both cores
# with two invocations if the machine is otherwise idle (timings then share the memory bandwidth).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-1}
shift || true
variants=("$@")
((${#variants[@]})) || variants=(floating_ring ball ball_sfd)
exe=build/app/turbodyn
[[ -x $exe ]] || { echo "reproduce_validation: build first (scripts/build.sh)" >&2; exit 1; }
mkdir -p out/validation docs/images

summary_field() {  # summary.json, python expression on s
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print($2)" "$1"
}

printf "%-15s %10s %22s %10s %10s %12s %9s\n" variant "wall [s]" "runs [s]" steps "rhs calls" "elem calls" complete |
  tee out/validation/timings.txt
for v in "${variants[@]}"; do
  model=examples/reference_${v}.toml
  [[ -f $model ]] || { echo "reproduce_validation: no $model" >&2; exit 2; }
  walls=()
  for ((i = 1; i <= n; i++)); do
    dir=out/validation/$v
    rm -rf "$dir"
    # Pictures only in the last run: they do not enter the integration wall time in summary.json anyway.
    plots=(--no-plots)
    ((i == n)) && plots=()
    status=0
    "$exe" run "$model" "${plots[@]}" -o "$dir" > "out/validation/$v.log" 2>&1 || status=$?
    ((status == 0)) || echo "reproduce_validation: $v run $i ended with exit code $status (see out/validation/$v.log)" >&2
    walls+=("$(summary_field "$dir/summary.json" "s['stats']['wall_time_s']")")
  done
  median=$(printf "%s\n" "${walls[@]}" | sort -g | awk '{a[NR]=$1} END {print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}')
  runs=$(printf "%.0f," "${walls[@]}")
  read -r steps rhs calls complete < <(summary_field "$dir/summary.json" \
    "s['stats']['steps'], s['stats']['rhs_calls'], s['stats']['force_element_calls'], s['complete']")
  printf "%-15s %10.1f %22s %10s %10s %12s %9s\n" "$v" "$median" "${runs%,}" "$steps" "$rhs" "$calls" "$complete" |
    tee -a out/validation/timings.txt
  # Ball-bearing variants: the natural frequencies of the rotor on linear bearings of the ball bearing's static
  # radial stiffness (5.0e7 N/m at 40 N preload, BallBearing.StaticStiffness...) drawn on the spectrograms.
  if [[ $v == ball || $v == ball_sfd ]]; then
    [[ -f out/validation/modal_ball/campbell.csv ]] ||
      "$exe" modal examples/reference_linear.toml --speeds "0:150000 rpm:61" --no-plots \
        --set bearings.compressor.k=5e7 --set bearings.turbine.k=5e7 -o out/validation/modal_ball > /dev/null
    "$exe" plot "$dir" --campbell out/validation/modal_ball/campbell.csv > /dev/null
  fi
  # The two pictures per variant that docs/validation.md shows beside the paper's Figs. 4-6.
  cp "$dir/spectrogram_disk.compressor.x.png" "docs/images/variant_${v}_compressor_x.png"
  cp "$dir/spectrogram_bearing.compressor.fx.png" "docs/images/variant_${v}_compressor_force.png"
done
echo "reproduce_validation: pictures in docs/images/variant_*.png, runs in out/validation/"
