#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Distributed view-cell preprocessing (issue 16, item 6): starts a
# single-node Slurm cluster of its own on localhost (munged with its own key,
# slurmctld and slurmd, everything in a temporary directory, on free ports),
# runs a small part of the city (--cells 0-159, coarse cull maps) in 4 shards
# through tools/slurm/preprocess-view-cells.sh (a job array and a dependent
# merge job) and checks that the merged database is byte for byte the one a
# single process makes; then the same under GNU parallel; and that a failing
# shard cancels the merge. Stops every daemon it started, whatever happens.
# Prints whole-process wall times of the three runs (docs/view-cells-slurm.md).
# A missing package fails the test, naming it (tools/deps.sh test installs
# them). Runs as root: the daemons run as root and so do the jobs.
# Usage: view-cells-slurm.sh OCCU-PREPROCESS SLURM-SUBMIT-SCRIPT PARALLEL-SCRIPT
set -euo pipefail
bin=$1
submit=$2
par=$3
fail() { echo "FAIL: $*"; exit 1; }

[ "$(id -u)" = 0 ] || fail "must run as root: it starts slurmctld, slurmd and munged as root (SlurmUser=root)"
missing=
need() { command -v "$1" >/dev/null || missing="$missing $2 (for $1)"; }
need munged munge; need mungekey munge; need slurmctld slurmctld; need slurmd slurmd
need sbatch slurm-client; need sinfo slurm-client; need scontrol slurm-client; need scancel slurm-client
need squeue slurm-client; need parallel parallel; need python3 python3
[ -z "$missing" ] || fail "missing Debian packages:$missing (apt-get install slurm-wlm munge parallel; tools/deps.sh test)"

dir=$(mktemp -d /tmp/occu-view-cells-slurm.XXXXXX)
chmod 755 "$dir"   # munged wants the directories above its socket open to all
mkdir -m 755 "$dir/munge" "$dir/state" "$dir/spool" "$dir/out"
ctld_pid= slurmd_pid= munged_pid=

logs() {
    for f in "$dir"/munge/munged.log "$dir"/slurmctld.log "$dir"/slurmd.log "$dir"/slurmctld.out "$dir"/slurmd.out; do
        [ -s "$f" ] && { echo "--- $f"; tail -n 15 "$f"; }
    done
    return 0
}
alive() { [ -n "$1" ] && kill -0 "$1" 2>/dev/null; }
# Stops what this test started, by process id; says so when one does not stop.
stop() {
    local left=
    if alive "$ctld_pid"; then
        scancel --quiet --user=root 2>/dev/null || true
        timeout 10 scontrol shutdown >/dev/null 2>&1 || true
    fi
    for pid in $ctld_pid $slurmd_pid; do
        for _ in $(seq 50); do alive "$pid" || break; sleep 0.2; done
        alive "$pid" && { kill -TERM "$pid"; sleep 1; }
        alive "$pid" && { kill -KILL "$pid"; left="$left $pid"; }
    done
    if alive "$munged_pid"; then
        munged --socket="$dir/munge/munge.sock" --stop >/dev/null 2>&1 || kill -TERM "$munged_pid"
        for _ in $(seq 25); do alive "$munged_pid" || break; sleep 0.2; done
        alive "$munged_pid" && { kill -KILL "$munged_pid"; left="$left $munged_pid"; }
    fi
    ctld_pid= slurmd_pid= munged_pid=
    [ -z "$left" ] || { echo "FAIL: had to kill -KILL$left"; return 1; }
}
trap 'status=$?; stop || status=1; [ $status = 0 ] || logs; rm -rf "$dir"; exit $status' EXIT

# munge: its own key, socket, pid, log and seed files. munged forks and
# returns once its socket is up (or fails, saying why).
mungekey --create --keyfile="$dir/munge/munge.key" || fail "mungekey could not make a key"
munged --socket="$dir/munge/munge.sock" --key-file="$dir/munge/munge.key" --pid-file="$dir/munge/munged.pid" \
       --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" || fail "munged did not start"
munged_pid=$(cat "$dir/munge/munged.pid")
munge --socket="$dir/munge/munge.sock" --no-input | unmunge --socket="$dir/munge/munge.sock" >/dev/null ||
    fail "munge cannot encode and decode a credential on its socket"

# Two free ports for slurmctld and slurmd (other clusters may run here).
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
cat > "$dir/slurm.conf" <<EOF
ClusterName=occutest
SlurmctldHost=localhost
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.sock
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
JobCompType=jobcomp/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=256 State=UNKNOWN
PartitionName=occu Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
# The commands (sbatch, sinfo, ...) and the jobs read this configuration.
export SLURM_CONF=$dir/slurm.conf

