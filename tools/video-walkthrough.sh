#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Makes DIR/route.mp4, a video of a walkthrough's route (ffmpeg, H.264, 10
# frames a second): for each chosen strategy its frame and its top view side
# by side (the top view's title carries the strategy, frame number and the
# running frame time in ms), strategies in a grid of two columns when there
# are more than two. It needs an image of every frame: run the walkthrough
# with --png-every 1. STRATEGY is a label as in summary.csv (default: every
# strategy there). Prints the path of the video. tools/demo runs it.
# Usage: tools/video-walkthrough.sh DIR [STRATEGY...]
set -euo pipefail

me=video-walkthrough.sh
die() { printf '%s: %s\n' "$me" "$*" >&2; exit 1; }

[ $# -ge 1 ] || die "usage: $me DIR [STRATEGY...] (a walkthrough's --out directory, run with --png-every 1)"
dir=$1
shift
summary=$dir/summary.csv
[ -f "$summary" ] || die "no $summary (make it with: build/demos/walkthrough --png-every 1 --out $dir)"
command -v ffmpeg >/dev/null ||
    die "ffmpeg is not installed, so no video was made (Debian: apt-get install ffmpeg; tools/deps.sh demo installs it)"

# Frames and size from summary.csv's header-named columns; every strategy when none is given.
read -r frames size < <(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
                                 { print $c["frames"], $c["size"]; exit }' "$summary")
[ -n "${size:-}" ] && [ -n "${frames:-}" ] || die "$summary has no frames or size column"
strategies=("$@")
if [ ${#strategies[@]} -eq 0 ]; then
    mapfile -t strategies < <(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "strategy") c = i; next } { print $c }' "$summary")
fi

# The walkthrough's file_name(): ':', '/' and '=' become '_'. Every frame of each must be there.
inputs=()
for s in "${strategies[@]}"; do
    name=${s//[:\/=]/_}
    for ((f = 0; f < frames; ++f)); do
        n=$(printf '%04d' "$f")
        for png in "$dir/$name-$n.png" "$dir/$name-top-$n.png"; do
            [ -f "$png" ] || die "no $png: the video needs an image of every frame (run the walkthrough with --png-every 1)"
        done
    done
    inputs+=(-framerate 10 -start_number 0 -i "$dir/$name-%04d.png"
             -framerate 10 -start_number 0 -i "$dir/$name-top-%04d.png")
done

# Each strategy a tile: frame | top view (2*size x size); tiles in one column
# up to two strategies, else two columns.
n=${#strategies[@]}
filter=""
for ((i = 0; i < n; ++i)); do
    filter+="[$((2 * i)):v][$((2 * i + 1)):v]hstack=inputs=2[t$i];"
done
if [ "$n" -eq 1 ]; then
    filter+="[t0]null[grid]"
else
    columns=1
    [ "$n" -le 2 ] || columns=2
    layout=""
    for ((i = 0; i < n; ++i)); do
        layout+="${layout:+|}$((i % columns * 2 * size))_$((i / columns * size))"
        filter+="[t$i]"
    done
    filter+="xstack=inputs=$n:layout=$layout:fill=black[grid]"
fi
# H.264 in yuv420p wants even sides.
filter+=";[grid]pad=ceil(iw/2)*2:ceil(ih/2)*2,format=yuv420p[out]"

video=$dir/route.mp4
log=$(mktemp)
trap 'rm -f "$log"' EXIT
ffmpeg -nostdin -y -loglevel error "${inputs[@]}" -filter_complex "$filter" -map '[out]' \
    -c:v libx264 -preset veryfast -crf 23 -r 10 -frames:v "$frames" "$video" 2>"$log" ||
    { cat "$log" >&2; die "ffmpeg failed"; }
echo "$video"
