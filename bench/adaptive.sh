#!/usr/bin/env bash
# Adaptive occlusion culling (Bartz et al. 1998, section 5): what each
# threshold costs in wrong pixels and saves in time, on one route.
# Usage: bench/adaptive.sh [route] [frames]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"
route=${1:-medium}
frames=${2:-30}
prefix=$("$OCCU_ROOT/tools/build.sh")
source "$prefix/occu/env.sh"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "## Adaptive culling on the $route route (occu-hier-shared, llvmpipe, 512x512, $frames frames)"
echo
echo "| threshold (NOHC/PHC) | mean ms | triangles | culling efficiency | wrong pixels per frame |"
echo "|---|---|---|---|---|"
for t in 0 0.01 0.02 0.05 0.1 0.2 0.3; do
    "$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --threshold "$t" \
        --strategies occu-hier-shared --out "$out" --png-every 0 |
        awk -v t="$t" '$1 == "occu-hier-shared" { w = ($9 == "-") ? "0 (conservative)" : $9; printf "| %s | %s | %s | %s | %s |\n", t, $2, $4, $7, w }'
done
