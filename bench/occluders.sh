#!/usr/bin/env bash
# Occluder selection and culling method comparisons of Poon and Wang
# (figures 6, 9 and 8) on occu's city, llvmpipe, 512x512, in one run each:
#   1. figure 6: PS, FH and MOS with 1..128 occluders at viewpoints (the
#      database's own grid views, as the paper's "certain viewpoint"), on a
#      hierarchy of LEAF-triangle leaves (16: occluders near the paper's
#      primitives): culling efficiency and frame time, and how many
#      occluders each needs to reach its best efficiency;
#   2. figure 9: PS, FH and MOS with 64 occluders on the dense route;
#   3. figure 8: none, vfc, mos-om (OM + SDM) and pc-mos (pixel-wise) on
#      three routes, with the time spent building maps and testing.
# The MOS databases are preprocessed once into build/ (occu-preprocess),
# named by what they depend on (tools/lib.sh, occluder_db_key).
# Usage: bench/occluders.sh [FRAMES] [LEAF]
# Prints markdown tables; writes build/bench-occluders/{viewpoints,route,methods}.csv
# and, with gnuplot, viewpoints.png (figure 6: culling and time against the
# number of occluders) and methods.png (figure 8).
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"

frames=${1:-30}
leaf=${2:-16}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$OCCU_ROOT/build/bench-occluders
mkdir -p "$out"
preprocess() { "$OCCU_ROOT/build/demos/occu-preprocess" build --max-occluders 512 "$@" >&2; }
key=$(occluder_db_key)
db=$out/city-$key.db
[ -s "$db" ] || preprocess --out "$db"
fine_db=$out/city-leaf$leaf-$key.db
[ -s "$fine_db" ] || preprocess --out "$fine_db" --leaf-triangles "$leaf"
walk() { "$OCCU_ROOT/build/demos/walkthrough" --png-every 0 "$@"; }

# The viewpoints: every 6th view with occluders at the grid's inner points,
# each camera exactly as preprocessing placed it.
views=$out/viewpoints.route
"$OCCU_ROOT/build/demos/occu-preprocess" views --out "$views" --every 6 "$fine_db" >/dev/null
nviews=$(grep -c . "$views")

echo "## Occluder selection at $nviews viewpoints, leaves of $leaf triangles: efficiency % / mean ms"
echo
echo "| occluders | om-ps | om-fh | mos-om |"
echo "|---|---|---|---|"
echo "occluders,strategy,mean_ms,efficiency_percent,triangles,setup_ms" > "$out/viewpoints.csv"
for n in 1 2 4 8 12 16 24 32 48 64 96 128; do
    walk --route "$views" --frames "$nviews" --leaf-triangles "$leaf" --occluder-db "$fine_db" --occluders "$n" \
         --strategies om-ps,om-fh,mos-om --out "$out/viewpoints-n$n" |
        awk -v n="$n" -v csv="$out/viewpoints.csv" '$1 ~ /^(om-ps|om-fh|mos-om)$/ {
                           r[$1] = sprintf("%s / %.2f", $7, $2); e = $7; sub("%", "", e)
                           printf "%s,%s,%s,%s,%s,%s\n", n, $1, $2, e, $4, $10 >> csv }
                       END {printf "| %s | %s | %s | %s |\n", n, r["om-ps"], r["om-fh"], r["mos-om"]}'
done
echo
# Figure 6's reading: the fewest occluders with which each criterion comes
# within 0.1 points (the table's precision) of its own best efficiency, and
# of MOS's best.
awk -F, 'NR > 1 { e[$2, $1] = $4; if ($4 > best[$2]) best[$2] = $4; ns[$1] = 1 }
         END { m = best["mos-om"]
               for (s in best) { at[s] = ""; to_m[s] = ""
                   for (n = 1; n <= 128; n++) if (n in ns) {
                       if (at[s] == "" && e[s, n] >= best[s] - 0.1 - 1e-9) at[s] = n
                       if (to_m[s] == "" && e[s, n] >= m - 0.1 - 1e-9) to_m[s] = n } }
               printf "Best efficiency (fewest occluders reaching it): om-ps %.1f%% (%s), om-fh %.1f%% (%s), mos-om %.1f%% (%s);\n",
                      best["om-ps"], at["om-ps"], best["om-fh"], at["om-fh"], m, at["mos-om"]
               printf "occluders to reach mos-om'"'"'s best: om-ps %s, om-fh %s, mos-om %s.\n",
                      to_m["om-ps"] == "" ? "never" : to_m["om-ps"], to_m["om-fh"] == "" ? "never" : to_m["om-fh"], to_m["mos-om"] }' \
    "$out/viewpoints.csv"