slurmctld -D -i -f "$SLURM_CONF" >"$dir/slurmctld.out" 2>&1 &
ctld_pid=$!
for _ in $(seq 100); do
    alive "$ctld_pid" || fail "slurmctld exited at start"
    timeout 5 scontrol ping 2>/dev/null | grep -q UP && break
    sleep 0.3
done
timeout 5 scontrol ping 2>/dev/null | grep -q UP || fail "slurmctld did not answer within 30 s"
slurmd -D -N localhost -f "$SLURM_CONF" >"$dir/slurmd.out" 2>&1 &
slurmd_pid=$!
state=
for _ in $(seq 100); do
    alive "$slurmd_pid" || fail "slurmd exited at start"
    state=$(timeout 5 sinfo --noheader --node=localhost --format=%T 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.3
done
[ "$state" = idle ] || fail "the node is not idle within 30 s (sinfo says '$state')"
echo "cluster up: slurmctld (pid $ctld_pid, port $ctld_port), slurmd (pid $slurmd_pid, port $slurmd_port), munged (pid $munged_pid)"

now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
opts=(--cells 0-159 --leaf-triangles 1024 --pixel 4 --epsilon 3)
t=$(now)
"$bin" view-cells "${opts[@]}" --out "$dir/out/whole.pvs" >"$dir/whole.log" 2>&1 || { cat "$dir/whole.log"; fail "one process"; }
whole_s=$(since "$t")
[ "$(grep -c '^pvs ' "$dir/out/whole.pvs")" -eq 160 ] || fail "the one-process database has not 160 sets"

t=$(now)
OCCU_PREPROCESS=$bin timeout 180 "$submit" --wait 4 "$dir/out/slurm.pvs" "${opts[@]}" >"$dir/slurm.log" 2>&1 ||
    { cat "$dir/slurm.log"; fail "the Slurm run"; }
slurm_s=$(since "$t")
cat "$dir/slurm.log"
# Slurm's own record (whole seconds): the first shard's start to the merge's end.
array_job=$(sed -n 's/^array job \([0-9]*\):.*/\1/p' "$dir/slurm.log")
merge_job=$(sed -n 's/^merge job \([0-9]*\):.*/\1/p' "$dir/slurm.log")
epoch() { date -d "$1" +%s; }
first_start=
for f in $(scontrol --oneliner show job "$array_job" | sed -n 's/.* StartTime=\([^ ]*\) .*/\1/p'); do
    s=$(epoch "$f")
    [ -z "$first_start" ] || [ "$s" -lt "$first_start" ] && first_start=$s
done
merge_end=$(epoch "$(scontrol --oneliner show job "$merge_job" | sed -n 's/.* EndTime=\([^ ]*\) .*/\1/p')")
inside_s=$((merge_end - first_start))
cmp "$dir/out/whole.pvs" "$dir/out/slurm.pvs" || fail "the Slurm run's merged database differs from the one-process one"
for i in 1 2 3 4; do
    grep -q "^shard $i/4 on .* (job [0-9]*_$i)" "$dir/out/slurm.pvs.shards/shard-$i.log" ||
        fail "shard $i/4 did not run as task $i of the job array"
done
grep -q "visible sets of 160 of .* from 4 shards" "$dir/out/slurm.pvs.shards/merge.log" || fail "no merge job log"

t=$(now)
OCCU_PREPROCESS=$bin "$par" 4 "$dir/out/parallel.pvs" "${opts[@]}" >"$dir/parallel.log" 2>&1 ||
    { cat "$dir/parallel.log"; fail "the GNU parallel run"; }
parallel_s=$(since "$t")
cmp "$dir/out/whole.pvs" "$dir/out/parallel.pvs" || fail "the GNU parallel run's merged database differs from the one-process one"

# A failing shard (a bad option) cancels the merge job: no database, a failure named.
if OCCU_PREPROCESS=$bin timeout 120 "$submit" --wait 2 "$dir/out/bad.pvs" --cells 0-3 --epsilon nan >"$dir/bad.log" 2>&1; then
    fail "the Slurm run succeeded with a failing shard"
fi
[ ! -e "$dir/out/bad.pvs" ] || fail "a database was made although its shards failed"
grep -q -- "--epsilon wants a number" "$dir/bad.log" || { cat "$dir/bad.log"; fail "the shard's error is not shown"; }
echo "a failing shard: $(tail -n 1 "$dir/bad.log")"
[ -z "$(squeue --noheader)" ] || { squeue; fail "jobs left in the queue"; }

stop || fail "a daemon did not stop"
echo "4 shards through sbatch (job array + afterok merge) and under GNU parallel equal the one-process database byte for byte"
echo "wall time, whole processes: one process ${whole_s} s; Slurm, 4 shards and the merge ${slurm_s} s (waits by squeue each second; from the first shard's start to the merge's end ${inside_s} s by Slurm's record); GNU parallel, 4 shards and the merge ${parallel_s} s"
