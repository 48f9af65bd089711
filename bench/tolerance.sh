#!/usr/bin/env bash
# The approximate overlap test (Poon and Wang, section 5.2): a box counts as
# covered when at most `tolerance` of its opacity-map pixels are holes. What
# each tolerance costs in wrong pixels and saves in time, on one route,
# beside vfc and the floor in the same run.
# Usage: bench/tolerance.sh [ROUTE] [FRAMES]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
route=${1:-dense}
frames=${2:-30}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
tolerances=(0 1 2 4 8 16 32 64)
strategies=vfc,ideal
for t in "${tolerances[@]}"; do strategies+=",om-ps:tolerance=$t"; done
"$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
    --strategies "$strategies" --out "$out" >/dev/null
s=$out/summary.csv
echo "## Approximate overlap test on the $route route (om-ps, 64 occluders, 128x128 maps, llvmpipe, 512x512, $frames frames, one run)"
echo
echo "vfc $(field "$s" vfc mean_ms) ms, ideal (the floor) $(field "$s" ideal mean_ms) ms."
echo
echo "| tolerance (map pixels) | mean ms | x vfc | x floor | triangles | culling efficiency | visible leaves culled | wrong pixels per frame |"
echo "|---|---|---|---|---|---|---|---|"
for t in "${tolerances[@]}"; do
    n="om-ps:tolerance=$t"
    w=$(field "$s" "$n" wrong_pixels_per_frame); [ "$w" = "-" ] && w="0 (conservative)"
    echo "| $t | $(field "$s" "$n" mean_ms) | $(field "$s" "$n" vs_vfc) | $(field "$s" "$n" x_floor) |" \
         "$(field "$s" "$n" triangles) | $(field "$s" "$n" efficiency_percent)% |" \
         "$(field "$s" "$n" visible_leaves_culled) | $w |"
done
