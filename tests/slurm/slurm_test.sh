#!/usr/bin/env bash
# The Slurm path of docs/instructors.md ("Slurm job arrays") on a real single-node Slurm: munged,
# slurmctld and slurmd started in the foreground on 127.0.0.1 from a slurm.conf in a temporary
# folder (proctrack/linuxproc, task/none: no cgroups, no systemd), a node of 2 CPUs and 2 GB so
# that scripts/slurm-batch.sh's own defaults must fit, and the daemons killed by pid on exit.
# On a small class (five submissions, one lab, one of them zipped) it checks that:
#   - the documented array and merge lines work, and the merge equals one plain `batch`
#     (summary.csv and summary.json byte for byte);
#   - a task cancelled while pending leaves no shard, and the merge refuses the set, naming it;
#   - that task submitted again alone (sbatch --array=3) grades shard 3/3, not 1/1;
#   - a task requeued (scontrol requeue) keeps its first log (--open-mode=append);
#   - the shards share the cache: the second grades nothing its predecessor graded;
#   - --memory follows what Slurm granted, and a zip's merged report names no shard folder.
# Needs root (the daemons, and apt-get for slurm-wlm and munge when they are missing); exits 77,
# saying why, where it cannot start Slurm.
# Usage: tests/slurm/slurm_test.sh SHADERLAB_PROGRAM SOURCE_DIR
set -euo pipefail
t_start=$(date +%s.%N)
bin=$(realpath "${1:?usage: slurm_test.sh SHADERLAB_PROGRAM SOURCE_DIR}")
src=$(realpath "${2:?usage: slurm_test.sh SHADERLAB_PROGRAM SOURCE_DIR}")
skip() {
  echo "SKIPPED: $*"
  exit 77
}
fail() {
  echo "FAILED: $*" >&2
  exit 1
}
since() { echo "$(date +%s.%N) $1" | awk '{printf "%.1f", $1 - $2}'; }

# ---- Slurm and munge ---------------------------------------------------------------------------
[ "$(id -u)" -eq 0 ] || skip "starting munged, slurmctld and slurmd needs root (run the test as root, e.g. in the container)"
have_slurm() { command -v munged && command -v slurmctld && command -v slurmd && command -v sbatch; } >/dev/null
if ! have_slurm; then
  command -v apt-get >/dev/null || skip "slurm-wlm and munge are not installed and there is no apt-get"
  t_install=$(date +%s.%N)
  echo "installing slurm-wlm and munge"
  install() { DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends slurm-wlm munge >/dev/null; }
  install || { apt-get update -qq && install; } || skip "slurm-wlm and munge cannot be installed (apt-get failed)"
  have_slurm || skip "slurm-wlm and munge were installed, but munged, slurmctld, slurmd or sbatch is missing"
  echo "installed in $(since "$t_install") s"
fi

