#!/usr/bin/env bash
# Sharding on a real Slurm (Debian slurm-wlm and munge): a one-node cluster started in a temporary
# folder (munged, slurmctld and slurmd on free ports, root as the Slurm user), examples/slurm's
# submit.sh sends the paper's Figure 1 at 64 frames as an array of 4 shards and a merge that waits
# for them (afterany); the merged glTF must be the single-machine run's bytes. Then a shard array
# with one task failing: the merge reports that shard missing, and rerunning it completes the job.
# Skipped (exit 77) when Slurm is not installed (a failure under CI) or cannot start here.
# usage: slurm_test.sh FVRML_RUN SOURCE_DIR
set -u
R="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
SRC="$(cd "$2" && pwd)"
. "$SRC/tests/support/skip.sh"
for tool in munged slurmctld slurmd sbatch squeue scontrol; do
  command -v "$tool" > /dev/null ||
    { fs_skip missing slurm "$tool is not installed (apt-get install slurm-wlm munge)" && exit 77; exit 1; }
done
[ "$(id -u)" = 0 ] || { fs_skip machine slurm "the test cluster runs its daemons as root" && exit 77; exit 1; }
T=$(mktemp -d)
fails=0
fail() { echo "FAIL $*"; fails=$((fails + 1)); }
export SLURM_CONF="$T/slurm.conf"
stop() {
  scontrol shutdown > /dev/null 2>&1
  sleep 1
  for pid in "$T"/slurmd.pid "$T"/slurmctld.pid "$T"/munged.pid; do [ -s "$pid" ] && kill "$(cat "$pid")" 2> /dev/null; done
  rm -rf "$T"
}
trap stop EXIT

