#!/usr/bin/env bash
# Spreading a turbodyn study over a cluster with a Slurm job array: each array task runs one deterministic slice
# (--shard K/N) of the design into its own directory; a final job merges the slices.
#
#   sbatch --array=0-15 examples/slurm_sweep.sh examples/study_reference_linear.toml out/study
#   # when all tasks have finished:
#   turbodyn merge examples/study_reference_linear.toml out/study/shard_* -o out/study/merged
#
# Within a node the runs of a slice use all cores given to the task (TBB); a task that is killed (time limit,
# preemption) can simply be resubmitted: finished runs of its slice are not redone.
#SBATCH --job-name=turbodyn-sweep
#SBATCH --cpus-per-task=8
#SBATCH --time=04:00:00
#SBATCH --output=slurm-%A_%a.out
set -euo pipefail
study=$1
out=$2
n=${SLURM_ARRAY_TASK_COUNT:?run this script as a Slurm job array (sbatch --array=0-N)}
k=${SLURM_ARRAY_TASK_ID:?}
exec turbodyn sweep "$study" --shard "$k/$n" -j "${SLURM_CPUS_PER_TASK:-0}" --no-plots -o "$out/shard_$k"
