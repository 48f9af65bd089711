#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Preprocesses the view cells' potentially visible sets (occu-preprocess
# view-cells; Wonka, Wimmer and Schmalstieg 2000) on a Slurm cluster: a job
# array of N tasks, task I making shard I/N (the cells c with c % N == I - 1,
# view-cells-shard.sbatch), and a merge job that waits for every task to
# succeed (--dependency=afterok on the array job; cancelled when a task fails)
# and joins the shards into OUT (view-cells-merge.sbatch). The shards and the
# jobs' logs go to OUT.shards/ (shard-I.pvs, shard-I.log, merge.log). OPTIONS
# are view-cells' own (not --shard or --out, which this sets) and reach every
# task unchanged, so the merged database is byte for byte the one a single
# `occu-preprocess view-cells OPTIONS --out OUT` makes.
#
# Prints the array job's id and the merge job's. --wait blocks until both jobs
# end and fails unless the merge completed (showing the logs' ends);
# --sbatch ARG passes ARG to both sbatch calls (e.g. --sbatch --partition=big).
# OUT and OCCU-PREPROCESS must be on a file system every node sees; the
# environment of this shell (GALLIUM_DRIVER, ...) reaches the jobs (sbatch's
# default --export=ALL). OCCU_PREPROCESS names the program (default:
# build/demos/occu-preprocess of this tree).
# Usage: tools/slurm/preprocess-view-cells.sh [--wait] [--sbatch ARG]... N OUT [OPTIONS...]
set -euo pipefail

me=preprocess-view-cells.sh
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { printf '%s: %s\n' "$me" "$*" >&2; exit 1; }
usage="usage: tools/slurm/$me [--wait] [--sbatch ARG]... N OUT [VIEW-CELLS OPTION...]"

wait=0
sbatch_args=()
while [ $# -gt 0 ]; do
    case $1 in
        --wait) wait=1; shift ;;
        --sbatch) [ $# -ge 2 ] || die "--sbatch needs an argument; $usage"; sbatch_args+=("$2"); shift 2 ;;
        -h|--help) echo "$usage"; exit 0 ;;
        --) shift; break ;;
        -*) die "unknown option '$1'; $usage" ;;
        *) break ;;
    esac
done
[ $# -ge 2 ] || die "$usage"
n=$1 out=$2
shift 2
# Slurm's default MaxArraySize is 1001: task ids 0 .. 1000.
[[ $n =~ ^[1-9][0-9]*$ ]] && [ "$n" -le 1000 ] ||
    die "N must be a whole number of shards from 1 to 1000 (Slurm's default MaxArraySize is 1001), not '$n'"
for a in "$@"; do
    case $a in
        --shard|--shard=*|--out|--out=*) die "do not give $a: the job array sets --shard I/$n and --out per task" ;;
    esac
done

command -v sbatch >/dev/null ||
    die "sbatch is not on PATH: install Slurm's client commands (Debian: apt-get install slurm-client; slurm-wlm has the daemons too)"
bin=${OCCU_PREPROCESS:-$here/../../build/demos/occu-preprocess}
[ -x "$bin" ] || die "no occu-preprocess at '$bin' (build it, or set OCCU_PREPROCESS)"
bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
mkdir -p "$(dirname "$out")"
out=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
dir=$out.shards
mkdir -p "$dir"
rm -f "$out" "$dir"/shard-*.pvs "$dir"/shard-*.log "$dir"/merge.log

# --parsable prints "JOBID" or "JOBID;CLUSTER".
array=$(sbatch --parsable --array="1-$n" --output="$dir/shard-%a.log" "${sbatch_args[@]}" \
               "$here/view-cells-shard.sbatch" "$bin" "$n" "$dir" "$@")
array=${array%%;*}
echo "array job $array: $n shards into $dir/shard-I.pvs (logs $dir/shard-I.log)"
merge_args=(--parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes --output="$dir/merge.log"
            "${sbatch_args[@]}" "$here/view-cells-merge.sbatch" "$bin" "$n" "$dir" "$out")
merge=$(sbatch "${merge_args[@]}")
merge=${merge%%;*}
echo "merge job $merge: after every shard, into $out (log $dir/merge.log)"
[ $wait = 1 ] || exit 0

# Waits by asking squeue each second (sbatch --wait polls at up to 10 s and
# exits 0 for a job cancelled before it ran), then asks for the merge's end.
fails=0
while :; do
    if ! jobs=$(squeue --noheader --jobs="$array,$merge" --states=PD,CF,R,CG,S --format=%i 2>/dev/null); then
        fails=$((fails + 1))
        [ $fails -lt 30 ] || die "squeue failed 30 times in a row; jobs $array and $merge are left to Slurm"
    elif [ -z "$jobs" ]; then
        break
    else
        fails=0
    fi
    sleep 1
done
state=$(scontrol --oneliner show job "$merge" 2>/dev/null | sed -n 's/.* JobState=\([^ ]*\) .*/\1/p')
if [ "$state" != COMPLETED ] || [ ! -s "$out" ]; then
    # Each log's last lines, without occu-preprocess's usage text.
    for log in "$dir"/shard-*.log "$dir"/merge.log; do
        if [ -f "$log" ]; then
            echo "--- $log"
            awk '/^usage:/ { skip = 1; next } /^[^ ]/ { skip = 0 } !skip' "$log" | tail -n 5
        fi
    done >&2
    die "the merge job $merge did not make $out (its state: ${state:-unknown}; a failed shard cancels it)"
fi
echo "$out: merged from $n shards"
