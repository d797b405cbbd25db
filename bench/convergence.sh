#!/usr/bin/env bash
# Convergence of the three reference variants in the numerical settings whose defaults the examples use: the
# film grids, the integrator tolerances and the shaft's finite-element mesh. Each setting is run on a window of
# the paper's ramp that contains the variant's characteristic behaviour (a full 4-s run per setting would take
# hours):
#   floating_ring  0 -> 22,500 rpm (0.6 s): inner-film whirl onset and its limit cycle
#   ball           0 -> 15,000 rpm (0.4 s): rolling, cage and ball-pass dynamics, rising unbalance response
#   ball_sfd       0 -> 15,000 rpm (0.4 s): the same with the damper films
# and the maxima of the compressor-wheel displacement and of the compressor-bearing force (x and y) are compared
# with the default; for the floating rings also the frequency of the inner-film whirl at the end of the window.
# Prints a table (also out/convergence/table_<variants>.txt).
#
# Usage: bench/convergence.sh [VARIANT ...]     (after scripts/build.sh; default all three)
set -euo pipefail
cd "$(dirname "$0")/.."
exe=${TURBODYN:-build/app/turbodyn}
[[ -x $exe ]] || { echo "convergence: build first (scripts/build.sh)" >&2; exit 1; }
variants=("$@")
((${#variants[@]})) || variants=(floating_ring ball ball_sfd)
out=out/convergence
mkdir -p "$out"

film() {  # film grid overrides for both bearings: KEYPREFIX NCIRC NAXIAL (KEYPREFIX like "" or "damper.")
  local p=$1 nc=$2 na=$3
  echo "--set bearings.compressor.${p}n_circ=$nc --set bearings.compressor.${p}n_axial=$na" \
       "--set bearings.turbine.${p}n_circ=$nc --set bearings.turbine.${p}n_axial=$na"
}

cases_for() {
  case $1 in
    floating_ring)
      echo "default|"
      echo "film grid 36 x 8|$(film "" 36 8)"
      echo "film grid 64 x 14|$(film "" 64 14)"
      echo "rtol 1e-6, atol 1e-10|--set solver.rtol=1e-6 --set solver.atol=1e-10"
      echo "rtol 1e-7, atol 1e-11|--set solver.rtol=1e-7 --set solver.atol=1e-11"
      echo "mesh 5 mm|--set mesh.max_element_length=5mm"
      ;;
    ball)
      echo "default|"
      echo "rtol 1e-5, atol 1e-9|--set solver.rtol=1e-5 --set solver.atol=1e-9"
      echo "rtol 1e-6, atol 1e-10|--set solver.rtol=1e-6 --set solver.atol=1e-10"
      echo "rtol 1e-7, atol 1e-11|--set solver.rtol=1e-7 --set solver.atol=1e-11"
      echo "mesh 5 mm|--set mesh.max_element_length=5mm"
      ;;
    ball_sfd)
      echo "default|"
      echo "damper grid 32 x 6|$(film damper. 32 6)"
      echo "damper grid 48 x 8|$(film damper. 48 8)"
      echo "damper grid 64 x 12|$(film damper. 64 12)"
      echo "newton_tolerance 0.1|--set solver.newton_tolerance=0.1"
      echo "rtol 1e-5, atol 1e-9|--set solver.rtol=1e-5 --set solver.atol=1e-9"
      echo "rtol 1e-6, atol 1e-10|--set solver.rtol=1e-6 --set solver.atol=1e-10"
      echo "rtol 1e-7, atol 1e-11|--set solver.rtol=1e-7 --set solver.atol=1e-11"
      echo "mesh 5 mm|--set mesh.max_element_length=5mm"
      ;;
  esac
}

window_for() {
  case $1 in
    floating_ring) echo "--set speed.end=22500rpm --set speed.duration=0.6" ;;
    *) echo "--set speed.end=15000rpm --set speed.duration=0.4" ;;
  esac
}

whirl() {  # timeseries.csv -> frequency (Hz) of the largest sub-synchronous line of the compressor wheel's x over
  # the last 40 ms (band 0.2-0.7 x rotor speed; a zero-padded DFT, 0.25 Hz steps), or "-"
  python3 - "$1" <<'EOF'
import cmath, csv, math, sys
try:
    rows = list(csv.DictReader(open(sys.argv[1])))
except OSError:
    print("-"); sys.exit()
t = [float(r["time_s"]) for r in rows]
x = [float(r["disk.compressor.x_m"]) for r in rows]
f_d = float(rows[-1]["speed_Hz"])
keep = [i for i in range(len(t)) if t[i] >= t[-1] - 0.04]
ts, xs = [t[i] for i in keep], [x[i] for i in keep]
mean = sum(xs) / len(xs)
best, f_best = -1.0, 0.0
f = 0.2 * f_d
while f <= 0.7 * f_d:
    a = abs(sum((xi - mean) * cmath.exp(-2j * math.pi * f * ti) for ti, xi in zip(ts, xs)))
    if a > best:
        best, f_best = a, f
    f += 0.25
print("%.1f" % f_best)
EOF
}

row() {  # summary.json -> "x y fx fy steps wall"
  python3 - "$1" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
p = s["probes"]
v = [p[k]["max_abs"] for k in ("disk.compressor.x", "disk.compressor.y", "bearing.compressor.fx", "bearing.compressor.fy")]
print("%.4f %.4f %.3f %.3f %d %.1f %s" % (v[0] * 1e6, v[1] * 1e6, v[2], v[3], s["stats"]["steps"], s["stats"]["wall_time_s"], s["complete"]))
EOF
}

{
  printf "%-14s %-22s %10s %10s %9s %9s %9s %8s %9s %10s\n" variant setting "x [um]" "y [um]" "fx [N]" "fy [N]" steps "wall [s]" \
    "max dev" "whirl [Hz]"
  for v in "${variants[@]}"; do
    ref=""
    while IFS='|' read -r name args; do
      dir=$out/$v/$(echo "$name" | tr -c 'a-z0-9\n' '_')
      mkdir -p "$out/$v"
      csv=""
      [[ $v == floating_ring ]] && csv="--set output.csv=true"
      # shellcheck disable=SC2086
      "$exe" run "examples/reference_${v}.toml" $(window_for "$v") $args $csv --no-plots -o "$dir" > "$dir.log" 2>&1 ||
        echo "convergence: $v '$name' exited with $? (see $dir.log)" >&2
      read -r x y fx fy steps wall complete < <(row "$dir/summary.json")
      if [[ -z $ref ]]; then ref="$x $y $fx $fy"; dev="-"; else
        dev=$(awk -v a="$ref" -v b="$x $y $fx $fy" 'BEGIN {split(a, r); split(b, c); m = 0;
          for (i = 1; i <= 4; ++i) { d = (c[i] - r[i]) / r[i]; if (d < 0) d = -d; if (d > m) m = d }
          printf "%.2f %%", 100 * m}')
      fi
      [[ $complete == True ]] || dev="$dev (incomplete)"
      f_w="-"
      [[ $v == floating_ring ]] && f_w=$(whirl "$dir/timeseries.csv")
      printf "%-14s %-22s %10s %10s %9s %9s %9s %8s %9s %10s\n" "$v" "$name" "$x" "$y" "$fx" "$fy" "$steps" "$wall" "$dev" "$f_w"
    done < <(cases_for "$v")
  done
} | tee "$out/table_$(IFS=_; echo "${variants[*]}").txt"
