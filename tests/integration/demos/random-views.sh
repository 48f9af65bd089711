#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-random-views: a CI-sized run (VIEWS random cameras over the city and
# the two assimp-testmodels scenes, every conservative strategy, om-mos and
# pc-mos with small occluder databases made on demand) loses no
# visible pixel, exits 0 and prints its summary; a strategy that does lose
# pixels (an approximation, ou:tolerance=0.9) makes it exit 1 naming the
# strategy, scene and view; bad options and unreadable scenes are refused
# with a message naming them; the house's own largest triangles as
# occluders (occluder-triangles) cull there and lose no pixel. Runs on the driver GALLIUM_DRIVER names
# (llvmpipe if none), given to the program as --driver.
# Usage: random-views.sh OCCU-RANDOM-VIEWS VIEWS
set -u
views=$1
count=$2
driver=${GALLIUM_DRIVER:-llvmpipe}
. "$(dirname "$0")/expect-error.sh"

haus=/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
if [ ! -r "$haus" ] || [ ! -r "$engine" ]; then
    echo "SKIP: Debian's assimp-testmodels is not installed ($haus, $engine)"
    exit 77
fi
out="$dir/out-dir"
printf 'this is not a scene\n' > "$dir/garbage.obj"

expect_error "--views" "$views" --views 0 --out "$out"
expect_error "--views" "$views" --views ten --out "$out"
expect_error "--views 2 gives some of the 3 scenes no view" "$views" --views 2 --out "$out"
expect_error "--size" "$views" --size 2 --out "$out"
expect_error "--seed" "$views" --seed -1 --out "$out"
expect_error "--fov" "$views" --fov 60 --out "$out"
expect_error "--fov" "$views" --fov 0,60 --out "$out"
expect_error "--fov" "$views" --fov 90,30 --out "$out"
expect_error "--fov" "$views" --fov 30,nan --out "$out"
expect_error "--batch" "$views" --batch 0 --out "$out"
expect_error "--switch-off" "$views" --switch-off 2 --out "$out"
expect_error "--coherence" "$views" --coherence maybe --out "$out"
expect_error "no-such-strategy" "$views" --strategies vfc,no-such-strategy --out "$out"
expect_error "no-such-setting" "$views" --strategies ou:no-such-setting=1 --out "$out"
expect_error "database-grid" "$views" --set database-grid=0 --out "$out"
expect_error "'nothing-has-this'" "$views" --set nothing-has-this=1 --out "$out"
expect_error "--make-databases" "$views" --make-databases some --out "$out"
expect_error "nowhere.db" "$views" --scene city --views 1 --strategies om-mos:database="$dir/nowhere.db" --out "$out"
expect_error "--strategies is empty" "$views" --strategies , --out "$out"
expect_error "--scene is empty" "$views" --scene , --out "$out"
expect_error "softpipe" "$views" --driver voodoo --out "$out"
expect_error "no-such-scene.obj" "$views" --scene city,"$dir/no-such-scene.obj" --views 2 --out "$out"
expect_error "garbage.obj" "$views" --scene "$dir/garbage.obj" --views 2 --out "$out"
expect_error "--nonsense" "$views" --nonsense 1
expect_error "--views" "$views" --views
# The counter finds lost pixels: an approximation loses some on the city.
expect_error "first by ou:tolerance=0.9 on scene city, view" "$views" --scene city --views 12 --size 64 \
    --strategies vfc,ou:tolerance=0.9 --driver "$driver" --out "$out"

# The CI-sized run: every conservative strategy, no pixel lost.
if "$views" --views "$count" --size 64 --seed 2026 --set database-grid=2 --set database-layers=2 \
    --set database-headings=4 --databases "$dir/databases" --driver "$driver" --out "$out" >"$dir/good" 2>&1; then
    status=0
else
    status=$?
fi
frames=$(sed -n 's/^total: [0-9]* views, \([0-9]*\) frames, 0 visible pixels lost.*/\1/p' "$dir/good")
if [ $status -eq 0 ] && [ -n "$frames" ] && grep -q "^total: $count views" "$dir/good" &&
    [ "$(grep -c '^scene .*: [0-9]* views, [0-9]* strategies, 0 visible pixels lost$' "$dir/good")" -eq 3 ] &&
    [ "$(grep -c '^occluder database made (for om-mos' "$dir/good")" -eq 3 ] &&
    grep -q '^left out: pvs' "$dir/good" &&
    [ "$(grep -cE '^(ou|chc|chc-shared|hzb-last-frame|om-mos|pc-mos|skins-both) +[0-9]+ ' "$dir/good")" -eq 21 ] &&
    [ "$(wc -l < "$out/views.csv")" -eq $((frames + 1)) ] &&
    [ "$(wc -l < "$out/summary.csv")" -ge 60 ]; then
    echo "ok: $count random views on $driver, $frames frames, 0 visible pixels lost"
    grep -E '^(scene|total)' "$dir/good"
else
    echo "FAIL (status $status): the CI-sized run"
    sed 's/^/    /' "$dir/good"
    failures=$((failures + 1))
fi

# The house's thin walls have no volume for skins: its own largest
# triangles as occluders (occluder-triangles) cull, and lose no pixel; so
# do they with merged coverage (coverage=merged: samples fused across
# triangles and their shared edges), and with leaves tested by their own
# triangles (occludee=triangles).
triangles=skins:occluder-triangles=256,hzb:occluder-triangles=256,hom:occluder-triangles=256
triangles=$triangles,skins:occluder-triangles=256:coverage=merged,hzb:occluder-triangles=256:coverage=merged
triangles=$triangles,skins:occluder-triangles=256:coverage=merged:occludee=triangles
if "$views" --scene "$haus" --views 40 --size 128 --seed 2026 --strategies "vfc,$triangles" --driver "$driver" \
    --out "$dir/triangles" >"$dir/triangles.out" 2>&1; then
    status=0
else
    status=$?
fi
if [ $status -eq 0 ] &&
    grep -q "^scene $haus: 40 views, 7 strategies, 0 visible pixels lost$" "$dir/triangles.out" &&
    [ "$(grep -cE '^(skins|hzb):occluder-triangles=256(:coverage=merged(:occludee=triangles)?)? +40 +[0-9.]+ +[0-9.]+x +- +[0-9]+ +([1-9][0-9]|100)\.[0-9]%' "$dir/triangles.out")" -eq 5 ]; then
    echo "ok: the house's own triangles as occluders, 40 random views on $driver, 0 visible pixels lost"
else
    echo "FAIL (status $status): the house's own triangles as occluders (skins and hzb must cull at least 10%)"
    sed 's/^/    /' "$dir/triangles.out"
    failures=$((failures + 1))
fi

echo "$failures failures"
[ $failures -eq 0 ]
