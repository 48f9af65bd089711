#!/bin/sh
# SPDX-License-Identifier: MIT
# skin-source=brushes (occluders/brush_occluders.h, LevelBrushOccluders::BoxBrush): the skin
# families with a Quake III level's box brushes as occluders, on random eyes
# in Debian's OpenArena levels (openarena-088-data, which tools/deps.sh test
# installs), every frame compared pixel for pixel with the unculled frame:
#   - oa_minia's random:100:2026 holds eyes in open space behind the arena's
#     walls, whose sides toward them are caulk (nodraw): a box brush against
#     such a wall hides nothing from there. Every skin family loses no pixel,
#     culls no leaf the oracle sees, and skins culls some occluded leaves;
#   - aggressor's random eyes, the same;
#   - a scene that is no level is refused, naming what the setting needs.
# Runs on the driver GALLIUM_DRIVER names (llvmpipe if none).
# Usage: level-brushes.sh WALKTHROUGH SIZE
set -u
walkthrough=$1
size=$2
driver=${GALLIUM_DRIVER:-llvmpipe}
. "$(dirname "$0")/expect-error.sh"
. "$(dirname "$0")/walkthrough-summary.sh"

pak=/usr/share/games/openarena/baseoa/pak6-patch088.pk3
if [ ! -r "$pak" ]; then
    echo "FAIL: openarena-088-data is not installed ($pak); tools/deps.sh test installs it"
    exit 1
fi


strategies=vfc
for family in skins hzb hom shadow planes; do
    strategies=$strategies,$family:skin-source=brushes
done
for level in oa_minia aggressor; do
    out=$dir/random-$level
    walk "random:100:2026 of $level" "$out" --scene "$pak:maps/$level.bsp" --route random:100:2026 \
        --strategies "$strategies" --coherence off --switch-off 0 --size "$size" --driver "$driver" \
        --report off --png-every 0 || continue
    summary=$out/summary.csv
    culled=$(column visible_leaves_culled "$summary")
    wrong=$(column wrong_pixels_per_frame "$summary")
    efficiency=$(column efficiency_percent "$summary")
    lossless=$(awk -F, -v c="$culled" -v w="$wrong" \
        'NR > 1 && $1 ~ /skin-source=brushes$/ && $c == 0 && ($w == "0.0" || $w == "-")' "$summary" | wc -l)
    culling=$(awk -F, -v e="$efficiency" '$1 == "skins:skin-source=brushes" && $e + 0 > 0' "$summary" | wc -l)
    if [ "$lossless" -eq 5 ] && [ "$culling" -eq 1 ]; then
        echo "ok: random:100:2026 of $level at ${size}px: the five skin families with skin-source=brushes" \
             "lose no pixel, cull no visible leaf, skins culls $(awk -F, -v e="$efficiency" \
             '$1 == "skins:skin-source=brushes" { print $e }' "$summary")% of the occluded leaves"
    else
        echo "FAIL: random:100:2026 of $level: a skin family with skin-source=brushes lost pixels or culled nothing"
        sed 's/^/    /' "$summary"
        failures=$((failures + 1))
    fi
done

expect_error "skin-source=brushes: the scene is not a Quake III level" \
    "$walkthrough" --scene field --frames 2 --strategies vfc,skins:skin-source=brushes --size 32 --driver "$driver" \
    --report off --png-every 0 --out "$dir/field"

echo "$failures failures"
[ $failures -eq 0 ]
