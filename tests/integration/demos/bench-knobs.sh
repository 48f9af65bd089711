#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-bench-knobs: a short run (om-ps on 3 frames of the dense route, its
# tolerance at 0 and 16) writes knobs.csv with a row per value and route
# (and the means, route "all"), the exact value (tolerance=0) with 0 wrong
# pixels, the table and a plot; bad options are refused with a message
# naming them; a sweep of an approximation without its exact value exits 1
# naming the knob.
# Usage: bench-knobs.sh OCCU-BENCH-KNOBS
set -u
bench=$1
. "$(dirname "$0")/expect-error.sh"
out="$dir/out-dir"

expect_error "--frames" "$bench" --frames 0 --out "$out"
expect_error "--knob" "$bench" --knob tolerance --out "$out"
expect_error "no-such-knob" "$bench" --strategies om-ps --knob no-such-knob=1 --out "$out"
expect_error "tolerance" "$bench" --strategies om-ps --knob tolerance=-1 --out "$out"
expect_error "--knob leaf-triangles wants auto or an integer" "$bench" --strategies om-ps --knob leaf-triangles=big --out "$out"
expect_error "nope" "$bench" --strategies nope --out "$out"
expect_error "vfc has no approximation or cost setting" "$bench" --strategies vfc --out "$out"
expect_error "--make-databases" "$bench" --strategies om-ps --make-databases some --out "$out"
expect_error "--bogus" "$bench" --bogus 1
expect_error "nowhere" "$bench" --routes nowhere --strategies om-ps --knob tolerance=0 --out "$out"
# An approximation knob swept without its exact value never reaches 0 wrong pixels: said loudly, exit 1.
expect_error "VIOLATION: om-ps tolerance" "$bench" --routes dense --frames 2 --strategies om-ps --knob tolerance=64 \
    --plots off --out "$out"

if ! "$bench" --routes dense --frames 3 --strategies om-ps --knob tolerance=0,16 --out "$out" >"$dir/log" 2>&1; then
    echo "FAIL: the short run failed"
    cat "$dir/log"
    exit 1
fi
csv="$out/knobs.csv"
rows=$(grep -c '^om-ps,tolerance,' "$csv")
[ "$rows" -eq 4 ] || { echo "FAIL: $rows om-ps tolerance rows in $csv, not 4 (2 values x dense, all)"; failures=$((failures + 1)); }
# The exact value: 0 wrong pixels per frame, on the route and over all.
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
         $1 == "om-ps" && $2 == "tolerance" && $3 == "0" { n++; if ($c["wrong_pixels_per_frame"] + 0 != 0 ||
             $c["wrong_pixels_max_route_total"] != 0) bad = 1 }
         END { exit !(n == 2 && !bad) }' "$csv" ||
    { echo "FAIL: om-ps tolerance=0 has wrong pixels (or no rows) in $csv"; failures=$((failures + 1)); }
grep -q '^| om-ps | tolerance=0 |' "$dir/log" || { echo "FAIL: no table row for om-ps"; cat "$dir/log"; failures=$((failures + 1)); }
if command -v gnuplot >/dev/null; then
    [ -s "$out/om-ps.png" ] || { echo "FAIL: no $out/om-ps.png"; failures=$((failures + 1)); }
fi
[ $failures -eq 0 ] && echo "ok: knobs.csv, the exact value at 0 wrong pixels, the table and the plot"
exit $((failures != 0))
