#!/bin/sh
# SPDX-License-Identifier: MIT
# bsp-pvs, a Quake III level's own PVS (strategies/teller_sequin_cell_portal_visibility/),
# on Debian's OpenArena levels (openarena-088-data, which tools/deps.sh test
# installs), every frame compared pixel for pixel with the unculled frame
# (the walkthrough compares every strategy not declared conservative):
#   - the spawn routes of aggressor and oa_minia (eyes where players stand):
#     bsp-pvs alone and chained before the unit's tests (ou-shared) and a CPU
#     map (om-ps) lose no pixel, cull no leaf the oracle sees, and cull (on
#     oa_minia, at least a third of the occluded leaves);
#   - random eyes in oa_minia's open leaves: the compiler's set is not
#     conservative there; the lost pixels are counted and reported (a number,
#     never '-': the comparison ran);
#   - a scene that is no level is refused, naming what bsp-pvs needs.
# Runs on the driver GALLIUM_DRIVER names (llvmpipe if none).
# Usage: level-pvs.sh WALKTHROUGH
set -u
walkthrough=$1
driver=${GALLIUM_DRIVER:-llvmpipe}
. "$(dirname "$0")/expect-error.sh"
. "$(dirname "$0")/walkthrough-summary.sh"

pak=/usr/share/games/openarena/baseoa/pak6-patch088.pk3
if [ ! -r "$pak" ]; then
    echo "FAIL: openarena-088-data is not installed ($pak); tools/deps.sh test installs it"
    exit 1
fi

for level in aggressor oa_minia; do
    out=$dir/spawn-$level
    walk "the spawn route of $level" "$out" --scene "$pak:maps/$level.bsp" --route spawn:1 \
        --strategies vfc,bsp-pvs,bsp-pvs+ou-shared,bsp-pvs+om-ps --size 64 --driver "$driver" \
        --report off --png-every 0 || continue
    summary=$out/summary.csv
    culled=$(column visible_leaves_culled "$summary")
    wrong=$(column wrong_pixels_per_frame "$summary")
    efficiency=$(column efficiency_percent "$summary")
    least=0
    [ "$level" = oa_minia ] && least=33
    lossless=$(awk -F, -v c="$culled" -v w="$wrong" -v e="$efficiency" -v least="$least" \
        'NR > 1 && $1 ~ /^bsp-pvs/ && $c == 0 && $w == "0.0" && $e + 0 > least' "$summary" | wc -l)
    if [ "$lossless" -eq 3 ]; then
        echo "ok: the spawn route of $level: bsp-pvs, bsp-pvs+ou-shared, bsp-pvs+om-ps lose no pixel" \
             "and cull more than $least% of the occluded leaves"
    else
        echo "FAIL: the spawn route of $level: a bsp-pvs strategy lost pixels or culled too little"
        sed 's/^/    /' "$summary"
        failures=$((failures + 1))
    fi
done

# Random eyes in open leaves: report what the compiler's set loses.
out=$dir/random
if walk "random views of oa_minia" "$out" --scene "$pak:maps/oa_minia.bsp" --route random:20:7 \
       --strategies vfc,bsp-pvs --size 64 --driver "$driver" --report off --png-every 0; then
    summary=$out/summary.csv
    wrong=$(column wrong_pixels_per_frame "$summary")
    culled=$(column visible_leaves_culled "$summary")
    loss=$(awk -F, -v w="$wrong" -v c="$culled" '$1 == "bsp-pvs" && $w ~ /^[0-9.]+$/ { print $w " pixels a frame lost, " $c " visible leaves culled" }' "$summary")
    if [ -n "$loss" ]; then
        echo "ok: 20 random views of oa_minia compared pixel for pixel: bsp-pvs $loss (the compiler's PVS)"
    else
        echo "FAIL: random views of oa_minia: no bsp-pvs row with lost pixels in $summary"
        sed 's/^/    /' "$summary"
        failures=$((failures + 1))
    fi
fi

expect_error "needs a Quake III level's BSP tree" \
    "$walkthrough" --scene field --frames 2 --strategies vfc,bsp-pvs+ou-shared --size 32 --driver "$driver" \
    --report off --png-every 0 --out "$dir/field"

echo "$failures failures"
[ $failures -eq 0 ]
