#!/usr/bin/env bash
# Reproduces the whole-run figures of docs/validation.md and the run-up timings of bench/README.md with one
# command: the paper's three bearing variants (examples/reference_floating_ring.toml, reference_ball.toml,
# reference_ball_sfd.toml), each run up from 0 to 150,000 rpm in 4 s at its default fidelity, single thread, and
# the two smaller figures of the document (the reference rotor on linear bearings, the rigid rotor's oil whirl).
#
# Usage: bench/reproduce_validation.sh [N] [VARIANT ...]     (after scripts/build.sh)
#   N        runs per variant (default 1; 3 for the medians quoted in bench/README.md). The pictures of the last
#            run are copied into docs/images/ under the names docs/validation.md uses.
#   VARIANT  any of floating_ring ball ball_sfd linear oil_whirl (default: all five), or floating_ring_thermal:
#            variant I with thermal films in both bearings (docs/thermal-films.md), or floating_ring_groove: variant
#            I with both outer films fed through a 2-mm circumferential groove instead of the top hole, or
#            ball_window: issue 17's
#            window of variant II, 90,000 -> 99,375 rpm in 0.25 s from the balls' no-slip state, with 40-ms STFT
#            segments (docs/ball-bearing.md; about 10 s), which prints each wheel's largest sub-synchronous line
#            at its end
# Output: out/validation/<variant>/ (time series, summary.json, all pictures), out/validation/<variant>.timing
# (one line per variant: median and single integration wall times, CPU times, steps, calls), and a table of all
# variants timed so far on stdout and in out/validation/timings.txt. Expect 5-10 minutes per run of a paper
# variant on a 2-core machine; two invocations with different variants can share the machine, one per core
# (their timings then share the memory bandwidth).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-1}
shift || true
variants=("$@")
((${#variants[@]})) || variants=(floating_ring ball ball_sfd linear oil_whirl)
exe=${TURBODYN:-build/app/turbodyn}  # TURBODYN: another binary (e.g. a copy, so that the build can go on)
[[ -x $exe ]] || { echo "reproduce_validation: build first (scripts/build.sh)" >&2; exit 1; }
mkdir -p out/validation docs/images

summary_field() {  # summary.json, python expression on s
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); print($2)" "$1"
}
median() { sort -g | awk '{a[NR]=$1} END {print (NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2}'; }

model_of() {
  case $1 in
    linear) echo examples/reference_linear.toml ;;
    oil_whirl) echo examples/rigid_rotor_oil_whirl.toml ;;
    floating_ring_thermal | floating_ring_groove) echo examples/reference_floating_ring.toml ;;
    ball_window) echo examples/reference_ball.toml ;;
    *) echo "examples/reference_$1.toml" ;;
  esac
}

sets_of() {  # the overrides that make a variant out of its model file
  case $1 in
    floating_ring_thermal) echo "--set bearings.compressor.thermal=bulk --set bearings.turbine.thermal=bulk" ;;
    floating_ring_groove)
      echo "--set bearings.compressor.feed_hole_diameter=0mm --set bearings.turbine.feed_hole_diameter=0mm" \
           "--set bearings.compressor.feed_groove_width=2mm --set bearings.turbine.feed_groove_width=2mm" ;;
    ball_window) echo "--set speed.start=90000rpm --set speed.end=99375rpm --set speed.duration=0.25s" \
                      "--set output.spectrogram_segment=800" ;;
  esac
}

