#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-collide refuses bad input with a message naming it and a failing
# exit status, never a crash (no signal) and never a silent success; and
# a good run prints its confusion tables and writes its files.
# Usage: collide-bad-input.sh OCCU-COLLIDE
set -u
collide=$1
. "$(dirname "$0")/expect-error.sh"

printf '0 1.7 0 10 1.7 0\n0 1.7 0 nan 1.7 0\n' > "$dir/nan.route"
out="$dir/out-dir"

# The city's street-level cameras have their near plane at 0.5 m: a step
# must reach beyond it.
expect_error "--step" "$collide" --frames 1 --step 0.3 --out "$out"
expect_error "--step" "$collide" --frames 1 --step 0.5 --out "$out"
expect_error "--step" "$collide" --frames 1 --step 0 --out "$out"
expect_error "--step" "$collide" --frames 1 --step -2 --out "$out"
expect_error "--step" "$collide" --frames 1 --step nan --out "$out"
expect_error "--step" "$collide" --frames 1 --step inf --out "$out"
expect_error "--step" "$collide" --frames 1 --step 2m --out "$out"
expect_error "--step" "$collide" --frames 1 --step 100000 --out "$out"
expect_error "--direction" "$collide" --frames 1 --direction sideways --out "$out"
expect_error "--frames" "$collide" --frames 0 --out "$out"
expect_error "--size" "$collide" --frames 1 --size 2 --out "$out"
expect_error "--png-every" "$collide" --frames 1 --png-every -1 --out "$out"
expect_error "random:N:SEED" "$collide" --route random:0:1 --out "$out"
expect_error "nan.route:2: tx is 'nan'" "$collide" --route "$dir/nan.route" --out "$out"
expect_error "no-such-scene.obj" "$collide" --frames 1 --scene "$dir/no-such-scene.obj" --out "$out"
expect_error "softpipe" "$collide" --frames 1 --driver voodoo --out "$out"
expect_error "--nonsense" "$collide" --nonsense 1
expect_error "--step" "$collide" --step

# A good run: both directions, tables, steps.csv and tinted frames.
if "$collide" --frames 3 --step 2 --direction both --size 96 --png-every 2 --out "$out" >"$dir/good" 2>&1 &&
    grep -q '^forward steps: 3' "$dir/good" && grep -q '^backward steps: 3' "$dir/good" &&
    grep -q '^all tiles' "$dir/good" && [ "$(wc -l < "$out/steps.csv")" -eq $((1 + 3 * 2 * 9)) ] &&
    [ -s "$out/forward-0000.png" ] && [ -s "$out/backward-0002.png" ]; then
    echo "ok: a good run"
else
    echo "FAIL: a good run"
    sed 's/^/    /' "$dir/good"
    failures=$((failures + 1))
fi

echo "$failures failures"
[ $failures -eq 0 ]
