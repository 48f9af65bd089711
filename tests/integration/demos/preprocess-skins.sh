#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-preprocess skins (Leone et al., section 4): skins made in two shards
# and merged are byte for byte the skins made whole; merge refuses a shard
# twice and shards of other options; a walkthrough takes the database and
# refuses one made for another scene, naming the file.
# Usage: preprocess-skins.sh OCCU-PREPROCESS WALKTHROUGH
set -eu
bin=$1
walkthrough=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
opts="--voxel-size 1"
"$bin" skins $opts --out "$dir/whole.txt" >"$dir/whole.log" 2>&1
# The summary counts meshes without skins by reason and how far meshes
# spread: the city's ground (1 m thick, no interior at 1 m voxels) spans it.
grep -q '^  without skins: 1: no interior' "$dir/whole.log" || { echo "no count of meshes without skins:"; cat "$dir/whole.log"; exit 1; }
grep -q 'largest 100%; 1 of [0-9]* meshes over half$' "$dir/whole.log" || { echo "no spread of the meshes:"; cat "$dir/whole.log"; exit 1; }
"$bin" skins $opts --shard 1/2 --out "$dir/s1.txt" >/dev/null 2>&1
"$bin" skins $opts --shard 2/2 --out "$dir/s2.txt" >/dev/null 2>&1
"$bin" merge --out "$dir/merged.txt" "$dir/s2.txt" "$dir/s1.txt" >/dev/null 2>&1
cmp "$dir/whole.txt" "$dir/merged.txt"
grep -q '^skins [0-9]* 1 ' "$dir/whole.txt" || { echo "no mesh got a skin"; exit 1; }
if "$bin" merge --out "$dir/twice.txt" "$dir/s1.txt" "$dir/s1.txt" 2>/dev/null; then
    echo "merge accepted the same shard twice"
    exit 1
fi
"$bin" skins --voxel-size 2 --shard 2/2 --out "$dir/other.txt" >/dev/null 2>&1
if "$bin" merge --out "$dir/mixed.txt" "$dir/s1.txt" "$dir/other.txt" 2>/dev/null; then
    echo "merge accepted shards made with other options"
    exit 1
fi
# The walkthrough culls with it, and refuses it for another scene.
"$walkthrough" --route dense --frames 2 --size 64 --png-every 0 --oracle off --strategies skins \
    --set skin-database="$dir/whole.txt" --out "$dir/walk" >/dev/null
if "$walkthrough" --city-copies 2 --route dense --frames 1 --size 64 --png-every 0 --oracle off --strategies skins \
       --set skin-database="$dir/whole.txt" --out "$dir/walk2" >/dev/null 2>"$dir/refused.log"; then
    echo "the walkthrough took skins made for another scene"
    exit 1
fi
grep -q "$dir/whole.txt" "$dir/refused.log" || { echo "the refusal does not name the file:"; cat "$dir/refused.log"; exit 1; }
echo "skin shards merge to the whole database; the walkthrough refuses skins of another scene"
