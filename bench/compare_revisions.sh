#!/usr/bin/env bash
# Times two git revisions side by side on the same short windows of the paper's three variants, interleaved
# (A, B, A, B, ...), and prints per case the medians of the integration wall time (summary.json) and of the CPU
# time of the process (user + sys), their ratios B/A, the steps, right-hand sides and force-element calls of each,
# and the largest relative difference of the maxima of B against A, so that every speed claim carries its
# accuracy check from the same runs.
#
# Usage: bench/compare_revisions.sh REV_A REV_B [N]
#   REV_A, REV_B  any git revisions (commit, branch, tag, HEAD~2, ...) of this repository
#   N             runs per case and revision (default 3)
# Environment:
#   CASES         cases to run, any of floating_ring ball ball_sfd ball_top ball_sfd_top (default the first three)
#   COMPARE_DIR   where the revisions are checked out and built (default /tmp/turbodyn-compare); a revision's
#                 build is kept there and reused by the next call (delete the directory to force a rebuild)
#   JOBS          build jobs (default 2)
#   ARCH          passed as -DTURBODYN_ARCH (auto, baseline, x86-64-v3, native; revisions before 7deaca0 ignore it and
#                 build for the baseline); unset: each revision's own default. Set it to compare across 7deaca0 like
#                 with like. Builds for a set ARCH go to build-ARCH.
#
# Each revision is checked out with `git worktree add --detach` as COMPARE_DIR/<commit> and built in its build/
# (Release, Ninja and ccache if present, only the `turbodyn` program); examples are read from that checkout. The cases, all with --no-plots:
#   floating_ring  examples/reference_floating_ring.toml, 0 -> 22,500 rpm in 0.6 s (the whirl onset window of
#                  docs/validation.md and issue 19's acceptance window)
#   ball           examples/reference_ball.toml, 0 -> 15,000 rpm in 0.4 s
#   ball_sfd       examples/reference_ball_sfd.toml, 0 -> 15,000 rpm in 0.4 s
# "max dev" is the largest of |max_B - max_A| / |max_A| over the maxima (summary.json probes' max_abs) of the
# compressor-wheel x, y and the compressor-bearing fx, fy (the four quantities of bench/convergence.sh); "all" is the
# same over every disk and bearing channel. Runs of one revision are deterministic; the script says so if the
# steps of the N runs differ.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
(($# >= 2)) || { sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//' >&2; exit 2; }
rev_a=$1 rev_b=$2 n=${3:-3}
cases=(${CASES:-floating_ring ball ball_sfd})
dir=${COMPARE_DIR:-/tmp/turbodyn-compare}
jobs=${JOBS:-2}
arch=${ARCH:-}
mkdir -p "$dir"

# Builds revision $1 (if not built yet) and prints the path of its turbodyn program.
build_revision() {
  local sha src bld
  sha=$(git -C "$root" rev-parse --verify "$1^{commit}")
  src=$dir/$sha bld=$dir/$sha/build${arch:+-$arch}
  if [[ ! -x $bld/app/turbodyn ]]; then
    if [[ ! -d $src ]]; then
      git -C "$root" worktree add --detach "$src" "$sha" > /dev/null 2>&1 ||
        { echo "compare_revisions: cannot check out $1 ($sha) in $src" >&2; return 1; }
    fi
    local gen=() launcher=() archflag=()
    [[ -n $arch ]] && archflag=(-DTURBODYN_ARCH="$arch")
    command -v ninja > /dev/null && gen=(-G Ninja)
    command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    echo "compare_revisions: building $1 ($sha) in $bld" >&2
    # build/ inside each checkout and one ccache base directory above them all: the compiler sees the same relative
    # paths for every revision, so unchanged files come from the cache.
    (export CCACHE_BASEDIR=$dir
     cmake -S "$src" -B "$bld" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "${archflag[@]}" > "$dir/$sha.build.log" 2>&1 &&
       cmake --build "$bld" --target turbodyn -j "$jobs" >> "$dir/$sha.build.log" 2>&1) ||
      { echo "compare_revisions: build of $1 failed (see $dir/$sha.build.log)" >&2; return 1; }
  fi
  echo "$bld/app/turbodyn"
}

args_for() {
  case $1 in
    floating_ring) echo "examples/reference_floating_ring.toml --set speed.end=22500rpm --set speed.duration=0.6" ;;
    ball) echo "examples/reference_ball.toml --set speed.end=15000rpm --set speed.duration=0.4" ;;
    ball_sfd) echo "examples/reference_ball_sfd.toml --set speed.end=15000rpm --set speed.duration=0.4" ;;
    # Top speed, where the full ball runs spend their time: 1,000 rpm of the ramp (26.7 ms) started mid-ramp.
    ball_top) echo "examples/reference_ball.toml --set speed.start=140000rpm --set speed.end=141000rpm --set speed.duration=0.02667" ;;
    ball_sfd_top) echo "examples/reference_ball_sfd.toml --set speed.start=140000rpm --set speed.end=141000rpm --set speed.duration=0.02667" ;;
    *) echo "compare_revisions: unknown case '$1' (floating_ring, ball, ball_sfd, ball_top, ball_sfd_top)" >&2; return 1 ;;
  esac
}

