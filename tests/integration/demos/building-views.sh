#!/bin/sh
# SPDX-License-Identifier: MIT
# Scenes nobody here made, from Debian's assimp-testmodels: every
# conservative strategy of the registry (the list is walkthrough
# --list-strategies', never typed in here) loses no visible pixel on them,
# from random eyes inside the model (route random:N:SEED in a model read
# from a file: spatial/inside_points.h) and on the orbit route; a strategy
# that cannot serve a scene refuses it with a reason, and walkthrough,
# asked for it alone, fails with a message naming it, not a crash. The
# scenes:
#   IFC/AC14-FZK-Haus.ifc  a real two-storey house (35,906 triangles): thin
#       walls, rooms, stairs, windows; the building the random eyes stand in;
#   glTF2/.../2CylinderEngine.glb  the largest complex model of the package
#       (121,496 triangles, 1,804 leaves): housings nested in housings, the
#       inside of an assembly, where parts hide parts at close range;
#   Collada/teapots.DAE  several separate closed objects in one scene:
#       occlusion between objects, eyes inside one of them.
# 'No pixel lost' says nothing where nothing is culled, so in each scene the
# strategies that cull there must cull some of the oracle's occluded leaves,
# on the random views and on the orbit: in the house and the engine the
# extension's (ou, ou-shared, chc, chc-shared, hp), om-ps and the skins that
# use the scene's faces (skins-drawn, skins-triangles); among the teapots,
# where little hides anything, skins-triangles (llvmpipe, 12 views: house
# 490-669 of 972 occluded leaves culled by those, engine 326-1622 of 2428,
# teapots 18 of 60; softpipe, 6 views: 378-639 of 880, 156-620 of 931, 16 of
# 40; the orbits alike). The others cull little or nothing in some scene
# (hzb and skins 3-55 leaves, hom, shadow and planes 0 in the house, om-mos
# 0 in the engine) and are not required to.
# Runs on the driver GALLIUM_DRIVER names (llvmpipe if none). At 64x64,
# with VIEWS random views a scene and FRAMES orbit frames, it took 71 s on
# llvmpipe (VIEWS 12, FRAMES 8) and 87 s on softpipe (VIEWS 6, FRAMES 4)
# on two shared cores under load: under tests/meson.build's 300 s.
# Usage: building-views.sh OCCU-RANDOM-VIEWS WALKTHROUGH VIEWS FRAMES
set -u
views=$1
walkthrough=$2
count=$3
frames=$4
driver=${GALLIUM_DRIVER:-llvmpipe}
. "$(dirname "$0")/expect-error.sh"

models=/usr/share/assimp/models
scenes="$models/IFC/AC14-FZK-Haus.ifc $models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb $models/Collada/teapots.DAE"
for scene in $scenes; do
    if [ ! -r "$scene" ]; then
        echo "FAIL: assimp-testmodels is not installed ($scene); tools/deps.sh test installs it"
        exit 1
    fi
done
small_databases="--set database-grid=2 --set database-layers=2 --set database-headings=4 --databases $dir/databases"

# must_cull WHAT CSV STRATEGY-COLUMN CULLED-COLUMN STRATEGIES...: each strategy
# named has a row of CSV whose culled column is above 0.
must_cull() {
    what=$1 csv=$2 name_column=$3 culled_column=$4
    shift 4
    idle=""
    for s in "$@"; do
        awk -F, -v s="$s" -v n="$name_column" -v c="$culled_column" \
            'NR > 1 && $n == s && $c > 0 { found = 1 } END { exit !found }' "$csv" || idle="$idle $s"
    done
    if [ -z "$idle" ]; then
        echo "ok: $what: $* each culled occluded leaves"
    else
        echo "FAIL: $what: culled no occluded leaf:$idle"
        sed 's/^/    /' "$csv"
        failures=$((failures + 1))
    fi
}

# A model with no inside (one open triangle): random eyes are a clear
# error after a bounded number of candidates, not a hang.
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$dir/triangle.obj"
expect_error "no eye inside the model" "$views" --scene "$dir/triangle.obj" --views 2 --size 64 --strategies vfc \
    --driver "$driver" --out "$dir/no-inside"

# The registry's conservative strategies: each family whose description
# says "; conservative", and its presets.
"$walkthrough" --list-strategies >"$dir/list" 2>&1 || { echo "FAIL: walkthrough --list-strategies"; exit 1; }
awk '/^  [a-z0-9-]+: / { family = substr($1, 1, length($1) - 1); if ((getline d) > 0) { kept = d ~ /; conservative/; if (kept) print family }; next }
     /^      [a-z0-9-]+ = / { if (kept) print $1 }' "$dir/list" >"$dir/conservative"
