#!/bin/sh
# SPDX-License-Identifier: MIT
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
# A shard of another hierarchy does not merge.
"$bin" build --grid 2,1,2 --directions 2 --leaf-triangles 256 --shard 2/2 --out "$dir/other.db" >/dev/null
if "$bin" merge --out "$dir/mixed.db" "$dir/s1.db" "$dir/other.db" 2>/dev/null; then
    echo "merge accepted shards of two hierarchies"
    exit 1
fi
# --cache: the database is named by its key, made once, and its path printed.
first=$("$bin" build $opts --cache "$dir/cache" 2>/dev/null)
second=$("$bin" build $opts --cache "$dir/cache" 2>"$dir/second.log")
[ "$first" = "$second" ] && [ -s "$first" ] || { echo "--cache gave '$first' then '$second'"; exit 1; }
grep -q "up to date" "$dir/second.log" || { echo "--cache made the database again"; exit 1; }
cmp "$first" "$dir/whole.db"
other=$("$bin" build $opts --max-occluders 7 --cache "$dir/cache" 2>/dev/null)
[ "$other" != "$first" ] || { echo "--cache gave one name to databases of other options"; exit 1; }
echo "shards merge to the whole database; --cache names databases by what they depend on"