for v in "${variants[@]}"; do
  model=$(model_of "$v")
  read -r -a sets <<< "$(sets_of "$v")"
  [[ -f $model ]] || { echo "reproduce_validation: no $model" >&2; exit 2; }
  dir=out/validation/$v
  walls=() cpus=()
  for ((i = 1; i <= n; i++)); do
    rm -rf "$dir"
    # Pictures only in the last run: they do not enter the integration wall time in summary.json anyway.
    plots=(--no-plots)
    ((i == n)) && plots=()
    status=0
    TIMEFORMAT=%U
    { time "$exe" run "$model" "${sets[@]}" "${plots[@]}" -o "$dir" > "out/validation/$v.log" 2>&1 || status=$?; } 2> "$dir.cpu"
    ((status == 0)) || echo "reproduce_validation: $v run $i ended with exit code $status (see out/validation/$v.log)" >&2
    walls+=("$(summary_field "$dir/summary.json" "s['stats']['wall_time_s']")")
    cpus+=("$(cat "$dir.cpu")")
    rm -f "$dir.cpu"
  done
  read -r steps rhs calls complete < <(summary_field "$dir/summary.json" \
    "s['stats']['steps'], s['stats']['rhs_calls'], s['stats']['force_element_calls'], s['complete']")
  printf "%-15s %10.1f %24s %24s %10s %10s %12s %9s\n" "$v" "$(printf "%s\n" "${walls[@]}" | median)" \
    "$(printf "%.0f," "${walls[@]}" | sed 's/,$//')" "$(printf "%.0f," "${cpus[@]}" | sed 's/,$//')" \
    "$steps" "$rhs" "$calls" "$complete" > "out/validation/$v.timing"
  case $v in
    ball | ball_sfd)
      # The natural frequencies of the rotor on linear bearings of the ball bearing's static radial stiffness
      # (5.0e7 N/m at 40 N preload, BallBearing.StaticStiffness...) drawn on the spectrograms.
      [[ -f out/validation/modal_ball/campbell.csv ]] ||
        "$exe" modal examples/reference_linear.toml --speeds "0:150000 rpm:61" --no-plots \
          --set bearings.compressor.k=5e7 --set bearings.turbine.k=5e7 -o out/validation/modal_ball > /dev/null
      backbones=()
      if [[ $v == ball ]]; then
        # The forward 1x critical speeds at a whirl amplitude (turbodyn modal --amplitudes) on the wheels' 1x order
        # tracks: each branch measured at the wheel that moves most in its mode (the first at the turbine wheel,
        # the second at the compressor wheel).
        [[ -f out/validation/backbone/modal.json ]] ||
          "$exe" modal "$model" --speeds "0:60000 rpm:13" --amplitudes "1:600 um:40" --no-plots \
            -o out/validation/backbone > /dev/null
        backbones=(--backbone out/validation/backbone/modal.json)
      fi
      "$exe" plot "$dir" --campbell out/validation/modal_ball/campbell.csv "${backbones[@]}" > /dev/null
      ;;
  esac
  # The pictures docs/validation.md shows.
  case $v in
    ball_window)
      # No pictures for the document: what issue 17 measures, the lines below the rotor speed at the window's end.
      grep "largest sub-synchronous line at the end" "out/validation/$v.log" | sed 's/^ */ball_window: /'
      ;;
    linear)
      cp "$dir/spectrogram_disk.compressor.x.png" docs/images/runup_linear_spectrogram_compressor_x.png
      cp "$dir/spectrogram_bearing.compressor.fx.png" docs/images/runup_linear_spectrogram_compressor_force.png
      cp "$dir/order1x_disk.compressor.png" docs/images/runup_linear_order1x_compressor.png
      ;;
    oil_whirl)
      cp "$dir/spectrogram_disk.mid.x.png" docs/images/oil_whirl_rigid_rotor_spectrogram.png
      ;;
    *)
      cp "$dir/spectrogram_disk.compressor.x.png" "docs/images/variant_${v}_compressor_x.png"
      cp "$dir/spectrogram_bearing.compressor.fx.png" "docs/images/variant_${v}_compressor_force.png"
      for f in ring_speed_ratio film_temperatures contact_pressure film_thickness; do
        if [[ -f $dir/$f.png ]]; then cp "$dir/$f.png" "docs/images/variant_${v}_$f.png"; fi
      done
      if [[ $v == ball ]]; then
        cp "$dir/order1x_disk.compressor.png" docs/images/variant_ball_order1x_compressor.png
        cp "$dir/order1x_disk.turbine.png" docs/images/variant_ball_order1x_turbine.png
        # The nonlinear unbalance response through the first two criticals (docs/ball-bearing.md).
        "$exe" response "$model" --speeds "10000 rpm:60000 rpm:101" --nonlinear -o out/validation/response_ball \
          > /dev/null
        cp out/validation/response_ball/response.png docs/images/response_nonlinear_ball.png
        # A slow run-down through the first critical (1/16 of the paper's rate) on its steady states.
        "$exe" run "$model" --set speed.start=38000rpm --set speed.end=24000rpm --set speed.duration=5.97333s \
          --no-plots -o out/validation/rundown_ball > /dev/null
        "$exe" response "$model" --speeds "15000 rpm:45000 rpm:61" --nonlinear --no-plots \
          -o out/validation/response_ball_rundown > /dev/null
        "$exe" plot out/validation/rundown_ball --response out/validation/response_ball_rundown/response.json \
          > /dev/null
        cp out/validation/rundown_ball/order1x_disk.turbine.png docs/images/response_nonlinear_rundown_turbine.png
      fi
      ;;
  esac
done

{
  printf "%-15s %10s %24s %24s %10s %10s %12s %9s\n" variant "wall [s]" "runs, wall [s]" "runs, CPU [s]" steps \
    "rhs calls" "elem calls" complete
  for v in floating_ring floating_ring_thermal floating_ring_groove ball ball_sfd ball_window linear oil_whirl; do
    [[ -f out/validation/$v.timing ]] && cat "out/validation/$v.timing"
  done
} | tee out/validation/timings.txt
echo "reproduce_validation: pictures in docs/images/, runs in out/validation/"
