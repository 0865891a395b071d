#!/usr/bin/env bash
# Grades a folder of submissions as a Slurm job array: task K of N runs
# `shaderlab batch --shard K/N` into RESULTS/shard-K, all tasks sharing one reference cache; a
# last job merges the shards into RESULTS/all (summary.csv, summary.json, one report each).
#
# Usage, from the course folder (where build/framework/shaderlab is):
#   jobid=$(sbatch --parsable --array=1-8 scripts/slurm-batch.sh SUBMISSIONS RESULTS [batch flags...])
#   sbatch --dependency=afterany:$jobid --wrap \
#     "build/framework/shaderlab merge RESULTS/shard-* --out RESULTS/all"
# A task that was killed (time limit, preemption) is simply run again: the batch resumes.
# Set SHADERLAB to use another shaderlab program. See docs/instructors.md.
#SBATCH --job-name=shaderlab-batch
#SBATCH --cpus-per-task=4
#SBATCH --mem-per-cpu=6G
#SBATCH --time=01:00:00
#SBATCH --output=shaderlab-batch-%A_%a.log
set -euo pipefail
subs=${1:?usage: sbatch --array=1-N scripts/slurm-batch.sh SUBMISSIONS RESULTS [batch flags...]}
results=${2:?usage: sbatch --array=1-N scripts/slurm-batch.sh SUBMISSIONS RESULTS [batch flags...]}
shift 2
# sbatch runs a copy of this script from its spool folder: paths start from where it was submitted.
cd "${SLURM_SUBMIT_DIR:-.}"
bin=${SHADERLAB:-build/framework/shaderlab}
count=${SLURM_ARRAY_TASK_COUNT:-1}
task=$((${SLURM_ARRAY_TASK_ID:-1} - ${SLURM_ARRAY_TASK_MIN:-1} + 1))
# Mesa's shader cache stays out of the home folder (shaderlab also sets this unless it is set).
export MESA_SHADER_CACHE_DISABLE=true
exec "$bin" batch "$subs" --out "$results/shard-$task" --shard "$task/$count" \
  --jobs "${SLURM_CPUS_PER_TASK:-1}" --memory 6G --cache "$results/reference-cache" "$@"
