#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Frame time of every strategy against vfc and the floor (ideal: the
# oracle's visible leaves alone) on the four built-in routes, llvmpipe
# 512x512, each route one walkthrough run with every strategy frame by
# frame side by side. Read from the walkthrough's summary.csv.
# Usage: bench/routes.sh [FRAMES] [STRATEGIES]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
frames=${1:-120}
strategies=${2:-none,vfc,ideal,ou-shared,hp,om-ps,om-mos,skins,hzb,hom,shadow}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
IFS=, read -r -a names <<<"$strategies"
echo "## Routes ($frames frames, llvmpipe, 512x512): mean ms (x vfc's speed, x the floor), culling efficiency"
echo
printf '| route |'; printf ' %s |' "${names[@]}"; echo
printf '|---|'; printf -- '---|%.0s' "${names[@]}"; echo
for route in dense street medium open; do
    "$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
        --strategies "$strategies" "${databases[@]}" --out "$out/$route" >/dev/null
    s=$out/$route/summary.csv
    printf '| %s |' "$route"
    for n in "${names[@]}"; do
        printf ' %.2f (%sx, %sx) %s%% |' "$(field "$s" "$n" mean_ms)" "$(field "$s" "$n" vs_vfc)" \
            "$(field "$s" "$n" x_floor)" "$(field "$s" "$n" efficiency_percent)"
    done
    echo
done
echo
echo "Cells: mean frame ms (vfc's mean / this mean, this mean / ideal's mean) culling efficiency."
