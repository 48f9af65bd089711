#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# What one setting of one strategy costs and saves: the strategy at each
# value, beside vfc and the floor (ideal), in one walkthrough run with every
# variant frame by frame side by side. For an approximation knob
# (`tolerance`, exact at 0) the wrong pixels per frame against the unculled
# frame are the error; for a cost knob, the time and culling it trades.
# Usage: bench/sweep.sh STRATEGY SETTING V1,V2,... [ROUTE] [FRAMES]
#   bench/sweep.sh ou-shared tolerance 0,0.01,0.02,0.05,0.1,0.2,0.3 medium 30   (Bartz et al., section 5)
#   bench/sweep.sh om-ps tolerance 0,1,2,4,8,16,32,64 dense 30                  (Poon and Wang, section 5.2)
#   bench/sweep.sh om-ps coverage-ratio 0,0.1,0.2,0.4,0.8 dense 30
# Prints a markdown table.
# Superseded by build/bench/occu-bench-knobs (docs/knobs.md), which sweeps every
# knob of every strategy at once on the routes as one program; kept because
# the tables of docs/cpu-depth-culling.md and docs/shadow-culling.md name it.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
[ $# -ge 3 ] || { sed -n '2,12p' "$0" >&2; exit 2; }
strategy=$1
setting=$2
IFS=, read -r -a values <<<"$3"
route=${4:-dense}
frames=${5:-30}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
strategies=vfc,ideal
for v in "${values[@]}"; do strategies+=",$strategy:$setting=$v"; done
"$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
    --strategies "$strategies" "${databases[@]}" --out "$out" >/dev/null
s=$out/summary.csv
echo "## $strategy: $setting on the $route route (llvmpipe, 512x512, $frames frames, one run)"
echo
echo "vfc $(field "$s" vfc mean_ms) ms, ideal (the floor) $(field "$s" ideal mean_ms) ms."
echo
echo "| $setting | mean ms | x vfc | x floor | triangles | culling efficiency | visible leaves culled | wrong pixels per frame |"
echo "|---|---|---|---|---|---|---|---|"
for v in "${values[@]}"; do
    n="$strategy:$setting=$v"
    w=$(field "$s" "$n" wrong_pixels_per_frame); [ "$w" = "-" ] && w="0 (conservative)"
    echo "| $v | $(field "$s" "$n" mean_ms) | $(field "$s" "$n" vs_vfc) | $(field "$s" "$n" x_floor) |" \
         "$(field "$s" "$n" triangles) | $(field "$s" "$n" efficiency_percent)% |" \
         "$(field "$s" "$n" visible_leaves_culled) | $w |"
done
