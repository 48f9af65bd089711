#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-raycast refuses bad input with a message naming it and a failing
# exit status, never a crash (no signal) and never a silent success; a good
# run casts through the lists of several brick sizes, finds every lists
# image equal to casting every pixel, and writes its table and images.
# Usage: raycast.sh OCCU-RAYCAST
set -u
raycast=$1
. "$(dirname "$0")/expect-error.sh"

out="$dir/out-dir"
expect_error "--brick" "$raycast" --frames 1 --brick 0 --out "$out"
expect_error "--brick" "$raycast" --frames 1 --brick 4,,8 --out "$out"
expect_error "--brick" "$raycast" --frames 1 --brick 4,x --out "$out"
expect_error "--step" "$raycast" --frames 1 --step nan --out "$out"
expect_error "--step" "$raycast" --frames 1 --step 0 --out "$out"
expect_error "--list-layers" "$raycast" --frames 1 --list-layers 0 --out "$out"
expect_error "--block" "$raycast" --frames 1 --block 3 --out "$out"
expect_error "--block" "$raycast" --frames 1 --block 9,1 --out "$out"
expect_error "--frames" "$raycast" --frames 0 --out "$out"
expect_error "softpipe" "$raycast" --frames 1 --driver voodoo --out "$out"
expect_error "--nonsense" "$raycast" --nonsense 1

# A good run on the open route, where the plume shows over the rooftops.
if "$raycast" --route open --frames 3 --size 128 --brick 4,16 --png-every 2 --out "$out" >"$dir/good" 2>&1 &&
    grep -q '^lists, 4^3-cell bricks: 0 pixels differ from casting every pixel, 0 pixels' "$dir/good" &&
    grep -q '^lists, 16^3-cell bricks: 0 pixels differ' "$dir/good" &&
    grep -q '^floor (rays that gain)' "$dir/good" &&
    [ "$(wc -l < "$out/frames.csv")" -eq $((1 + 3 * 5)) ] &&
    [ -s "$out/raycast-0000.png" ] && [ -s "$out/lists-0002.png" ]; then
    echo "ok: a good run"
else
    echo "FAIL: a good run"
    sed 's/^/    /' "$dir/good"
    failures=$((failures + 1))
fi

echo "$failures failures"
[ $failures -eq 0 ]
