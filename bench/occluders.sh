#!/usr/bin/env bash
# Occluder selection and culling method comparisons of Poon and Wang
# (figures 6, 8 and 9) on occu's city, llvmpipe, 512x512, in one run each:
#   1. PS, FH and MOS with 16..512 occluders on the dense route: culling
#      efficiency (occluded leaves culled) and frame time;
#   2. none, vfc, mos-om (OM + SDM) and pc-mos (pixel-wise) on three routes.
# The MOS database is preprocessed once into build/ (occu-preprocess).
# Usage: bench/occluders.sh [FRAMES]
# Prints markdown tables; writes build/bench-occluders/{selection,methods}.csv
# and, with gnuplot, selection.png (the paper's figure 6: culling and time
# against the number of occluders) and methods.png (figure 8).
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"

frames=${1:-30}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$OCCU_ROOT/build/bench-occluders
mkdir -p "$out"
db=$out/city.db
[ -s "$db" ] || "$OCCU_ROOT/build/demos/occu-preprocess" build --out "$db" --max-occluders 512
walk() { "$OCCU_ROOT/build/demos/walkthrough" --frames "$frames" --png-every 0 --occluder-db "$db" "$@"; }

echo "## Occluder selection, dense route ($frames frames): efficiency % / mean ms"
echo
echo "| occluders | om-ps | om-fh | mos-om |"
echo "|---|---|---|---|"
echo "occluders,strategy,mean_ms,efficiency_percent,triangles" > "$out/selection.csv"
for n in 16 32 64 128 256 512; do
    walk --route dense --occluders "$n" --strategies om-ps,om-fh,mos-om --out "$out/n$n" |
        awk -v n="$n" -v csv="$out/selection.csv" '$1 ~ /^(om-ps|om-fh|mos-om)$/ {
                           r[$1] = sprintf("%s / %.2f", $7, $2); e = $7; sub("%", "", e)
                           printf "%s,%s,%s,%s,%s\n", n, $1, $2, e, $4 >> csv }
                       END {printf "| %s | %s | %s | %s |\n", n, r["om-ps"], r["om-fh"], r["mos-om"]}'
done
echo
echo "## Culling methods by route (64 occluders): mean ms (speed-up vs vfc)"
echo
echo "| route | none | vfc | mos-om (OM+SDM) | pc-mos (PC) | OM+SDM vs PC |"
echo "|---|---|---|---|---|---|"
echo "route,none_ms,vfc_ms,mos_om_ms,pc_mos_ms" > "$out/methods.csv"
for route in dense medium open; do
    walk --route "$route" --strategies none,vfc,mos-om,pc-mos --out "$out/$route" |
        awk -v route="$route" -v csv="$out/methods.csv" '$1 ~ /^(none|vfc|mos-om|pc-mos)$/ {ms[$1] = $2; x[$1] = $6}
            END {printf "| %s | %.2f | %.2f | %.2f (%s) | %.2f (%s) | %.2fx |\n", route, ms["none"], ms["vfc"],
                 ms["mos-om"], x["mos-om"], ms["pc-mos"], x["pc-mos"], ms["pc-mos"] / ms["mos-om"]
                 printf "%s,%s,%s,%s,%s\n", route, ms["none"], ms["vfc"], ms["mos-om"], ms["pc-mos"] >> csv}'
done

if command -v gnuplot >/dev/null; then
    for s in om-ps om-fh mos-om; do   # one file per line: gnuplot joins points of one file
        awk -F, -v s="$s" 'NR == 1 || $2 == s' "$out/selection.csv" > "$out/selection-$s.csv"
    done
    gnuplot <<GNUPLOT
set datafile separator ","
set datafile columnheaders
set terminal pngcairo size 1000,420 font ",10"
set output "$out/selection.png"
set multiplot layout 1,2 title "Occluder selection, dense route (Poon and Wang, figure 6)"
set logscale x 2
set xlabel "occluders"
set key bottom right
set ylabel "culling efficiency (%)"
plot for [s in "om-ps om-fh mos-om"] "$out/selection-".s.".csv" using 1:4 with linespoints title s
set key top left
set ylabel "mean frame time (ms)"
plot for [s in "om-ps om-fh mos-om"] "$out/selection-".s.".csv" using 1:3 with linespoints title s
unset multiplot
set output "$out/methods.png"
unset logscale x
set title "Culling methods by route (Poon and Wang, figure 8)"
set style data histograms
set style histogram clustered
set style fill solid 0.8
set yrange [0:*]
set ylabel "mean frame time (ms)"
set xlabel ""
set key top left
plot "$out/methods.csv" using 2:xtic(1) title "none", "" using 3 title "vfc", "" using 4 title "mos-om (OM+SDM)", "" using 5 title "pc-mos (PC)"
GNUPLOT
    echo
    echo "plots: $out/selection.png, $out/methods.png; data: $out/selection.csv, $out/methods.csv"
fi
