#!/usr/bin/env bash
# A study on a real Slurm scheduler, on this one machine (issue 21): installs Debian's Slurm and MUNGE if they are
# missing, starts a private single-node cluster (controller and compute node = this host; configuration, keys,
# state, spool and logs in a temporary directory; its own ports, so a system Slurm is left alone), runs the study
# as a job array of 3 shards through examples/slurm_sweep.sh, merges the shards, runs the same study without Slurm
# on one thread and checks that the merged results table equals the single-machine one. The scheduler is stopped
# on exit, also on failure or Ctrl-C.
#
# Usage: bench/slurm_cluster.sh [STUDY] [OUT]
#   STUDY  default examples/study_reference_linear.toml (16 run-ups of the linear rotor)
#   OUT    default out/slurm; its shard_*, merged, single and slurm-*.out are replaced on every call
# Environment:
#   TURBODYN        the turbodyn binary (default build/app/turbodyn, built with scripts/build.sh if missing)
#   SHARDS          array size (default 3)
#   SLURM_PORT_BASE slurmctld listens on it, slurmd on it + 1 (default 6917; Slurm's own default is 6817)
#   ARRAY_TIMEOUT   seconds to wait for the job array (default 3600)
# Needs root, or sudo for installing the packages and running munged, slurmctld and slurmd (slurmd runs jobs).
set -euo pipefail
# Paths given as arguments or in TURBODYN are relative to the caller's directory; the defaults to the repository.
[[ -n "${1:-}" ]] && study_arg=$(realpath -m -- "$1")
[[ -n "${2:-}" ]] && out_arg=$(realpath -m -- "$2")
[[ -n "${TURBODYN:-}" ]] && TURBODYN=$(realpath -m -- "$TURBODYN")
cd "$(dirname "$0")/.."
repo=$(pwd)

die() { echo "slurm_cluster.sh: FAILED: $*" >&2; exit 1; }
now() { date +%s.%N; }
alive() { [[ -r /proc/$1/stat ]] && [[ $(awk '{print $3}' "/proc/$1/stat" 2> /dev/null) != Z ]]; }  # not a zombie
phase_start=0
declare -a phase_lines=()
begin() { phase_name=$1; phase_start=$(now); echo; echo "== $1"; }
end() {
  local t; t=$(awk -v a="$phase_start" -v b="$(now)" 'BEGIN {printf "%.1f", b - a}')
  phase_lines+=("$(printf '%-50s %6s s' "$phase_name" "$t")")
  echo "-- $phase_name: $t s"
}

study=${study_arg:-examples/study_reference_linear.toml}
out=${out_arg:-out/slurm}
shards=${SHARDS:-3}
port=${SLURM_PORT_BASE:-6917}
array_timeout=${ARRAY_TIMEOUT:-3600}
[[ -f "$study" ]] || die "study file '$study' not found"
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || die "SHARDS must be a positive integer"
study=$(realpath "$study")
mkdir -p "$out"
out=$(realpath "$out")

if [[ $(id -u) == 0 ]]; then
  SUDO=()
else
  command -v sudo > /dev/null || die "not root and no sudo: installing Slurm and running slurmd need root"
  SUDO=(sudo)
fi

# --- turbodyn ---------------------------------------------------------------------------------------------------
begin "turbodyn binary"
if [[ -n "${TURBODYN:-}" ]]; then
  [[ -x "$TURBODYN" ]] || die "TURBODYN=$TURBODYN is not an executable"
else
  TURBODYN=build/app/turbodyn
  if [[ ! -x "$TURBODYN" ]]; then
    echo "build/app/turbodyn missing: building with scripts/build.sh"
    scripts/build.sh
  fi
fi
TURBODYN=$(realpath "$TURBODYN")
echo "turbodyn: $TURBODYN"
end