total=$(wc -l <"$dir/conservative")
if [ "$total" -lt 10 ] || ! grep -qx vfc "$dir/conservative" || ! grep -qx ou "$dir/conservative"; then
    echo "FAIL: only $total conservative strategies read from walkthrough --list-strategies"
    sed 's/^/    /' "$dir/conservative"
    exit 1
fi
echo "ok: $total conservative strategies in the registry: $(tr '\n' ' ' <"$dir/conservative")"

for scene in $scenes; do
    name=$(basename "$scene")
    case $name in
        teapots.DAE) culling="skins-triangles" ;;
        *) culling="ou ou-shared chc chc-shared hp om-ps skins-drawn skins-triangles" ;;
    esac
    # Random eyes inside the model: every conservative strategy (the
    # program's default), 0 visible pixels lost.
    status=0
    # shellcheck disable=SC2086
    "$views" --scene "$scene" --views "$count" --size 64 --seed 2026 $small_databases --driver "$driver" \
        --out "$dir/random-$name" >"$dir/random.out" 2>&1 || status=$?
    sed -n 's/^left out: \([a-z0-9-]*\) (.*)$/\1/p' "$dir/random.out" >"$dir/refused"
    refused=$(wc -l <"$dir/refused")
    ran=$((total - refused))
    missing=""
    for s in $(cat "$dir/conservative"); do
        grep -qE "^$s +$count +[0-9]" "$dir/random.out" || grep -qx "$s" "$dir/refused" || missing="$missing $s"
    done
    if [ $status -eq 0 ] && [ -z "$missing" ] &&
        grep -q "^scene $scene: $count views, $ran strategies, 0 visible pixels lost$" "$dir/random.out"; then
        echo "ok: $count random views inside $name on $driver, $ran strategies, 0 visible pixels lost" \
             "($refused refused with a reason: $(tr '\n' ' ' <"$dir/refused"))"
        # summary.csv: strategy $2, occluded leaves culled $9.
        # shellcheck disable=SC2086
        must_cull "random views inside $name" "$dir/random-$name/summary.csv" 2 9 $culling
    else
        echo "FAIL (status $status): random views inside $name (strategies neither run nor refused:$missing)"
        sed 's/^/    /' "$dir/random.out"
        failures=$((failures + 1))
    fi

    # A refused strategy, asked for alone, is a message and an exit status.
    for s in $(cat "$dir/refused"); do
        expect_error "$s" "$walkthrough" --scene "$scene" --route orbit --frames 1 --strategies "$s" --size 64 \
            --driver "$driver" --report off --png-every 0 --out "$dir/refused-$name"
    done

    # The orbit route: every strategy that serves the scene, no leaf the
    # oracle sees culled (then no visible pixel is lost).
    strategies=$(grep -vxF -f "$dir/refused" "$dir/conservative" | paste -sd, -)
    [ "$refused" -gt 0 ] || strategies=$(paste -sd, "$dir/conservative")
    status=0
    # shellcheck disable=SC2086
    "$walkthrough" --scene "$scene" --route orbit --frames "$frames" --strategies "$strategies" --size 64 \
        $small_databases --driver "$driver" --report off --png-every 0 --out "$dir/orbit-$name" \
        >"$dir/orbit.out" 2>&1 || status=$?
    summary=$dir/orbit-$name/summary.csv
    if [ $status -eq 0 ] && [ -f "$summary" ] &&
        [ "$(awk -F, -v f="$frames" 'NR > 1 && $3 == "yes" && $4 == f && $12 == 0' "$summary" | wc -l)" -eq "$ran" ]; then
        echo "ok: the orbit of $name, $frames frames, $ran strategies, no visible leaf culled"
        # summary.csv: strategy $1, efficiency_percent (occluded leaves culled) $11.
        # shellcheck disable=SC2086
        must_cull "the orbit of $name" "$summary" 1 11 $culling
    else
        echo "FAIL (status $status): the orbit of $name"
        sed 's/^/    /' "$dir/orbit.out"
        [ ! -f "$summary" ] || sed 's/^/    /' "$summary"
        failures=$((failures + 1))
    fi
done

echo "$failures failures"
[ $failures -eq 0 ]