# Two free ports next to each other (slurmctld, slurmd).
port=$(python3 -c 'import socket
for p in range(20000 + __import__("os").getpid() % 20000, 60000, 2):
    try:
        a, b = socket.socket(), socket.socket(); a.bind(("", p)); b.bind(("", p + 1)); a.close(); b.close(); print(p); break
    except OSError: pass')
host=$(hostname)
mkdir -p "$T/state" "$T/spool" "$T/log"
dd if=/dev/urandom of="$T/munge.key" bs=1024 count=1 2> /dev/null
chmod 400 "$T/munge.key"
cat > "$SLURM_CONF" <<EOF
ClusterName=fvrmltest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$T/munge.socket
CredType=cred/munge
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
PlugStackConfig=$T/plugstack.conf
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
: > "$T/plugstack.conf"
started=0
munged --force --key-file="$T/munge.key" --socket="$T/munge.socket" --pid-file="$T/munged.pid" \
  --log-file="$T/log/munged.log" --seed-file="$T/munge.seed" &&
  slurmctld -f "$SLURM_CONF" -i && slurmd -f "$SLURM_CONF" && started=1
for _ in $(seq 1 40); do
  [ "$started" = 1 ] && sinfo -h -o %t 2> /dev/null | grep -q idle && break
  sleep 0.5
done
if ! sinfo -h -o %t 2> /dev/null | grep -q idle; then
  tail -5 "$T"/log/*.log 2> /dev/null
  fs_skip machine slurm "a one-node Slurm cluster could not start here" && exit 77
  exit 1
fi
echo "slurm: a one-node cluster on $host, ports $port and $((port + 1))"

# wait_job ID SECONDS: until the job (every task of an array) has left the queue.
wait_job() {
  for _ in $(seq 1 $(($2 * 2))); do
    local left
    left=$(squeue -h -j "$1" -o %r 2> /dev/null)
    [ -z "$left" ] && return 0
    grep -q DependencyNeverSatisfied <<<"$left" && return 1
    sleep 0.5
  done
  return 1
}

# ---- Figure 1 at 64 frames in 4 shards, through examples/slurm as a user runs it ----
mkdir -p "$T/bin" "$T/examples"
ln -s "$R" "$T/bin/fvrml-run"
cp -r "$SRC/examples/slurm" "$SRC/examples/paper" "$T/examples/"
export PATH="$T/bin:$PATH"
jobs=$(cd "$T/examples/slurm" && OUTPUT=figure1.glb ./submit.sh 4) || fail "submit.sh: $jobs"
merge_job=$(tail -1 <<<"$jobs")
wait_job "$merge_job" 600 || fail "the merge job did not finish in 10 minutes"
"$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 64 -o "$T/single.glb" 2> /dev/null
parts=$(ls "$T"/examples/slurm/parts/part-*.fvc 2> /dev/null | wc -l)
[ "$parts" = 4 ] || fail "the array made $parts parts, not 4"
if cmp -s "$T/single.glb" "$T/examples/slurm/figure1.glb"; then
  echo "slurm: 4 shards merged into the single run's $(stat -c %s "$T/single.glb") bytes"
else
  fail "the merged figure1.glb differs from the single run's (merge log: $(tail -3 "$T/examples/slurm/parts/merge.log" 2> /dev/null))"
fi

# ---- One big shape in 3 slabs (FRAMES=0), PLY, through the same scripts ----
rm -rf "$T/examples/slurm/parts"
cp "$SRC/bench/scenes/gyroid-sphere256.wrl" "$T/examples/big.wrl"
jobs=$(cd "$T/examples/slurm" && FRAMES=0 FORMAT=ply SCENE=../big.wrl OUTPUT=big.ply ./submit.sh 3) || fail "submit.sh (slabs): $jobs"
wait_job "$(tail -1 <<<"$jobs")" 600 || fail "the merge of the slabs did not finish in 10 minutes"
"$R" "$T/examples/big.wrl" -o "$T/single.ply" 2> /dev/null
if cmp -s "$T/single.ply" "$T/examples/slurm/big.ply"; then
  echo "slurm: 3 slabs merged into the single run's $(stat -c %s "$T/single.ply") bytes of PLY"
else
  fail "the merged big.ply differs from the single run's (merge log: $(tail -3 "$T/examples/slurm/parts/merge.log" 2> /dev/null))"
fi

# ---- A shard that fails: the merge reports it missing; that shard again, then the merge ----
mkdir -p "$T/fail/parts"
cat > "$T/fail/shards.sbatch" <<EOF
#!/bin/bash
#SBATCH --output=parts/shard-%a.log
[ "\$SLURM_ARRAY_TASK_ID" = 2 ] && [ ! -e retry ] && exit 3
fvrml-run "$SRC/examples/paper/figure1-morphing.wrl" --frames 8 --format glb --shard auto -o parts/part-\$SLURM_ARRAY_TASK_ID.fvc
EOF
cp "$SRC/examples/slurm/merge.sbatch" "$T/fail/"
cd "$T/fail"
array=$(sbatch --parsable --array=0-3 shards.sbatch)
merge_job=$(OUTPUT=fail.glb sbatch --parsable --export=ALL --dependency="afterany:$array" merge.sbatch)
wait_job "$merge_job" 120 || fail "the merge after a failed shard did not finish"
[ -e fail.glb ] && fail "the merge wrote fail.glb although shard 2 failed"
grep -q '^error: shard 2 of 4 missing (run it with --shard 2/4)$' parts/merge.log ||
  fail "the merge's report of the failed shard: $(cat parts/merge.log)"
touch retry
rerun=$(FVRML_SHARDS=4 sbatch --parsable --export=ALL --array=2 shards.sbatch)
wait_job "$rerun" 120 || fail "the rerun shard did not finish"
merge_job=$(OUTPUT=fail.glb sbatch --parsable --export=ALL merge.sbatch)
wait_job "$merge_job" 120 || fail "the merge after the rerun did not finish"
"$R" "$SRC/examples/paper/figure1-morphing.wrl" --frames 8 -o single8.glb 2> /dev/null
cmp -s single8.glb fail.glb || fail "after rerunning the failed shard, the merge is not the single run's bytes: $(ls -la; cat parts/merge.log)"
cd /

[ "$fails" = 0 ] && echo "slurm: all checks passed"
exit $((fails > 0))