work=$(mktemp -d /tmp/shaderlab-slurm.XXXXXX) # mode 0700, as munged wants its folders
pids=()
jobs_submitted=()
cleanup() {
  local code=$?
  set +e
  ((${#jobs_submitted[@]})) && scancel "${jobs_submitted[@]}" 2>/dev/null
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null; done
  for p in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$p" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$p" 2>/dev/null
    wait "$p" 2>/dev/null
  done
  if ((code != 0 && code != 77)); then
    echo "---- logs (kept in $work)"
    tail -n 20 "$work"/*.log "$work"/*.out 2>/dev/null
  else
    rm -rf "$work"
  fi
  exit "$code"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

# Two free TCP ports, away from a real Slurm's 6817 and 6818.
port_free() { ! (echo >"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
port=$((20000 + ($$ % 20000)))
while ! port_free "$port" || ! port_free $((port + 1)); do port=$((port + 2)); done

mkdir -p "$work/munge" "$work/state" "$work/spool"
chmod 700 "$work/munge"
head -c 1024 /dev/urandom >"$work/munge/munge.key"
chmod 600 "$work/munge/munge.key"
munged -F --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.sock" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munge/seed" \
  >"$work/munged.out" 2>&1 &
pids+=($!)
node=$(hostname -s)
cat >"$work/slurm.conf" <<EOF
ClusterName=shaderlab-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
ReturnToService=2
SlurmdParameters=config_overrides
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 RealMemory=2048 State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF="$work/slurm.conf"
for _ in $(seq 50); do [ -S "$work/munge/munge.sock" ] && break; sleep 0.1; done
[ -S "$work/munge/munge.sock" ] || skip "munged did not start: $(tail -n 3 "$work/munged.out")"
t_slurm=$(date +%s.%N)
slurmctld -D -i >"$work/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D >"$work/slurmd.out" 2>&1 &
pids+=($!)
state=""
for _ in $(seq 150); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || skip "Slurm did not start (node state '$state'): $(tail -n 3 "$work/slurmctld.out" "$work/slurmd.out")"
echo "Slurm up in $(since "$t_slurm") s (ports $port, $((port + 1)))"

# Waits until every job named is gone from the queue (at most 180 s); fails at once when one can
# never run on this node (the script asking for more than 2 CPUs and 2 GB).
wait_jobs() {
  local ids queue
  ids=$(IFS=, && echo "$*")
  for _ in $(seq 900); do
    queue=$(squeue -h -o '%i %T %r' -j "$ids" 2>/dev/null || true)
    [ -n "$queue" ] || return 0
    if grep -q PartitionConfig <<<"$queue"; then
      fail "a job can never start on a node of 2 CPUs and 2 GB: $queue"
    fi
    sleep 0.2
  done
  squeue >&2
  fail "jobs $* still queued after 180 s"
}

# Whether the summary.json $3 says shard $1 of $2.
is_shard() { grep -q "\"index\": $1," "$3" && grep -q "\"count\": $2," "$3"; }

# ---- the class ---------------------------------------------------------------------------------
# alice, bob and erin.zip hold the same lab folder, carol hers with a comment, dave the starter.
cd "$work"
lab=01-phong
mkdir -p subs/alice subs/bob subs/carol subs/dave zipped/erin
cp -r "$src/reference_solutions/$lab" subs/alice/
cp -r "$src/reference_solutions/$lab" subs/bob/
cp -r "$src/reference_solutions/$lab" subs/carol/
echo "// carol's own" >>"subs/carol/$lab/phong.frag"
mkdir -p "subs/dave/$lab" && cp "$src/labs/$lab/phong.vert" "$src/labs/$lab/phong.frag" "subs/dave/$lab/"
cp -r "$src/reference_solutions/$lab" zipped/erin/
python3 -c 'import shutil, sys; shutil.make_archive(sys.argv[1], "zip", sys.argv[2], "erin")' subs/erin zipped ||
  fail "python3 could not write the zip"
export SHADERLAB="$bin" SHADERLAB_LABS="$src/labs"
t_base=$(date +%s.%N)
"$bin" batch subs --out base --lab "$lab" --jobs 2 --cache base-cache >base.log 2>&1 || fail "the plain batch failed: $(tail -n 3 base.log)"
echo "one plain batch: $(since "$t_base") s"

# ---- the documented array and merge, with one task cancelled while pending ----------------------
t_array=$(date +%s.%N)
script="$src/scripts/slurm-batch.sh"
jobid=$(sbatch --parsable --array=1-3 "$script" subs results --lab "$lab")
jobs_submitted+=("$jobid")
# The node's 2 CPUs hold one task at a time (the script asks for 2): task 3 is still pending.
[ -n "$(squeue -h -t PD -j "${jobid}_3")" ] || fail "task 3 was not pending when cancelled: $(squeue)"
scancel "${jobid}_3"
merge1=$(sbatch --parsable --dependency="afterany:$jobid" --wrap \
  "${SHADERLAB:-build/framework/shaderlab} merge results/shard-* --out results/all")
jobs_submitted+=("$merge1")
wait_jobs "$jobid" "$merge1"
[ "$(cat results/shards 2>/dev/null)" = 3 ] || fail "results/shards does not say 3 shards"
[ ! -e results/shard-3 ] || fail "the cancelled task left results/shard-3"
for k in 1 2; do
  is_shard "$k" 3 "results/shard-$k/summary.json" ||
    fail "results/shard-$k/summary.json does not say shard $k/3"
  grep -q -- "--memory 768M" "shaderlab-batch-${jobid}_$k.log" ||
    fail "task $k: --memory is not Slurm's 1024 MiB per CPU less 256: $(grep slurm-batch.sh: "shaderlab-batch-${jobid}_$k.log")"
done
grep -q "incomplete: shard 3 of 3 is missing" "slurm-$merge1.out" ||
  fail "the merge of shards 1 and 2 of 3 did not refuse, naming shard 3: $(cat "slurm-$merge1.out")"
[ ! -e results/all/summary.csv ] || fail "the incomplete merge wrote results/all/summary.csv"
# Shard 2 (bob, erin.zip) holds only work shard 1 (alice, dave) graded: the shared cache has it.
grep -q " 0 worker runs" "shaderlab-batch-${jobid}_2.log" ||
  fail "shard 2 graded again what shard 1 graded: $(grep 'worker runs' "shaderlab-batch-${jobid}_2.log")"
echo "array of 3 (task 3 cancelled) and the refused merge: $(since "$t_array") s"

# ---- task 3 submitted again alone; task 1 requeued; the merge again -------------------------------
t_again=$(date +%s.%N)
again=$(sbatch --parsable --array=3 "$script" subs results --lab "$lab")
jobs_submitted+=("$again")
wait_jobs "$again"
is_shard 3 3 results/shard-3/summary.json ||
  fail "sbatch --array=3 did not grade shard 3/3: $(cat "shaderlab-batch-${again}_3.log")"
scontrol requeue "${jobid}_1"
scontrol update JobId="${jobid}_1" StartTime=now # Slurm otherwise holds a requeued job for 2 minutes
wait_jobs "${jobid}_1"
[ "$(grep -c '^slurm-batch.sh: ' "shaderlab-batch-${jobid}_1.log")" = 2 ] ||
  fail "the requeued task's log does not hold both runs: $(cat "shaderlab-batch-${jobid}_1.log")"
grep -q "(0 graded, 2 unchanged since their report)" "shaderlab-batch-${jobid}_1.log" ||
  fail "the requeued task graded again: $(tail -n 3 "shaderlab-batch-${jobid}_1.log")"
merge2=$(sbatch --parsable --dependency="afterany:$again" --wrap \
  "${SHADERLAB:-build/framework/shaderlab} merge results/shard-* --out results/all")
jobs_submitted+=("$merge2")
wait_jobs "$merge2"
grep -q "5 submissions from 3 results folders" "slurm-$merge2.out" || fail "the merge failed: $(cat "slurm-$merge2.out")"
echo "task 3 again, task 1 requeued, merge: $(since "$t_again") s"

# ---- the merge is the plain batch's --------------------------------------------------------------
cmp results/all/summary.csv base/summary.csv || fail "summary.csv: the merge differs from the plain batch"
cmp results/all/summary.json base/summary.json || fail "summary.json: the merge differs from the plain batch"
! grep -q "results/shard-" results/all/erin/report.json ||
  fail "erin.zip's merged report points into a shard: $(grep -o '"folder": "[^"]*"' results/all/erin/report.json)"
grep -q "\"folder\": \"$work/subs/erin.zip/erin/$lab\"" results/all/erin/report.json ||
  fail "erin.zip's report does not name the zip: $(grep -o '"folder": "[^"]*"' results/all/erin/report.json)"
echo "passed: the merged shards equal one batch; total $(since "$t_start") s"
