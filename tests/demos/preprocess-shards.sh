#!/bin/sh
# occu-preprocess: a database built in two shards and merged is byte for byte
# the database built whole (views are independent and the output is
# deterministic), and merging refuses a shard twice.
# Usage: preprocess-shards.sh OCCU-PREPROCESS
set -eu
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
opts="--grid 2,1,2 --directions 2 --leaf-triangles 512"
"$bin" build $opts --out "$dir/whole.db" >/dev/null
"$bin" build $opts --shard 1/2 --out "$dir/s1.db" >/dev/null
"$bin" build $opts --shard 2/2 --out "$dir/s2.db" >/dev/null
"$bin" merge --out "$dir/merged.db" "$dir/s2.db" "$dir/s1.db" >/dev/null
cmp "$dir/whole.db" "$dir/merged.db"
if "$bin" merge --out "$dir/twice.db" "$dir/s1.db" "$dir/s1.db" 2>/dev/null; then
    echo "merge accepted the same shard twice"
    exit 1
fi
# Not empty: the views hold occluders.
grep -q '^view [0-9]* [0-9]' "$dir/whole.db"
echo "shards merge to the whole database"
