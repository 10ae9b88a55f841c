#!/usr/bin/env bash
# make test-slurm: a real single-node Slurm on this machine (Debian's slurm-wlm and munge), everything in a temporary
# folder (munge key and socket, slurm.conf, state, spool, logs; non-default ports), stopped and removed at the end:
# no system-wide change outlives the test. Then, as a cluster user would:
#   1. the smoke study as a job array of 3 shards through studies/slurm_array.sh, and an afterok merge job;
#      the merged tables must equal a single run's byte for byte (all but the store and timings.csv);
#   2. the same again with one array task killed while it runs: the merge job's dependency can then never be met;
#      resubmitting that task alone (sbatch --array=K ... STUDY N) resumes it from its store, and a new merge job
#      gives the single run's tables again: nothing lost.
# Needs root or sudo (munged runs as the munge user, slurmd as root), BUILD (the build folder with beamid) and SRC.
set -euo pipefail
SRC=${SRC:-$(cd "$(dirname "$0")/../.." && pwd)}
BUILD=${BUILD:-$SRC/build}
start_time=$(date +%s)
as_root=(); as_munge=(runuser -u munge --)
[ "$(id -u)" -eq 0 ] || { as_root=(sudo); as_munge=(sudo -u munge); }

scratch=$(mktemp -d /tmp/beamid-slurm.XXXXXX)
chmod 755 "$scratch"
pids=()
cleanup() {
  for pid in "${pids[@]}"; do "${as_root[@]}" kill "$pid" 2>/dev/null || true; done
  sleep 1
  for pid in "${pids[@]}"; do "${as_root[@]}" kill -9 "$pid" 2>/dev/null || true; done
  "${as_root[@]}" rm -rf "$scratch"
}
trap cleanup EXIT
# The jobs' own logs first: CI shows a failure's head, and a shard's one-line error is the answer.
fail() { echo "FAIL: $*"; for f in "$scratch"/work/beamid-*.log "$scratch"/slurm/*.log; do [ -f "$f" ] && { echo "== $f"; tail -20 "$f"; }; done; exit 1; }

# munge: its own key, socket, pid and log, owned by the munge user, in the scratch folder.
m="$scratch/munge"
"${as_root[@]}" mkdir -p "$m"
"${as_root[@]}" dd if=/dev/urandom of="$m/munge.key" bs=1024 count=1 status=none
"${as_root[@]}" chown -R munge:munge "$m"
"${as_root[@]}" chmod 700 "$m"
"${as_root[@]}" chmod 400 "$m/munge.key"
"${as_munge[@]}" /usr/sbin/munged --key-file="$m/munge.key" --socket="$m/munge.socket" \
    --pid-file="$m/munged.pid" --log-file="$m/munged.log" --seed-file="$m/munged.seed" --force
for _ in $(seq 50); do [ -S "$m/munge.socket" ] && break; sleep 0.1; done
[ -S "$m/munge.socket" ] || fail "munged did not start"
pids+=("$("${as_root[@]}" cat "$m/munged.pid")")
# The socket's folder must let slurm's daemons and clients (root) reach it.
"${as_root[@]}" chmod 755 "$m"

# Slurm: one node (this machine, all its CPUs), one partition, ports off the defaults.
s="$scratch/slurm"
mkdir -p "$s/state" "$s/spool"
host=$(hostname -s)
cpus=$(nproc)
port=$((20000 + RANDOM % 20000))
cat >"$s/slurm.conf" <<CONF
ClusterName=beamid-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$m/munge.socket
StateSaveLocation=$s/state
SlurmdSpoolDir=$s/spool
SlurmctldPidFile=$s/slurmctld.pid
SlurmdPidFile=$s/slurmd.pid
SlurmctldLogFile=$s/slurmctld.log
SlurmdLogFile=$s/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
MinJobAge=600
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$s/slurm.conf"
"${as_root[@]}" env SLURM_CONF="$SLURM_CONF" /usr/sbin/slurmctld -D -f "$SLURM_CONF" >"$s/slurmctld.out" 2>&1 &
pids+=($!)
"${as_root[@]}" env SLURM_CONF="$SLURM_CONF" /usr/sbin/slurmd -D -f "$SLURM_CONF" >"$s/slurmd.out" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  state=$(sinfo -h -n "$host" -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.3
done
[ "$state" = idle ] || fail "the node did not come up (sinfo: '$state')"
echo "slurm: node $host idle with $cpus CPUs after $(( $(date +%s) - start_time )) s"

# The job's working folder: the project's build and study files, results of its own.
w="$scratch/work"
mkdir -p "$w"
ln -s "$BUILD" "$w/build"
ln -s "$SRC/studies" "$w/studies"
cd "$w"
"$BUILD/beamid" study studies/smoke.toml --output "$w/single" >/dev/null 2>&1 || fail "the single run failed"

wait_for() {  # wait_for JOBID...: until none is pending or running; a job whose dependency failed ends the test
  local jobs
  jobs=$(IFS=,; echo "$*")
  for _ in $(seq 1200); do
    [ -z "$(squeue -h -j "$jobs" -o %i 2>/dev/null)" ] && return 0
    # A job waiting on a failed one waits forever (it cost CI 10 minutes to learn that a shard had failed).
    squeue -h -j "$jobs" -o "%i %r" 2>/dev/null | grep -q DependencyNeverSatisfied &&
      fail "jobs $*: one can never start, a job it waits for failed"
    sleep 0.5
  done
  fail "jobs $* did not finish in 10 minutes"
}
job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -1; }
same_tables() {  # same_tables DIR: the merged tables equal the single run's
  diff -r -x store -x timings.csv "$w/single" "$1" >"$scratch/diff.txt" || { head -20 "$scratch/diff.txt"; return 1; }
}

# 1. Three shards and a merge job that waits for them.
array=$(sbatch --parsable --cpus-per-task=1 --array=1-3 studies/slurm_array.sh studies/smoke.toml 3)
shards=$(printf 'results/smoke-shard-%d,' 1 2 3); shards=${shards%,}
merge=$(sbatch --parsable --dependency="afterok:$array" --wrap \
  "build/beamid merge studies/smoke.toml --shards $shards --output results/merged")
wait_for "$array" "$merge"
[ "$(job_state "$merge")" = COMPLETED ] || fail "the merge job ended $(job_state "$merge")"
same_tables results/merged || fail "the merged tables differ from a single run's"
echo "slurm: 3 shards + afterok merge: tables equal the single run's byte for byte"

# 2. Again from scratch, with shard 2 killed while it runs: once its store holds the truth record and at least one
# unit (a shard of the smoke study runs its 20 units in 2-5 s, so a shard that finished before the kill landed is
# tried again, up to three times).
for attempt in 1 2 3; do
  rm -rf results
  array=$(sbatch --parsable --cpus-per-task=1 --array=1-3 studies/slurm_array.sh studies/smoke.toml 3)
  merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=no --wrap \
    "build/beamid merge studies/smoke.toml --shards $shards --output results/merged")
  for _ in $(seq 1200); do
    # Records only: the store also holds its lock file 'claim' (and a record being written is '*.rec.tmp'), so
    # counting every file let the kill land with the truth record alone and nothing for the resubmission to reuse.
    [ "$(find results/smoke-shard-2/store -type f -name '*.rec' 2>/dev/null | wc -l)" -ge 2 ] && break
    sleep 0.05
  done
  scancel "${array}_2"
  wait_for "$array"
  [ "$(job_state "${array}_2")" = CANCELLED ] && break
  echo "slurm: shard 2 finished before the kill landed (attempt $attempt); again"
  scancel "$merge"
  wait_for "$merge"
done
[ "$(job_state "${array}_2")" = CANCELLED ] || fail "shard 2 could not be killed while running in 3 attempts"
kept=$(find results/smoke-shard-2/store -type f -name '*.rec' | wc -l)
reason=$(squeue -h -j "$merge" -o %r)
echo "slurm: shard 2 killed with $kept records (its truth and units) in its store; the merge job waits: $reason"
scancel "$merge"
again=$(sbatch --parsable --cpus-per-task=1 --array=2 studies/slurm_array.sh studies/smoke.toml 3)
merge=$(sbatch --parsable --dependency="afterok:$again" --wrap \
  "build/beamid merge studies/smoke.toml --shards $shards --output results/merged")
wait_for "$again" "$merge"
[ "$(job_state "$merge")" = COMPLETED ] || fail "the merge job after the resubmission ended $(job_state "$merge")"
# Its summary line (study,units,computed,reused,...) counts the units it took from the store instead of computing.
reused=$(awk -F, '$1 == "smoke" { print $4 }' beamid-"${again}"_2.log)
[ "${reused:-0}" -ge 1 ] || fail "the resubmitted shard did not resume from its store (reused '${reused}')"
grep -q "truth records" beamid-"${again}"_2.log && fail "the resubmitted shard recomputed its truth record"
same_tables results/merged || fail "after the resubmission the merged tables differ from a single run's"
echo "slurm: shard 2 resubmitted alone took its truth and $reused unit(s) from its store; merged tables equal the single run's: nothing lost"
echo "slurm test passed in $(( $(date +%s) - start_time )) s"
