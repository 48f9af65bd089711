#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-bench-real-scenes: bad --tables are refused with a message naming
# them; a short run in two tables of frames (small, with the look, then
# flat) on a level's spawn points and a textured model's orbit prints both
# tables' targets, writes runs.csv rows for each table, and its look-cost
# line is vfc's mean in the first table over its mean in the second, as
# runs.csv has them.
# Usage: bench-real-scenes.sh OCCU-BENCH-REAL-SCENES
set -u
bench=$1
. "$(dirname "$0")/expect-error.sh"
out="$dir/out-dir"
level=/usr/share/games/openarena/baseoa/pak6-patch088.pk3:maps/aggressor.bsp
model=/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb
for f in /usr/share/games/openarena/baseoa/pak6-patch088.pk3 "$model"; do
    [ -f "$f" ] || { echo "SKIP: no $f (tools/deps.sh test installs it)"; exit 77; }
done

expect_error "--tables wants SIZE:LOOK items" "$bench" --tables 512 --out "$out"
expect_error "item '512:shiny'" "$bench" --tables 512:shiny --out "$out"
expect_error "item '9x9:flat'" "$bench" --tables 9x9:flat --out "$out"
expect_error "--tables is empty" "$bench" --tables , --out "$out"
expect_error "not both" "$bench" --tables 512:flat --size 256 --out "$out"
expect_error "--look wants flat or scene" "$bench" --look shiny --out "$out"

if ! "$bench" --scenes "$level,$model" --strategies vfc,ideal --spawn-views 1 --orbit-frames 3 --random-views 0 \
        --load-levels "$level" --repeat 1 --tables 96x54:scene,48:flat --databases "$dir/db" --out "$out" \
        >"$dir/log" 2>&1; then
    echo "FAIL: the short run failed"
    cat "$dir/log"
    exit 1
fi
for heading in "## The targets, 96x54 with the look" "## The targets, 48x48 flat" \
               "## What the look costs: vfc's frame 96x54 with the look against 48x48 flat"; do
    grep -qF "$heading" "$dir/log" || { echo "FAIL: no '$heading'"; failures=$((failures + 1)); }
done
csv="$out/runs.csv"
# check_scene PATH ROUTE NAME: vfc rows in both tables, and the look-cost
# line of the scene and route is the first table's vfc mean over the second's.
check_scene() {
    for table in 96x54,scene 48x48,flat; do
        awk -F, -v s="$1" -v r="$2" -v t="$table" \
            'BEGIN { split(t, p, ",") } $1 == s && $2 == r && $3 == p[1] && $4 == p[2] && $6 == "vfc" { f = 1 }
             END { exit !f }' "$csv" ||
            { echo "FAIL: no vfc row for $3 $2 in $table in $csv"; failures=$((failures + 1)); }
    done
    printed=$(sed -n "s/^look cost: \`$3\` $2: .*: \([0-9.]*\)x\$/\1/p" "$dir/log")
    if [ -z "$printed" ]; then
        echo "FAIL: no look cost line for $3 $2"
        failures=$((failures + 1))
        return
    fi
    awk -F, -v s="$1" -v r="$2" -v printed="$printed" \
        '$1 == s && $2 == r && $6 == "vfc" { if ($4 == "scene") a = $8; else b = $8 }
         END { d = (b > 0 ? a / b : 0) - printed; if (d < 0) d = -d; exit !(b > 0 && d <= 0.006) }' "$csv" ||
        { echo "FAIL: $3 $2: look cost $printed is not vfc's scene mean over its flat mean in $csv"; failures=$((failures + 1)); }
}
check_scene "$level" spawn:1 aggressor
check_scene "$model" orbit BoxTextured.glb
# Every conservative strategy (here vfc and ideal) keeps every pixel.
grep -q 'not met: [0-9]* px' "$dir/log" && { echo "FAIL: lost pixels"; failures=$((failures + 1)); }
[ $failures -eq 0 ] && echo "ok: two tables, runs.csv rows of each, the look cost from their vfc means"
exit $((failures != 0))
