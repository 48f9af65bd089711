#!/usr/bin/env bash
# The approximate overlap test (Poon and Wang, section 5.2): a box counts as
# covered when at most T of its opacity-map pixels are holes. What each
# tolerance costs in wrong pixels and saves in time, on one route.
# Usage: bench/tolerance.sh [route] [frames]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"
route=${1:-dense}
frames=${2:-30}
prefix=$("$OCCU_ROOT/tools/build.sh")
source "$prefix/occu/env.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "## Approximate overlap test on the $route route (om-ps, 64 occluders, 128x128 maps, llvmpipe, 512x512, $frames frames)"
echo
echo "| tolerance (map pixels) | mean ms | triangles | culling efficiency | visible leaves culled | wrong pixels per frame |"
echo "|---|---|---|---|---|---|"
for t in 0 1 2 4 8 16 32 64; do
    "$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --tolerance "$t" \
        --strategies om-ps --out "$out" --png-every 0 |
        awk -v t="$t" '$1 == "om-ps" { w = ($9 == "-") ? "0 (conservative)" : $9; printf "| %s | %s | %s | %s | %s | %s |\n", t, $2, $4, $7, $8, w }'
done
