#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Occluder selection and culling method comparisons of Poon and Wang
# (figures 6, 9 and 8) on occu's city, llvmpipe, 512x512, in one run each:
#   1. figure 6: PS, FH and MOS with 1..128 occluders at viewpoints (the
#      database's own grid views, as the paper's "certain viewpoint"), on a
#      hierarchy of LEAF-triangle leaves (16: occluders near the paper's
#      primitives): culling efficiency and frame time, and how many
#      occluders each needs to reach its best efficiency;
#   2. figure 9: PS, FH and MOS with 64 occluders on the dense route;
#   3. figure 8: none, vfc, om-mos (OM + SDM) and pc-mos (pixel-wise) on
#      three routes, with the time spent building maps and testing.
# The MOS databases are preprocessed once into build/occluders/
# (occu-preprocess build --cache: named by what they depend on). Results
# are read from the walkthrough's summary.csv by column name.
# Usage: bench/occluders.sh [FRAMES] [LEAF]
# Prints markdown tables; writes build/bench-occluders/{viewpoints,route,methods}.csv
# and, with gnuplot, viewpoints.png (figure 6: culling and time against the
# number of occluders) and methods.png (figure 8).
set -euo pipefail
source "$(dirname "$0")/lib.sh"

frames=${1:-30}
leaf=${2:-16}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$OCCU_ROOT/build/bench-occluders
mkdir -p "$out"
db=$(occluder_db --max-occluders 512)
fine_db=$(occluder_db --max-occluders 512 --leaf-triangles "$leaf")
walk() { "$OCCU_ROOT/build/demos/walkthrough" --png-every 0 "$@" >/dev/null; }

# The viewpoints: every 6th view with occluders at the grid's inner points,
# each camera exactly as preprocessing placed it.
views=$out/viewpoints.route
"$OCCU_ROOT/build/demos/occu-preprocess" views --out "$views" --every 6 "$fine_db" >/dev/null
nviews=$(grep -c . "$views")

echo "## Occluder selection at $nviews viewpoints, leaves of $leaf triangles: efficiency % / mean ms"
echo
echo "| occluders | om-ps | om-fh | om-mos |"
echo "|---|---|---|---|"
echo "occluders,strategy,mean_ms,efficiency_percent,triangles,setup_ms" > "$out/viewpoints.csv"
for n in 1 2 4 8 12 16 24 32 48 64 96 128; do
    walk --route "$views" --leaf-triangles "$leaf" --occluder-db "$fine_db" --set occluders="$n" \
         --strategies om-ps,om-fh,om-mos --out "$out/viewpoints-n$n"
    row="| $n |"
    for strategy in om-ps om-fh om-mos; do
        f() { field "$out/viewpoints-n$n/summary.csv" "$strategy" "$1"; }
        row+=" $(f efficiency_percent)% / $(f mean_ms) |"
        echo "$n,$strategy,$(f mean_ms),$(f efficiency_percent),$(f triangles),$(f setup_ms)" >> "$out/viewpoints.csv"
    done
    echo "$row"
done
echo
# Figure 6's reading: the fewest occluders with which each criterion comes
# within 0.1 points (the table's precision) of its own best efficiency, and
# of MOS's best.
awk -F, 'NR > 1 { e[$2, $1] = $4; if ($4 > best[$2]) best[$2] = $4; ns[$1] = 1 }
         END { m = best["om-mos"]
               for (s in best) { at[s] = ""; to_m[s] = ""
                   for (n = 1; n <= 128; n++) if (n in ns) {
                       if (at[s] == "" && e[s, n] >= best[s] - 0.1 - 1e-9) at[s] = n
                       if (to_m[s] == "" && e[s, n] >= m - 0.1 - 1e-9) to_m[s] = n } }
               printf "Best efficiency (fewest occluders reaching it): om-ps %.1f%% (%s), om-fh %.1f%% (%s), om-mos %.1f%% (%s);\n",
                      best["om-ps"], at["om-ps"], best["om-fh"], at["om-fh"], m, at["om-mos"]
               printf "occluders to reach om-mos'"'"'s best: om-ps %s, om-fh %s, om-mos %s.\n",
                      to_m["om-ps"] == "" ? "never" : to_m["om-ps"], to_m["om-fh"] == "" ? "never" : to_m["om-fh"], to_m["om-mos"] }' \
    "$out/viewpoints.csv"

