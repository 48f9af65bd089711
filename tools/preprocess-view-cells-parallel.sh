#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The shards of tools/slurm/preprocess-view-cells.sh under GNU parallel on
# this machine (or, with parallel's own --sshlogin options in PARALLEL, on
# others): N runs of occu-preprocess view-cells OPTIONS --shard I/N, JOBS at
# a time (default: one per core), then occu-preprocess merge of the N shards
# into OUT. The shards and parallel's job log go to OUT.shards/ (shard-I.pvs,
# joblog). The first shard to fail stops the others and the merge. OPTIONS
# are view-cells' own (not --shard or --out); the merged database is byte for
# byte the one a single `occu-preprocess view-cells OPTIONS --out OUT` makes.
# OCCU_PREPROCESS names the program (default: build/demos/occu-preprocess).
# Usage: tools/preprocess-view-cells-parallel.sh [-j JOBS] N OUT [OPTIONS...]
set -euo pipefail

me=preprocess-view-cells-parallel.sh
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
die() { printf '%s: %s\n' "$me" "$*" >&2; exit 1; }
usage="usage: tools/$me [-j JOBS] N OUT [VIEW-CELLS OPTION...]"

jobs=
if [ "${1:-}" = -j ]; then
    [ $# -ge 2 ] || die "$usage"
    jobs=$2
    shift 2
    [[ $jobs =~ ^[1-9][0-9]*$ ]] || die "-j takes a whole number of jobs at a time, not '$jobs'"
fi
case ${1:-} in -h|--help) echo "$usage"; exit 0 ;; esac
[ $# -ge 2 ] || die "$usage"
n=$1 out=$2
shift 2
[[ $n =~ ^[1-9][0-9]*$ ]] || die "N must be a whole number of shards, 1 or more, not '$n'"
for a in "$@"; do
    case $a in
        --shard|--shard=*|--out|--out=*) die "do not give $a: this sets --shard I/$n and --out per shard" ;;
    esac
done
command -v parallel >/dev/null || die "GNU parallel is not installed (Debian: apt-get install parallel)"
parallel --version 2>/dev/null | grep -q 'GNU parallel' ||
    die "'$(command -v parallel)' is not GNU parallel (moreutils has another; Debian: apt-get install parallel)"
bin=${OCCU_PREPROCESS:-$here/../build/demos/occu-preprocess}
[ -x "$bin" ] || die "no occu-preprocess at '$bin' (build it, or set OCCU_PREPROCESS)"

dir=$out.shards
mkdir -p "$dir"
rm -f "$out" "$dir"/shard-*.pvs "$dir"/joblog
# -q: each OPTION stays one argument (no shell splitting); {} is the shard.
parallel --will-cite -q ${jobs:+-j "$jobs"} --halt now,fail=1 --joblog "$dir/joblog" --tagstring "shard {}/$n" \
    "$bin" view-cells "$@" --shard "{}/$n" --out "$dir/shard-{}.pvs" ::: $(seq 1 "$n") ||
    die "a shard failed (parallel's job log: $dir/joblog)"
shards=()
for ((i = 1; i <= n; ++i)); do shards+=("$dir/shard-$i.pvs"); done
"$bin" merge --out "$out" "${shards[@]}"
