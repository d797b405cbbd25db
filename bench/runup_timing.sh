#!/usr/bin/env bash
# End-to-end run-up timings: each case is run N times (default 3) without pictures; prints the median wall time
# of the integration and the steps and right-hand-side calls (from summary.json).
# Usage: bench/runup_timing.sh [N]        (after scripts/build.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-3}
exe=build/app/turbodyn
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

cases=(
  "reference_linear|examples/reference_linear.toml|"
  "reference_linear_bdf|examples/reference_linear.toml|--set solver.integrator=cvode-bdf"
  "reference_linear_erk|examples/reference_linear.toml|--set solver.integrator=arkode-erk"
)
[[ "${TURBODYN_BENCH_UNREDUCED:-0}" == 1 ]] && cases+=(
  "reference_linear_unreduced_bdf|examples/reference_linear.toml|--set solver.reduction_cutoff=0 --set solver.integrator=cvode-bdf"
)

printf "%-34s %10s %10s %12s %12s\n" case "wall [s]" "spread" steps "rhs calls"
for c in "${cases[@]}"; do
  IFS='|' read -r name model args <<< "$c"
  walls=()
  for ((i = 0; i < n; i++)); do
    # shellcheck disable=SC2086
    "$exe" run "$model" $args --no-plots -o "$out/$name" > /dev/null 2>&1
    walls+=("$(python3 -c "import json;print(json.load(open('$out/$name/summary.json'))['stats']['wall_time_s'])")")
  done
  read -r median spread < <(printf "%s\n" "${walls[@]}" | sort -g | awk '{a[NR]=$1} END {m=(NR%2)?a[(NR+1)/2]:(a[NR/2]+a[NR/2+1])/2; printf "%.2f %.2f-%.2f\n", m, a[1], a[NR]}')
  read -r steps rhs < <(python3 -c "import json;s=json.load(open('$out/$name/summary.json'))['stats'];print(s['steps'],s['rhs_calls'])")
  printf "%-34s %10s %10s %12s %12s\n" "$name" "$median" "$spread" "$steps" "$rhs"
done
