#!/bin/sh
# SPDX-License-Identifier: MIT
# A Quake III level from Debian's OpenArena data (openarena-088-data, which
# tools/deps.sh test installs), the small arena aggressor: occu-random-views
# over its open space (eyes only in BSP leaves of a cluster), every
# conservative strategy, om-mos and pc-mos with small occluder databases
# made at start, loses no visible pixel; the walkthrough's spawn route
# visits every spawn point of the level (K views each) with the oracle, no
# visible leaf culled. Runs on the driver GALLIUM_DRIVER names (llvmpipe if
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
else
    echo "FAIL (status $status): the spawn route of aggressor"
    sed 's/^/    /' "$dir/spawn.out"
    [ ! -f "$summary" ] || sed 's/^/    /' "$summary"
    failures=$((failures + 1))
fi

echo "$failures failures"
[ $failures -eq 0 ]
