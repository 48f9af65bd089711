#!/usr/bin/env bash
# Adaptive occlusion culling (Bartz et al. 1998, section 5): what each
# tolerance (occluded when NOHC <= tolerance * PHC) costs in wrong pixels
# and saves in time, on one route, beside vfc and the floor in the same run.
# Usage: bench/adaptive.sh [ROUTE] [FRAMES]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
route=${1:-medium}
frames=${2:-30}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
tolerances=(0 0.01 0.02 0.05 0.1 0.2 0.3)
strategies=vfc,ideal
for t in "${tolerances[@]}"; do strategies+=",ou-shared:tolerance=$t"; done
"$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
    --strategies "$strategies" --out "$out" >/dev/null
s=$out/summary.csv
echo "## Adaptive culling on the $route route (ou-shared, llvmpipe, 512x512, $frames frames, one run)"
echo
echo "vfc $(field "$s" vfc mean_ms) ms, ideal (the floor) $(field "$s" ideal mean_ms) ms."
echo
echo "| tolerance (NOHC/PHC) | mean ms | x vfc | x floor | triangles | culling efficiency | wrong pixels per frame |"
echo "|---|---|---|---|---|---|---|"
for t in "${tolerances[@]}"; do
    n="ou-shared:tolerance=$t"
    w=$(field "$s" "$n" wrong_pixels_per_frame); [ "$w" = "-" ] && w="0 (conservative)"
    echo "| $t | $(field "$s" "$n" mean_ms) | $(field "$s" "$n" vs_vfc) | $(field "$s" "$n" x_floor) |" \
         "$(field "$s" "$n" triangles) | $(field "$s" "$n" efficiency_percent)% | $w |"
done
