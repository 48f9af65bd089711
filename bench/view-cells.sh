#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What the view-cell knobs (Wonka et al.: epsilon, the cull map's pixel,
# the longest cell edge) cost and save: for each setting, the PVS database
# of the cells a route's cameras are in (occu-preprocess view-cells --route),
# its time per cell, size and share of the scene occluded, then one
# walkthrough of the route with pvs on every database side by side, beside
# vfc and the floor (ideal).
# Usage: bench/view-cells.sh [ROUTE] [FRAMES] [COPIES] [EPSILON:PIXEL:MAX_EDGE ...]
#   bench/view-cells.sh dense 60 1 1:1:24 2:2:24 4:4:24 0.75:1:24 1:1:12 1:1:48
# Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
route=${1:-dense}
frames=${2:-60}
copies=${3:-1}
shift $(( $# < 3 ? $# : 3 ))
settings=("$@")
[ ${#settings[@]} -gt 0 ] || settings=(1:1:24 2:2:24 4:4:24 0.75:1:24 1:1:12 1:1:48)
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
strategies=vfc,ideal
rows=()
for s in "${settings[@]}"; do
    IFS=: read -r eps pixel edge <<<"$s"
    db=$out/pvs-$eps-$pixel-$edge.pvs
    log=$out/pvs-$eps-$pixel-$edge.log
    "$OCCU_ROOT/build/demos/occu-preprocess" view-cells --city-copies "$copies" --route "$route" --frames "$frames" \
        --epsilon "$eps" --pixel "$pixel" --max-edge "$edge" --out "$db" >"$log" 2>/dev/null
    # "FILE: N cells in S s; per cell V visible leaves of L, P% of the triangles occluded"
    cells=$(sed -n 's/.*: \([0-9]*\) cells in \([0-9.]*\) s;.*/\1/p' "$log")
    secs=$(sed -n 's/.*: \([0-9]*\) cells in \([0-9.]*\) s;.*/\2/p' "$log")
    occluded=$(sed -n 's/.*, \([0-9.]*\)% of the triangles occluded.*/\1/p' "$log")
    size=$(du -k "$db" | cut -f1)
    strategies+=",pvs:pvs-database=$db"
    rows+=("$eps|$pixel|$edge|$cells|$(awk -v s="$secs" -v n="$cells" 'BEGIN { printf "%.3f", n ? s / n : 0 }')|$size|$occluded|pvs:pvs-database=$db")
done
"$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --city-copies "$copies" --png-every 0 \
    --report off --strategies "$strategies" --out "$out/walk" >"$out/walk.log"
sum=$out/walk/summary.csv
echo "## view cells: knobs on the $route route ($copies x $copies copies of the city; llvmpipe, 512x512, $frames frames, one walkthrough run)"
echo
echo "vfc $(field "$sum" vfc mean_ms) ms, ideal (the floor) $(field "$sum" ideal mean_ms) ms."
echo
echo "| epsilon | pixel | max edge | cells on the route | s per cell | database KiB | % of the scene occluded (per cell) | pvs mean ms | x vfc | x floor |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for r in "${rows[@]}"; do
    IFS='|' read -r eps pixel edge cells per size occ label <<<"$r"
    echo "| $eps | $pixel | $edge | $cells | $per | $size | $occ | $(field "$sum" "$label" mean_ms) | $(field "$sum" "$label" vs_vfc) | $(field "$sum" "$label" x_floor) |"
done
echo
grep '^pvs' "$out/walk.log" | sed "s|$out/||g; s/^/    /"
