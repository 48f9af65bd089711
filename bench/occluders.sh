#!/usr/bin/env bash
# Occluder selection and culling method comparisons of Poon and Wang
# (figures 6, 8 and 9) on occu's city, llvmpipe, 512x512, in one run each:
#   1. PS, FH and MOS with 16..512 occluders on the dense route: culling
#      efficiency (occluded leaves culled) and frame time;
#   2. none, vfc, mos-om (OM + SDM) and pc-mos (pixel-wise) on three routes.
# The MOS database is preprocessed once into build/ (occu-preprocess).
# Usage: bench/occluders.sh [FRAMES]   (CSV and tables in build/bench-occluders/)
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"

frames=${1:-30}
"$OCCU_ROOT/tools/build.sh" >/dev/null
out=$OCCU_ROOT/build/bench-occluders
mkdir -p "$out"
db=$out/city.db
[ -s "$db" ] || "$OCCU_ROOT/build/demos/occu-preprocess" build --out "$db" --max-occluders 512
walk() { "$OCCU_ROOT/build/demos/walkthrough" --frames "$frames" --png-every 0 --occluder-db "$db" "$@"; }

echo "## Occluder selection, dense route ($frames frames): efficiency % / mean ms"
echo
echo "| occluders | om-ps | om-fh | mos-om |"
echo "|---|---|---|---|"
for n in 16 32 64 128 256 512; do
    walk --route dense --occluders "$n" --strategies om-ps,om-fh,mos-om --out "$out/n$n" |
        awk -v n="$n" '$1 ~ /^(om-ps|om-fh|mos-om)$/ {r[$1] = sprintf("%s / %.2f", $7, $2)}
                       END {printf "| %s | %s | %s | %s |\n", n, r["om-ps"], r["om-fh"], r["mos-om"]}'
done
echo
echo "## Culling methods by route (64 occluders): mean ms (speed-up vs vfc)"
echo
echo "| route | none | vfc | mos-om (OM+SDM) | pc-mos (PC) | OM+SDM vs PC |"
echo "|---|---|---|---|---|---|"
for route in dense medium open; do
    walk --route "$route" --strategies none,vfc,mos-om,pc-mos --out "$out/$route" |
        awk -v route="$route" '$1 ~ /^(none|vfc|mos-om|pc-mos)$/ {ms[$1] = $2; x[$1] = $6}
            END {printf "| %s | %.2f | %.2f | %.2f (%s) | %.2f (%s) | %.2fx |\n", route, ms["none"], ms["vfc"],
                 ms["mos-om"], x["mos-om"], ms["pc-mos"], x["pc-mos"], ms["pc-mos"] / ms["mos-om"]}'
done