# --- packages ---------------------------------------------------------------------------------------------------
begin "install slurm-wlm and munge (if missing)"
need=(slurmctld slurmd sbatch sinfo squeue scontrol munged)
missing=0
for c in "${need[@]}"; do command -v "$c" > /dev/null || missing=1; done
if ((missing)); then
  echo "installing slurm-wlm munge with apt-get"
  apt=("${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get)
  if ! "${apt[@]}" install -y slurm-wlm munge; then
    "${apt[@]}" update
    "${apt[@]}" install -y slurm-wlm munge || die "apt-get install slurm-wlm munge"
  fi
  for c in "${need[@]}"; do command -v "$c" > /dev/null || die "$c still missing after installing slurm-wlm munge"; done
else
  echo "already installed"
fi
echo "$(slurmctld -V), $(munged --version 2>&1 | head -1)"
end

# --- private cluster --------------------------------------------------------------------------------------------
state=$(mktemp -d "${TMPDIR:-/tmp}/turbodyn-slurm.XXXXXX")
chmod 755 "$state"   # slurmd (root) and the jobs (this user) read it; munged wants no group/other write
declare -a daemon_pids=() daemon_names=()
jobid=""
ok=0
cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  if ((${#daemon_pids[@]})); then
    echo
    echo "== stopping the scheduler"
    local i
    # Jobs still queued or running (interrupt, timeout) are cancelled first: a slurmstepd whose slurmd has gone
    # would linger.
    if [[ -n "$jobid" ]] && [[ -n $(squeue -h -j "$jobid" 2> /dev/null) ]]; then
      scancel "$jobid" 2> /dev/null || true
      for _ in $(seq 60); do
        [[ -z $(squeue -h -j "$jobid" 2> /dev/null) ]] && break
        sleep 0.5
      done
      echo "cancelled job array $jobid"
    fi
    for ((i = ${#daemon_pids[@]} - 1; i >= 0; i--)); do
      if alive "${daemon_pids[i]}"; then
        "${SUDO[@]}" kill -TERM "${daemon_pids[i]}" 2> /dev/null || true
        for _ in $(seq 50); do
          alive "${daemon_pids[i]}" || break
          sleep 0.2
        done
        "${SUDO[@]}" kill -KILL "${daemon_pids[i]}" 2> /dev/null || true
        echo "stopped ${daemon_names[i]} (pid ${daemon_pids[i]})"
      fi
    done
    wait 2> /dev/null || true
  fi
  if ((ok)); then
    "${SUDO[@]}" rm -rf "$state"
  else
    echo "slurm_cluster.sh: configuration and daemon logs kept in $state" >&2
    for log in "$state"/log/*.log; do
      [[ -s "$log" ]] && { echo "--- tail of $log" >&2; tail -n 15 "$log" >&2; }
    done
    ((rc)) || rc=1
  fi
  exit "$rc"
}
trap cleanup EXIT
trap 'echo "slurm_cluster.sh: interrupted" >&2; exit 130' INT TERM

begin "start munged, slurmctld, slurmd"
host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$state"/{munge,ctld,spool,log,bin}
# A copy of the binary serves the jobs, the merge and the single-machine run alike: a rebuild of build/ while the
# script runs can neither break a job nor mix two versions in the comparison.
cp "$TURBODYN" "$state/bin/turbodyn"
TURBODYN=$state/bin/turbodyn
chmod 755 "$state/munge"   # clients (sinfo, sbatch) reach the socket; the key itself is 0400
# munged's key: 1 KiB from the kernel's generator, readable only by the daemon's user.
dd if=/dev/urandom of="$state/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$state/munge/munge.key"
if ((${#SUDO[@]})); then "${SUDO[@]}" chown -R root:root "$state/munge"; fi
sock=$state/munge/munge.socket
for p in "$port" $((port + 1)); do
  if (exec 3<> "/dev/tcp/127.0.0.1/$p") 2> /dev/null; then
    die "port $p is in use (another slurmctld/slurmd? set SLURM_PORT_BASE)"
  fi
done
conf=$state/slurm.conf
cat > "$conf" << EOF
# Private single-machine cluster of bench/slurm_cluster.sh
ClusterName=turbodyn
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/spool
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/log/slurmctld.log
SlurmdLogFile=$state/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SlurmdParameters=config_overrides
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MinJobAge=3600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1024 State=UNKNOWN
PartitionName=turbodyn Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$conf
slurm_version=$(sinfo --version)   # the clients want a configuration even for this
echo "slurm.conf: $conf (host $host, $cpus CPUs, ports $port/$((port + 1)))"

start_daemon() {  # name, command...
  local name=$1
  shift
  "${SUDO[@]}" "$@" > "$state/log/$name.stdout" 2>&1 &
  daemon_pids+=($!)
  daemon_names+=("$name")
}
start_daemon munged munged --foreground --force --key-file="$state/munge/munge.key" --socket="$sock" \
  --pid-file="$state/munge/munged.pid" --log-file="$state/log/munged.log" --seed-file="$state/munge/munged.seed"
for _ in $(seq 50); do [[ -S "$sock" ]] && break; sleep 0.2; done
[[ -S "$sock" ]] || die "munged did not create its socket $sock"
munge -S "$sock" -n | unmunge -S "$sock" > /dev/null || die "munge/unmunge round trip on $sock"
echo "munged up (socket $sock)"
start_daemon slurmctld env SLURM_CONF="$conf" slurmctld -D -c -f "$conf"
start_daemon slurmd env SLURM_CONF="$conf" slurmd -D -N "$host" -f "$conf"
deadline=$((SECONDS + 90))
state_now=""
while ((SECONDS < deadline)); do
  for i in "${!daemon_pids[@]}"; do
    alive "${daemon_pids[i]}" || die "${daemon_names[i]} exited (see $state/log)"
  done
  state_now=$(sinfo -h -n "$host" -o %t 2> /dev/null || true)
  [[ "$state_now" == idle ]] && break
  sleep 0.5
done
[[ "$state_now" == idle ]] || die "node $host not idle after 90 s (state '${state_now:-no answer}')"
sinfo
end

# --- the study as a job array -----------------------------------------------------------------------------------
begin "job array of $shards shards (sbatch -> all done)"
rm -rf "$out"/shard_* "$out/merged" "$out/single"
rm -f "$out"/slurm-*.out
submitted=$(PATH="$state/bin:$PATH" sbatch --parsable --array=0-$((shards - 1)) --cpus-per-task=1 --chdir="$repo" \
  --output="$out/slurm-%A_%a.out" --job-name=turbodyn-sweep examples/slurm_sweep.sh "$study" "$out") \
  || die "sbatch"
jobid=${submitted%%;*}
echo "submitted array job $jobid: examples/slurm_sweep.sh $study $out"
deadline=$((SECONDS + array_timeout))
last=""
while :; do
  left=$(squeue -h -j "$jobid" -o '%i %T' 2> /dev/null) || die "squeue failed"
  [[ -z "$left" ]] && break
  summary=$(awk '{print $2}' <<< "$left" | sort | uniq -c | awk '{printf "%s%s %s", (NR > 1 ? ", " : ""), $1, $2}')
  [[ "$summary" != "$last" ]] && echo "  $(date +%T) $summary"
  last=$summary
  ((SECONDS < deadline)) || { scancel "$jobid" || true; die "job array $jobid not finished after $array_timeout s (cancelled)"; }
  sleep 1
done
failed=0
while read -r line; do
  task=$(grep -o 'ArrayTaskId=[0-9]*' <<< "$line" | cut -d= -f2)
  st=$(grep -o 'JobState=[A-Z_]*' <<< "$line" | cut -d= -f2)
  ec=$(grep -o ' ExitCode=[0-9:]*' <<< "$line" | cut -d= -f2)
  rt=$(grep -o ' RunTime=[0-9:-]*' <<< "$line" | cut -d= -f2)
  echo "  task $task: $st, exit code $ec, run time $rt"
  if [[ "$st" != COMPLETED || "$ec" != 0:0 ]]; then
    failed=1
    echo "--- $out/slurm-${jobid}_$task.out" >&2
    cat "$out/slurm-${jobid}_$task.out" >&2 || true
  fi
done < <(scontrol -o show job "$jobid")
((failed == 0)) || die "a task of job array $jobid failed (its output above)"
for ((k = 0; k < shards; k++)); do
  [[ -f "$out/shard_$k/results.csv" ]] || die "shard $k wrote no results.csv (see $out/slurm-${jobid}_$k.out)"
done
end

begin "merge the shards"
shard_dirs=()
for ((k = 0; k < shards; k++)); do shard_dirs+=("$out/shard_$k"); done
"$TURBODYN" merge "$study" "${shard_dirs[@]}" -o "$out/merged" --no-plots || die "turbodyn merge"
end

begin "same study on this machine without Slurm (-j 1)"
"$TURBODYN" sweep "$study" -j 1 --no-plots -o "$out/single" || die "turbodyn sweep -j 1"
end

# --- comparison -------------------------------------------------------------------------------------------------
begin "compare merged with single"
a=$out/merged/results.csv
b=$out/single/results.csv
header=$(head -n 1 "$a")
[[ "$header" == "$(head -n 1 "$b")" ]] || die "the headers of $a and $b differ"
[[ "$header" == *,wall_time_s ]] || die "results.csv no longer ends with wall_time_s: update the comparison"
rows=$(($(wc -l < "$a") - 1))
cols=$(awk -F, 'NR == 1 {print NF}' "$a")
# wall_time_s is the last column and a plain number: drop it from the last comma on.
if cmp -s <(sed 's/,[^,]*$//' "$a") <(sed 's/,[^,]*$//' "$b"); then
  echo "results.csv: $rows runs x $((cols - 1)) columns equal byte for byte (run, parameters, metrics, status,"
  echo "  error; the timing column wall_time_s left out): merged == single"
else
  diff <(sed 's/,[^,]*$//' "$a") <(sed 's/,[^,]*$//' "$b") >&2 || true
  die "merged results.csv differs from the single-machine one (diff above)"
fi
if cmp -s "$out/merged/sensitivity.csv" "$out/single/sensitivity.csv"; then
  echo "sensitivity.csv: equal byte for byte"
else
  diff "$out/merged/sensitivity.csv" "$out/single/sensitivity.csv" >&2 || true
  die "merged sensitivity.csv differs from the single-machine one"
fi
if cmp -s "$a" "$b"; then echo "(the wall times happen to be equal too)"; fi
end

echo
echo "== summary ($slurm_version, $host, $cpus CPUs; study $(basename "$study"), $shards shards)"
printf '%s\n' "${phase_lines[@]}"
echo "single-machine table == merged Slurm table: yes"
ok=1
