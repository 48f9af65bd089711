#!/usr/bin/env bash
# The occluder database's density against preprocessing time and culling
# (Poon and Wang, section 3: grid points over the scene, representative view
# directions at each): mos-om against vfc on the dense and medium routes,
# llvmpipe 512x512, one run per database with both strategies side by side.
# Databases are preprocessed once into build/bench-grid/ (named by the
# grid and by tools/lib.sh's occluder_db_key), with their preprocessing log.
# Usage: bench/grid.sh [FRAMES] [NX,NY,NZ/HEADINGS ...]
#        (default: 8,1,8/8 15,1,15/8 8,1,8/16)     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"
frames=${1:-30}
shift || true
configs=("$@")
[ ${#configs[@]} -gt 0 ] || configs=(8,1,8/8 15,1,15/8 8,1,8/16)
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$OCCU_ROOT/build/bench-grid
mkdir -p "$out"
key=$(occluder_db_key)

echo "## Occluder database density ($frames frames, 64 occluders): mos-om mean ms (speed-up over vfc), efficiency"
echo
echo "| grid points | headings | views | preprocessing s | dense | medium |"
echo "|---|---|---|---|---|---|"
for c in "${configs[@]}"; do
    grid=${c%/*}
    dirs=${c#*/}
    db=$out/city-${grid//,/x}-h$dirs-$key.db
    if [ ! -s "$db" ]; then
        "$OCCU_ROOT/build/demos/occu-preprocess" build --out "$db" --grid "$grid" --directions "$dirs" \
            --max-occluders 512 > "$db.log" 2>/dev/null
    fi
    line=$(grep "views in" "$db.log")
    views=$(sed -E 's/.*: ([0-9]+) views in.*/\1/' <<<"$line")
    seconds=$(sed -E 's/.* views in ([0-9.]+) s.*/\1/' <<<"$line")
    row="| ${grid//,/x} | $dirs | $views | $seconds |"
    for route in dense medium; do
        cell=$("$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
                   --occluder-db "$db" --strategies vfc,mos-om --out "$out/run" |
               awk '$1 == "vfc" { vfc = $2 } $1 == "mos-om" { ms = $2; eff = $7 }
                    END { printf "%.2f (%.2fx) %s", ms, vfc / ms, eff }')
        row="$row $cell |"
    done
    echo "$row"
done
