#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The occluder database's density against preprocessing time and culling
# (Poon and Wang, section 3: grid points over the scene, representative view
# directions at each): om-mos against vfc and the floor on the dense and
# medium routes, llvmpipe 512x512, one run per database with the strategies
# side by side. Databases are preprocessed once into build/occluders/
# (occu-preprocess build --cache) with their preprocessing log.
# Usage: bench/grid.sh [FRAMES] [NX,NY,NZ/HEADINGS ...]
#        (default: 8,1,8/8 15,1,15/8 8,1,8/16)     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
frames=${1:-30}
shift || true
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(8,1,8/8 15,1,15/8 8,1,8/16)
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$OCCU_ROOT/build/bench-grid
mkdir -p "$out"

echo "## Occluder database density ($frames frames, 64 occluders): om-mos mean ms (x vfc, x the floor), efficiency"
echo
echo "| grid points | headings | views | preprocessing s | dense | medium |"
echo "|---|---|---|---|---|---|"
for c in "${configs[@]}"; do
    grid=${c%/*}
    dirs=${c#*/}
    log=$out/${grid//,/x}-h$dirs.log
    db=$(occluder_db --grid "$grid" --directions "$dirs" --max-occluders 512 2>"$log")
    # The preprocessing time, from this run's log or the one that made the database.
    if grep -q "views in" "$log"; then cp "$log" "$db.log"; fi
    line=$(grep "views in" "$db.log")
    views=$(sed -E 's/.*: ([0-9]+) views in.*/\1/' <<<"$line")
    seconds=$(sed -E 's/.* views in ([0-9.]+) s.*/\1/' <<<"$line")
    row="| ${grid//,/x} | $dirs | $views | $seconds |"
    for route in dense medium; do
        "$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
            --occluder-db "$db" --strategies vfc,ideal,om-mos --out "$out/run" >/dev/null
        s=$out/run/summary.csv
        row+=" $(field "$s" om-mos mean_ms) ($(field "$s" om-mos vs_vfc)x, $(field "$s" om-mos x_floor)x) $(field "$s" om-mos efficiency_percent)% |"
    done
    echo "$row"
done
