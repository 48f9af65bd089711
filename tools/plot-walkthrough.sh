#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Plots a walkthrough's per-frame results (DIR/frames.csv, written by
# build/demos/walkthrough --out DIR) with gnuplot, into DIR:
#   frame-times.png  frame time of every strategy along the route, log scale:
#                    occlusion culling against vfc and the floor (ideal), as
#                    Wonka et al.'s figure 11 plots it
#   triangles.png    triangles drawn per frame, log scale
#   efficiency.png   culling efficiency per frame: occluded leaves culled /
#                    occluded leaves, against the exact-visibility oracle
#                    (left out when the walkthrough ran with --oracle off)
# Prints the path of each plot it made, one a line. tools/demo runs it.
# Usage: tools/plot-walkthrough.sh DIR
set -euo pipefail

me=plot-walkthrough.sh
die() { printf '%s: %s\n' "$me" "$*" >&2; exit 1; }

[ $# -eq 1 ] || die "usage: $me DIR (a walkthrough's --out directory, holding frames.csv)"
dir=$1
csv=$dir/frames.csv
[ -f "$csv" ] || die "no $csv (make it with: build/demos/walkthrough --out $dir)"
command -v gnuplot >/dev/null ||
    die "gnuplot is not installed, so no plots were made (Debian: apt-get install gnuplot-nox; tools/deps.sh demo installs it)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Per strategy, in the order of the walkthrough's --strategies, from the
# columns named in the header: frame ms triangles, and frame efficiency for
# the frames with occluded leaves (efficiency is undefined without them).
awk -F, -v work="$work" '
    NR == 1 {
        for (i = 1; i <= NF; ++i) col[$i] = i
        split("strategy route frame ms triangles oracle_occluded_leaves occluded_leaves_culled", need, " ")
        for (k in need)
            if (!(need[k] in col)) { print "frames.csv has no column " need[k] > "/dev/stderr"; bad = 1; exit 1 }
        next
    }
    {
        s = $col["strategy"]
        if (!(s in id)) { id[s] = ++n; print s > (work "/labels"); print $col["route"] > (work "/route") }
        f = work "/" id[s]
        print $col["frame"], $col["ms"], $col["triangles"] > (f ".dat")
        ms[s] += $col["ms"]; frames[s]++
        if ($col["oracle_occluded_leaves"] > 0) {
            print $col["frame"], 100 * $col["occluded_leaves_culled"] / $col["oracle_occluded_leaves"] > (f "-eff.dat")
            any_efficiency = 1
        }
    }
    END {
        if (bad) exit 1
        for (s in id) printf "%.2f\n", ms[s] / frames[s] > (work "/" id[s] ".mean")
        if (any_efficiency) print "yes" > (work "/efficiency")
    }' "$csv" || die "cannot read $csv"
[ -s "$work/labels" ] || die "$csv holds no frames"

route=$(head -n 1 "$work/route")
size=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "size") c = i; next } c { print $c; exit }' \
           "$dir/summary.csv" 2>/dev/null || true)
where="the $route route${size:+, ${size}x${size} pixels}"
where=${where//\\/\/}
where=${where//\"/\'}

# One line per strategy: the baselines drawn apart (vfc dashed black, the
# floor ideal dotted grey, none light grey), the others in gnuplot's colours.
plot_command() {   # COLUMN FILE-SUFFIX [mean]: with "mean", each title gives the strategy's mean ms
    local column=$1 suffix=$2 mean=${3:-} k=0 sep="" style label
    printf 'plot'
    while IFS= read -r label; do
        k=$((k + 1))
        [ -s "$work/$k$suffix.dat" ] || continue
        case $label in
            vfc) style='lc rgb "black" dt 2 lw 2' ;;
            ideal) style='lc rgb "#707070" dt 3 lw 2' ;;
            none) style='lc rgb "#b0b0b0" lw 1.5' ;;
            *) style="lc $k lw 1.5" ;;
        esac
        label=${label//\\/\\\\}
        [ -z "$mean" ] || label="$label ($(cat "$work/$k.mean") ms mean)"
        printf '%s "%s" using 1:%s with lines %s title "%s"' "$sep" "$work/$k$suffix.dat" "$column" "$style" \
            "${label//\"/\\\"}"
        sep=","
    done < "$work/labels"
    echo
}

plots=("$dir/frame-times.png" "$dir/triangles.png")
{
    cat <<GNUPLOT
set terminal pngcairo size 1100,620 font ",11" noenhanced
set key below
set grid xtics ytics mytics lc rgb "#dddddd"
set xlabel "frame"
set logscale y
set output "$dir/frame-times.png"
set title "Frame time per frame along $where (log scale)"
set ylabel "frame time (ms)"
$(plot_command 2 "" mean)
set output "$dir/triangles.png"
set title "Triangles drawn per frame along $where (log scale)"
set ylabel "triangles drawn"
set format y "%.0s%c"
$(plot_command 3 "")
GNUPLOT
    if [ -f "$work/efficiency" ]; then
        plots+=("$dir/efficiency.png")
        cat <<GNUPLOT
set output "$dir/efficiency.png"
unset logscale y
set format y "%g"
set yrange [-2:102]
set title "Culling efficiency per frame along $where: occluded leaves culled / occluded leaves"
set ylabel "culling efficiency (%)"
set key below
$(plot_command 2 "-eff")
GNUPLOT
    fi
} > "$work/plots.gp"
gnuplot "$work/plots.gp" 2> "$work/gnuplot.log" || { cat "$work/gnuplot.log" >&2; die "gnuplot failed on $csv"; }
[ -f "$work/efficiency" ] ||
    echo "$me: no efficiency.png: $csv has no oracle counts (the walkthrough ran with --oracle off)" >&2
printf '%s\n' "${plots[@]}"