echo
echo "## Occluder selection on the dense route ($frames frames, 64 occluders, leaves of 256 triangles)"
echo
echo "| criterion | mean ms | efficiency | setup ms |"
echo "|---|---|---|---|"
walk --route dense --frames "$frames" --occluder-db "$db" --strategies om-ps,om-fh,mos-om --out "$out/route" |
    awk -v csv="$out/route.csv" 'BEGIN { print "strategy,mean_ms,efficiency_percent,setup_ms" > csv }
        $1 ~ /^(om-ps|om-fh|mos-om)$/ { printf "| %s | %.2f | %s | %.2f |\n", $1, $2, $7, $10
                                         e = $7; sub("%", "", e); printf "%s,%s,%s,%s\n", $1, $2, e, $10 >> csv }'
echo
echo "## Culling methods by route (64 occluders): mean ms (speed-up vs vfc); maps and tests: setup + test ms"
echo
echo "| route | none | vfc | mos-om (OM+SDM) | pc-mos (PC) | OM+SDM vs PC | OM+SDM setup + tests | PC setup + tests |"
echo "|---|---|---|---|---|---|---|---|"
echo "route,none_ms,vfc_ms,mos_om_ms,pc_mos_ms,mos_om_setup_ms,mos_om_test_ms,pc_mos_setup_ms,pc_mos_test_ms" > "$out/methods.csv"
for route in dense medium open; do
    walk --route "$route" --frames "$frames" --occluder-db "$db" --strategies none,vfc,mos-om,pc-mos --out "$out/$route" |
        awk -v route="$route" -v csv="$out/methods.csv" '$1 ~ /^(none|vfc|mos-om|pc-mos)$/ {ms[$1] = $2; x[$1] = $6; su[$1] = $10; t[$1] = $11}
            END {printf "| %s | %.2f | %.2f | %.2f (%s) | %.2f (%s) | %.2fx | %.2f + %.2f | %.2f + %.2f |\n", route, ms["none"], ms["vfc"],
                 ms["mos-om"], x["mos-om"], ms["pc-mos"], x["pc-mos"], ms["pc-mos"] / ms["mos-om"],
                 su["mos-om"], t["mos-om"], su["pc-mos"], t["pc-mos"]
                 printf "%s,%s,%s,%s,%s,%s,%s,%s,%s\n", route, ms["none"], ms["vfc"], ms["mos-om"], ms["pc-mos"],
                        su["mos-om"], t["mos-om"], su["pc-mos"], t["pc-mos"] >> csv}'
done

if command -v gnuplot >/dev/null; then
    for s in om-ps om-fh mos-om; do   # one file per line: gnuplot joins points of one file
        awk -F, -v s="$s" 'NR == 1 || $2 == s' "$out/viewpoints.csv" > "$out/viewpoints-$s.csv"
    done
    gnuplot <<GNUPLOT
set datafile separator ","
set datafile columnheaders
set terminal pngcairo size 1000,420 font ",10"
set output "$out/viewpoints.png"
set multiplot layout 1,2 title "Occluder selection at $nviews viewpoints, leaves of $leaf triangles (Poon and Wang, figure 6)"
set logscale x 2
set xlabel "occluders"
set key bottom right
set ylabel "culling efficiency (%)"
plot for [s in "om-ps om-fh mos-om"] "$out/viewpoints-".s.".csv" using 1:4 with linespoints title s
set key top left
set ylabel "mean frame time (ms)"
plot for [s in "om-ps om-fh mos-om"] "$out/viewpoints-".s.".csv" using 1:3 with linespoints title s
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
    echo "plots: $out/viewpoints.png, $out/methods.png; data: $out/{viewpoints,route,methods}.csv"
fi