echo
echo "## Occluder selection on the dense route ($frames frames, 64 occluders, leaves of 256 triangles)"
echo
walk --route dense --frames "$frames" --occluder-db "$db" --strategies vfc,ideal,om-ps,om-fh,om-mos --out "$out/route"
r=$out/route/summary.csv
echo "vfc $(field "$r" vfc mean_ms) ms, ideal (the floor) $(field "$r" ideal mean_ms) ms."
echo
echo "| criterion | mean ms | x vfc | x floor | efficiency | setup ms |"
echo "|---|---|---|---|---|---|"
echo "strategy,mean_ms,efficiency_percent,setup_ms" > "$out/route.csv"
for strategy in om-ps om-fh om-mos; do
    f() { field "$r" "$strategy" "$1"; }
    echo "| $strategy | $(f mean_ms) | $(f vs_vfc) | $(f x_floor) | $(f efficiency_percent)% | $(f setup_ms) |"
    echo "$strategy,$(f mean_ms),$(f efficiency_percent),$(f setup_ms)" >> "$out/route.csv"
done
echo
echo "## Culling methods by route (64 occluders): mean ms (speed-up vs vfc, x the floor); maps and tests: setup + test ms"
echo
echo "| route | none | vfc | ideal | om-mos (OM+SDM) | pc-mos (PC) | OM+SDM vs PC | OM+SDM setup + tests | PC setup + tests |"
echo "|---|---|---|---|---|---|---|---|---|"
echo "route,none_ms,vfc_ms,om_mos_ms,pc_mos_ms,om_mos_setup_ms,om_mos_test_ms,pc_mos_setup_ms,pc_mos_test_ms" > "$out/methods.csv"
for route in dense medium open; do
    walk --route "$route" --frames "$frames" --occluder-db "$db" --strategies none,vfc,ideal,om-mos,pc-mos --out "$out/$route"
    m=$out/$route/summary.csv
    f() { field "$m" "$1" "$2"; }
    echo "| $route | $(f none mean_ms) | $(f vfc mean_ms) | $(f ideal mean_ms) |" \
         "$(f om-mos mean_ms) ($(f om-mos vs_vfc)x, $(f om-mos x_floor)x) | $(f pc-mos mean_ms) ($(f pc-mos vs_vfc)x, $(f pc-mos x_floor)x) |" \
         "$(awk -v a="$(f pc-mos mean_ms)" -v b="$(f om-mos mean_ms)" 'BEGIN { printf "%.2fx", a / b }') |" \
         "$(f om-mos setup_ms) + $(f om-mos test_ms) | $(f pc-mos setup_ms) + $(f pc-mos test_ms) |"
    echo "$route,$(f none mean_ms),$(f vfc mean_ms),$(f om-mos mean_ms),$(f pc-mos mean_ms),$(f om-mos setup_ms),$(f om-mos test_ms),$(f pc-mos setup_ms),$(f pc-mos test_ms)" >> "$out/methods.csv"
done

if command -v gnuplot >/dev/null; then
    for s in om-ps om-fh om-mos; do   # one file per line: gnuplot joins points of one file
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
plot for [s in "om-ps om-fh om-mos"] "$out/viewpoints-".s.".csv" using 1:4 with linespoints title s
set key top left
set ylabel "mean frame time (ms)"
plot for [s in "om-ps om-fh om-mos"] "$out/viewpoints-".s.".csv" using 1:3 with linespoints title s
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
plot "$out/methods.csv" using 2:xtic(1) title "none", "" using 3 title "vfc", "" using 4 title "om-mos (OM+SDM)", "" using 5 title "pc-mos (PC)"
GNUPLOT
    echo
    echo "plots: $out/viewpoints.png, $out/methods.png; data: $out/{viewpoints,route,methods}.csv"
fi
