#!/usr/bin/env bash
# Grades a folder of submissions as a Slurm job array: array task K runs
# `shaderlab batch --shard K/N` into RESULTS/shard-K. The tasks share one cache, RESULTS/cache
# (reference renders and graded labs, keyed by content), so a lab folder that several students
# submitted alike is graded once for the whole class; a last job merges the shards into RESULTS/all.
#
# Usage, from the course folder (where build/framework/shaderlab is):
#   jobid=$(sbatch --parsable --array=1-8 scripts/slurm-batch.sh SUBMISSIONS RESULTS --lab LAB... [batch flags...])
#   sbatch --dependency=afterany:$jobid --wrap \
#     "${SHADERLAB:-build/framework/shaderlab} merge RESULTS/shard-* --out RESULTS/all"
# Set SHADERLAB to use another shaderlab program. See docs/instructors.md, "Slurm job arrays".
#
# Shards. K is the array task id (ids are shard numbers: --array=1-N) and N the number of shards,
# fixed for RESULTS by the first task that starts: SHADERLAB_SHARDS when set, else the highest task
# id of its array (8 for --array=1-8). That task writes N into RESULTS/shards; every later task
# (a requeued one, one resubmitted alone) reads it from there, so task 4 stays shard 4/8 however it
# is run again. Each shard records K/N and the list it was cut from in its summary.json, and
# `merge` refuses an incomplete set, naming the missing shards (a task cancelled while pending
# leaves no folder). To grade a different way (another N, other submissions), use a fresh RESULTS.
#
# Running one task again (failed, cancelled, or out of time; it resumes where it stopped):
#   scontrol requeue JOBID_4                                      (the same task, same log)
#   sbatch --array=4 scripts/slurm-batch.sh SUBMISSIONS RESULTS --lab LAB...   (when it never ran)
# and then the merge line again. Logs are appended to (--open-mode=append), so a requeued task
# keeps its first run's log above the second's.
#
# Resources. The defaults fit a node of 2 CPUs and 2 GB; ask for more on the command line, e.g.
#   sbatch --cpus-per-task=8 --mem-per-cpu=2G --time=04:00:00 --array=1-8 scripts/slurm-batch.sh ...
# A task grades one lab per CPU at a time (--jobs), and each render process may use what Slurm
# granted per CPU (SLURM_MEM_PER_CPU, or SLURM_MEM_PER_NODE over the CPUs) less 256 MiB for the
# worker around it (--memory; 2G where Slurm says nothing). --jobs or --memory among the batch
# flags replace these.
#SBATCH --job-name=shaderlab-batch
#SBATCH --cpus-per-task=2
#SBATCH --mem-per-cpu=1G
#SBATCH --time=01:00:00
#SBATCH --output=shaderlab-batch-%A_%a.log
#SBATCH --open-mode=append
set -euo pipefail
usage="usage: sbatch --array=1-N scripts/slurm-batch.sh SUBMISSIONS RESULTS [batch flags...]"
subs=${1:?$usage}
results=${2:?$usage}
shift 2
fail() {
  echo "slurm-batch.sh: $*" >&2
  exit 2
}
# sbatch runs a copy of this script from its spool folder: paths start from where it was submitted.
cd "${SLURM_SUBMIT_DIR:-.}"
bin=${SHADERLAB:-build/framework/shaderlab}
command -v "$bin" >/dev/null || fail "$bin: no shaderlab program there (build it, or set SHADERLAB)"
is_count() { [[ "$1" =~ ^[1-9][0-9]*$ ]]; }

k=${SLURM_ARRAY_TASK_ID:-1}
is_count "$k" || fail "array task id $k: task ids are shard numbers, from 1 (--array=1-N)"

# The plan: N, written once (a hard link is atomic, also on NFS), read by every task.
mkdir -p "$results"
plan="$results/shards"
if [ ! -e "$plan" ]; then
  n=${SHADERLAB_SHARDS:-${SLURM_ARRAY_TASK_MAX:-1}}
  is_count "$n" || fail "SHADERLAB_SHARDS=$n: expected a number of shards, 1 or more"
  tmp="$plan.tmp-$(hostname)-$$"
  echo "$n" >"$tmp"
  ln "$tmp" "$plan" 2>/dev/null || true # a task that started at the same time may have won
  rm -f "$tmp"
fi
n=$(cat "$plan")
is_count "$n" || fail "$plan: expected the number of shards, it holds '$n'"
if [ -n "${SHADERLAB_SHARDS:-}" ] && [ "$SHADERLAB_SHARDS" != "$n" ]; then
  fail "SHADERLAB_SHARDS=$SHADERLAB_SHARDS, but $results was graded in $n shards ($plan): use a fresh RESULTS folder"
fi
((k <= n)) || fail "task $k, but $results is graded in $n shards ($plan): run tasks 1 to $n, or use a fresh RESULTS folder"

# One worker per CPU; each render process gets the memory of its CPU less the worker's share.
cpus=${SLURM_CPUS_PER_TASK:-$(nproc)}
per_cpu_mb=""
if [ -n "${SLURM_MEM_PER_CPU:-}" ]; then
  per_cpu_mb=$SLURM_MEM_PER_CPU
elif [ -n "${SLURM_MEM_PER_NODE:-}" ] && ((SLURM_MEM_PER_NODE > 0)); then
  per_cpu_mb=$((SLURM_MEM_PER_NODE / cpus))
fi
memory=2G
if [ -n "$per_cpu_mb" ]; then
  mb=$((per_cpu_mb - 256))
  ((mb >= 256)) || mb=$((per_cpu_mb / 2))
  ((mb >= 64)) || fail "Slurm granted ${per_cpu_mb} MiB per CPU: too little to render (ask for --mem-per-cpu=1G)"
  memory="${mb}M"
fi
extra=()
has_flag() {
  local f=$1
  shift
  for a in "$@"; do [[ "$a" == "$f" || "$a" == "$f="* ]] && return 0; done
  return 1
}
has_flag --shard "$@" && fail "--shard is this script's (task K of N); pass the other batch flags"
has_flag --jobs "$@" || has_flag -j "$@" || extra+=(--jobs "$cpus")
has_flag --memory "$@" || extra+=(--memory "$memory")
has_flag --cache "$@" || extra+=(--cache "$results/cache")

# Mesa's shader cache stays out of the home folder (shaderlab also sets this unless it is set).
export MESA_SHADER_CACHE_DISABLE=true
command=("$bin" batch "$subs" --out "$results/shard-$k" --shard "$k/$n" "${extra[@]}" "$@")
echo "slurm-batch.sh: $(date -Is) on $(hostname), ${cpus} CPUs: ${command[*]}"
exec "${command[@]}"
