#!/bin/sh
# SPDX-License-Identifier: MIT
# A Quake III level from Debian's OpenArena data (openarena-088-data, which
# tools/deps.sh test installs), the small arena aggressor: occu-random-views
# over its open space (eyes only in BSP leaves of a cluster), every
# conservative strategy, om-mos and pc-mos with small occluder databases
# made at start, loses no visible pixel; the walkthrough's spawn route
# visits every spawn point of the level (K views each) with the oracle, no
# visible leaf culled. 'Nothing lost' says nothing where nothing is culled,
# so the strategies named must also cull occluded leaves (the oracle's).
# The views are seeded: the counts are the same every run but chc's, which
# depend on when its results arrive (llvmpipe, 40 views: ou 33, chc 22 and
# 26, hzb 3, om-ps 58, om-mos 8, pc-mos 8, skins 3 of 288 occluded leaves;
# softpipe, 10 views: 22, 28, 1, 23, 1, 1, 1 of 95). On the spawn route om-ps
# culls 2.0% of the occluded leaves on both drivers and occu-hier-shared
# none, so only om-ps is required to cull there.
# Runs on the driver GALLIUM_DRIVER names (llvmpipe if
# none). Usage: level-views.sh OCCU-RANDOM-VIEWS WALKTHROUGH VIEWS
set -u
views=$1
walkthrough=$2
count=$3
driver=${GALLIUM_DRIVER:-llvmpipe}
. "$(dirname "$0")/expect-error.sh"

level=/usr/share/games/openarena/baseoa/pak6-patch088.pk3:maps/aggressor.bsp
if [ ! -r "${level%%:*}" ]; then
    echo "FAIL: openarena-088-data is not installed (${level%%:*}); tools/deps.sh test installs it"
    exit 1
fi

# Random views: every conservative strategy, no pixel lost.
if "$views" --scene "$level" --views "$count" --size 64 --seed 2026 --set database-grid=2 --set database-layers=2 \
       --set database-headings=4 --databases "$dir/databases" --driver "$driver" \
       --out "$dir/random" >"$dir/random.out" 2>&1; then
    status=0
else
    status=$?
fi
if [ $status -eq 0 ] &&
    grep -q "^scene $level: $count views, [0-9]* strategies, 0 visible pixels lost$" "$dir/random.out" &&
    [ "$(grep -cE '^(ou|chc|hzb|om-ps|om-mos|pc-mos|skins) +[0-9]+ ' "$dir/random.out")" -eq 7 ]; then
    echo "ok: $count random views of aggressor on $driver, 0 visible pixels lost"
    # summary.csv: strategy $2, occluded leaves (the oracle's) $8, of them culled $9.
    not_culling=$(awk -F, 'NR > 1 && $2 ~ /^(ou|chc|hzb|om-ps|om-mos|pc-mos|skins)$/ && !($8 > 0 && $9 > 0) { print $2 }' \
                  "$dir/random/summary.csv" | paste -sd' ' -)
    culling=$(awk -F, 'NR > 1 && $2 ~ /^(ou|chc|hzb|om-ps|om-mos|pc-mos|skins)$/ && $8 > 0 && $9 > 0 { n++ } END { print n + 0 }' \
              "$dir/random/summary.csv")
    if [ "$culling" -eq 7 ]; then
        echo "ok: each of the 7 strategies culled occluded leaves:" \
             "$(awk -F, 'NR > 1 && $2 ~ /^(ou|chc|hzb|om-ps|om-mos|pc-mos|skins)$/ { printf "%s %d of %d; ", $2, $9, $8 }' \
                "$dir/random/summary.csv")"
    else
        echo "FAIL: strategies that culled no occluded leaf of the random views: ${not_culling:-missing from summary.csv}"
        sed 's/^/    /' "$dir/random/summary.csv"
        failures=$((failures + 1))
    fi
else
    echo "FAIL (status $status): random views of aggressor"
    sed 's/^/    /' "$dir/random.out"
    failures=$((failures + 1))
fi

# The spawn route: 2 views at each of the level's 9 spawn points.
if "$walkthrough" --scene "$level" --route spawn:2 --strategies vfc,ideal,occu-hier-shared,om-ps --size 64 \
       --driver "$driver" --report off --png-every 0 --out "$dir/spawn" >"$dir/spawn.out" 2>&1; then
    status=0
else
    status=$?
fi
summary=$dir/spawn/summary.csv
if [ $status -eq 0 ] && grep -q "route spawn:2, 18 frames" "$dir/spawn.out" && [ -f "$summary" ] &&
    [ "$(awk -F, 'NR > 1 && $4 == 18 && $12 == 0' "$summary" | wc -l)" -eq 4 ]; then
    echo "ok: the spawn route of aggressor, 18 frames, no visible leaf culled"
    # summary.csv: strategy $1, efficiency_percent (occluded leaves culled) $11.
    if awk -F, 'NR > 1 && $1 == "om-ps" && $11 > 0 { found = 1 } END { exit !found }' "$summary"; then
        echo "ok: om-ps culled $(awk -F, 'NR > 1 && $1 == "om-ps" { print $11 }' "$summary")% of the route's occluded leaves"
    else
        echo "FAIL: om-ps culled no occluded leaf on the spawn route"
        sed 's/^/    /' "$summary"
        failures=$((failures + 1))
    fi
else
    echo "FAIL (status $status): the spawn route of aggressor"
    sed 's/^/    /' "$dir/spawn.out"
    [ ! -f "$summary" ] || sed 's/^/    /' "$summary"
    failures=$((failures + 1))
fi

echo "$failures failures"
[ $failures -eq 0 ]