exe_a=$(build_revision "$rev_a")
exe_b=$(build_revision "$rev_b")
out=$(mktemp -d "$dir/runs.XXXXXX")
trap 'rm -rf "$out"' EXIT

# One run: revision label (a|b), program, case, index. Writes $out/<case>.<label>.<i>/ and its .cpu (user + sys, s).
run_one() {
  local label=$1 exe=$2 case=$3 i=$4 run
  run=$out/$case.$label.$i
  local -a a
  read -r -a a <<< "$(args_for "$case")"
  # Examples are read from the revision's own tree, so that a changed example is part of the comparison.
  local src
  src=$(dirname "$(dirname "$(dirname "$exe")")")
  (cd "$src" && /usr/bin/time -f "%U %S" -o "$run.time" "$exe" run "${a[@]}" --no-plots -o "$run" > "$run.log" 2>&1) ||
    echo "compare_revisions: $case ($label, run $i) exited with an error (see $run.log)" >&2
  awk '{print $1 + $2}' "$run.time" > "$run.cpu"
}

for ((i = 1; i <= n; i++)); do
  for c in "${cases[@]}"; do
    run_one a "$exe_a" "$c" "$i"
    run_one b "$exe_b" "$c" "$i"
  done
done

echo "A = $rev_a ($(git -C "$root" rev-parse --short "$rev_a^{commit}")), B = $rev_b ($(git -C "$root" rev-parse --short "$rev_b^{commit}")), $n interleaved runs each, medians"
python3 - "$out" "$n" "${cases[@]}" <<'EOF'
import json, statistics, sys
out, n, cases = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
key4 = ("disk.compressor.x", "disk.compressor.y", "bearing.compressor.fx", "bearing.compressor.fy")

def load(case, label):
    runs = []
    for i in range(1, n + 1):
        base = "%s/%s.%s.%d" % (out, case, label, i)
        try:
            s = json.load(open(base + "/summary.json"))
        except (OSError, ValueError):
            continue
        s["_cpu"] = float(open(base + ".cpu").read())
        runs.append(s)
    return runs

def dev(a, b, keys):
    worst, where = 0.0, "-"
    for k in keys:
        if k not in a["probes"] or k not in b["probes"]:
            continue
        x, y = a["probes"][k]["max_abs"], b["probes"][k]["max_abs"]
        d = abs(y - x) / abs(x) if x != 0 else (0.0 if y == 0 else float("inf"))
        if d > worst:
            worst, where = d, k
    return worst, where

head = "%-14s %-3s %9s %13s %8s %9s %8s %9s %8s %9s %11s %9s  %s"
print(head % ("case", "rev", "wall [s]", "range", "B/A", "CPU [s]", "B/A", "steps", "per step", "rhs", "elem calls",
              "max dev", "worst channel"))
for c in cases:
    A, B = load(c, "a"), load(c, "b")
    if not A or not B:
        print("%-14s missing runs (see the logs)" % c)
        continue
    med = lambda runs, f: statistics.median(f(r) for r in runs)
    wall = [med(R, lambda r: r["stats"]["wall_time_s"]) for R in (A, B)]
    cpu = [med(R, lambda r: r["_cpu"]) for R in (A, B)]
    steps = [med(R, lambda r: r["stats"]["steps"]) for R in (A, B)]
    for k, (label, R) in enumerate((("A", A), ("B", B))):
        st = R[-1]["stats"]
        same = len({r["stats"]["steps"] for r in R}) == 1
        complete = all(r["complete"] for r in R)
        walls = [r["stats"]["wall_time_s"] for r in R]
        rng = "%.2f-%.2f" % (min(walls), max(walls))
        ratio_w = ratio_c = ratio_s = d4s = worst = ""
        if k == 1:
            ratio_s = "%.3f" % ((cpu[1] / steps[1]) / (cpu[0] / steps[0]))
            ratio_w, ratio_c = "%.3f" % (wall[1] / wall[0]), "%.3f" % (cpu[1] / cpu[0])
            d4, _ = dev(A[-1], B[-1], key4)
            keys = [p for p in A[-1]["probes"] if p.startswith("disk.") or p.endswith(".fx") or p.endswith(".fy")]
            da, wa = dev(A[-1], B[-1], keys)
            d4s, worst = "%.3f %%" % (100 * d4), "%.3f %% (%s)" % (100 * da, wa)
        print(head % (c if k == 0 else "", label, "%.2f" % wall[k], rng, ratio_w, "%.2f" % cpu[k], ratio_c,
                      "%d%s" % (st["steps"], "" if same else "*"), ratio_s, st["rhs_calls"], st["force_element_calls"],
                      d4s, worst + ("" if complete else "  INCOMPLETE RUN")))
print("wall: integration wall time (summary.json); CPU: user + sys of the process; medians of the runs; per step: "
      "B/A of the median CPU per median step count (the ball windows' steps move with round-off); max dev: "
      "maxima of compressor x, y, fx, fy, B against A; * = the runs of one revision took different step counts")
EOF
