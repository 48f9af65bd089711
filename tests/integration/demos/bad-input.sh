#!/bin/sh
# SPDX-License-Identifier: MIT
# Bad input to the demos gets a message naming it and a failing exit status,
# never a crash (no signal) and never a silent success.
# Usage: bad-input.sh WALKTHROUGH OCCU-PREPROCESS
set -u
walkthrough=$1
preprocess=$2
. "$(dirname "$0")/expect-error.sh"

printf 'v 0 0 0\nv 1 0 0\nf 1 2 99\n' > "$dir/broken.obj"
printf 'this is not a scene\n' > "$dir/garbage.gltf"
printf '0 1.7 0 1 1.7\n' > "$dir/short.route"
printf 'hello\n' > "$dir/bad.db"
# Non-finite numbers: a vertex, a route camera, a database grid spacing.
printf 'o wall\nv 0 0 0\nv 1 0 0\nv 1 nan 0\nf 1 2 3\n' > "$dir/nan.obj"
printf '0 1.7 0 10 1.7 0\n0 1.7 0 nan 1.7 0\n' > "$dir/nan.route"
printf '0 0 5 0 0 0\n' > "$dir/box.route"
printf 'occu-database occluder-sets 1\nalgorithm minimum-occluder-set\nsettings resolution=32 grid-origin=0,0,0 grid-spacing=1,inf,1 grid-points=2,1,2 headings=4\nscene f leaves=1 triangles=2\ncode c\nmesa m\nend\n' > "$dir/inf.db"
# Debian's assimp-testmodels (tools/deps.sh test installs it): a box whose
# vertices include infinities.
infinite_box=$(dpkg -L assimp-testmodels 2>/dev/null | grep '/BoxWithInfinites\.glb$' | head -n 1)
[ -n "$infinite_box" ] || { echo "FAIL: assimp-testmodels is not installed (BoxWithInfinites.glb)"; failures=$((failures + 1)); }
# Quake III levels: a .bsp cut short after its magic, and one whose faces lump runs
# past the end of the file (a directory entry of lump 13 beyond its bytes).
printf 'IBSP' > "$dir/short.bsp"
{ printf 'IBSP\056\000\000\000'; i=0; while [ $i -lt 17 ]; do printf '\220\000\000\000\000\000\000\000'; i=$((i + 1)); done; } > "$dir/lumps.bsp"
printf '\220\000\000\000\150\000\000\000' | dd of="$dir/lumps.bsp" bs=1 seek=$((8 + 13 * 8)) conv=notrunc 2>/dev/null
pak=/usr/share/games/openarena/baseoa/pak6-patch088.pk3
[ -f "$pak" ] || { echo "FAIL: openarena-088-data is not installed ($pak)"; failures=$((failures + 1)); }
# A real database, of the city in leaves of 256 triangles.
"$preprocess" build --out "$dir/small.db" --grid 2,1,2 --directions 1 >/dev/null 2>&1 || echo "could not make small.db"

expect_error "zbuffer-magic" "$walkthrough" --strategies vfc,zbuffer-magic
expect_error "--frames" "$walkthrough" --frames -3
expect_error "--size wants PIXELS or WIDTHxHEIGHT" "$walkthrough" --size 1280x
expect_error "--look wants flat or scene" "$walkthrough" --look pretty
expect_error "--clock wants wall or thread, got 'foo'" "$walkthrough" --clock foo
expect_error "--size wants PIXELS or WIDTHxHEIGHT" "$walkthrough" --size 1280x8
expect_error "--size wants PIXELS or WIDTHxHEIGHT" "$walkthrough" --size 64x64x64
expect_error "--leaf-triangles wants auto or an integer" "$walkthrough" --leaf-triangles automatic
expect_error "tolerance" "$walkthrough" --strategies ou:tolerance=1.5
expect_error "tolerance" "$walkthrough" --strategies ou --set tolerance=nan
expect_error "'threshold'" "$walkthrough" --strategies ou:threshold=0.1
expect_error "proxy" "$walkthrough" --strategies ou:proxy=maybe
expect_error "'passes'" "$walkthrough" --strategies vfc,om-ps --set passes=shared
expect_error "--coherence" "$walkthrough" --coherence maybe
expect_error "--allocator" "$walkthrough" --allocator glibc
expect_error "--make-databases" "$walkthrough" --make-databases some
# A database a strategy requires is made on demand, where it can be written.
expect_error "cannot make the database directory '/proc/occu-databases'" "$walkthrough" --frames 1 --size 16 \
    --strategies om-mos:database-grid=1:database-headings=1 --databases /proc/occu-databases --out "$dir/walk"
expect_error "needs the oracle" "$walkthrough" --strategies vfc,ideal --oracle off
expect_error "bad.db" "$walkthrough" --frames 1 --strategies om-mos --occluder-db "$dir/bad.db"
expect_error "small.db: made for another scene" "$walkthrough" --frames 1 --strategies om-mos --leaf-triangles 512 \
    --occluder-db "$dir/small.db"
expect_error "random:N:SEED" "$walkthrough" --frames 1 --route random:0:1
expect_error "broken.obj" "$walkthrough" --frames 1 --scene "$dir/broken.obj"
expect_error "garbage.gltf" "$walkthrough" --frames 1 --scene "$dir/garbage.gltf"
expect_error "no-such-scene.obj" "$walkthrough" --frames 1 --scene "$dir/no-such-scene.obj"
expect_error "nan.obj': vertex 2 of mesh 'wall' is (1, nan, 0)" "$walkthrough" --frames 1 --scene "$dir/nan.obj"
[ -z "$infinite_box" ] || expect_error "BoxWithInfinites.glb': vertex" "$walkthrough" --frames 1 \
    --strategies vfc --oracle off --png-every 0 --out "$dir/walk" --scene "$infinite_box" --route "$dir/box.route"
expect_error "short.bsp': Quake III BSP: the file is 4 bytes" "$walkthrough" --frames 1 --scene "$dir/short.bsp"
expect_error "lumps.bsp': Quake III BSP: lump 13 (faces): bytes 144 to 248 lie beyond the end" "$walkthrough" --frames 1 \
    --scene "$dir/lumps.bsp"
expect_error "no-such-level.bsp': no such file" "$walkthrough" --frames 1 --scene "$dir/no-such-level.bsp"
expect_error "cannot open the archive '$dir/no-such.pk3'" "$walkthrough" --frames 1 --scene "$dir/no-such.pk3:maps/x.bsp"
expect_error "holds no member 'maps/no-such-level.bsp'" "$walkthrough" --frames 1 --scene "$pak:maps/no-such-level.bsp"
expect_error "route 'spawn': the scene is not a Quake III level" "$walkthrough" --frames 1 --route spawn
expect_error "nan.route:2: tx is 'nan'" "$walkthrough" --frames 1 --route "$dir/nan.route"
expect_error "inf.db:3: settings: grid-spacing is '1,inf,1'" "$walkthrough" --frames 1 --strategies om-mos --occluder-db "$dir/inf.db"
expect_error "inf.db:3: settings: grid-spacing is '1,inf,1'" "$preprocess" views --out "$dir/x.route" "$dir/inf.db"
expect_error "short.route" "$walkthrough" --frames 1 --route "$dir/short.route"
expect_error "map-divisor" "$walkthrough" --strategies om-ps:map-divisor=0
expect_error "--nonsense" "$walkthrough" --nonsense 1
expect_error "--grid" "$preprocess" build --out "$dir/x.db" --grid 3,0,3
expect_error "--shard" "$preprocess" build --out "$dir/x.db" --shard 0/2
expect_error "--selection" "$preprocess" build --out "$dir/x.db" --selection best
expect_error "--pixels-per-occluder" "$preprocess" build --out "$dir/x.db" --pixels-per-occluder 0
expect_error "--cache" "$preprocess" build --out "$dir/x.db" --cache "$dir"
expect_error "--out FILE or --cache DIR" "$preprocess" build
expect_error "bad.db" "$preprocess" merge --out "$dir/x.db" "$dir/bad.db"
expect_error "views needs one database" "$preprocess" views --out "$dir/x.route"
expect_error "--every" "$preprocess" views --out "$dir/x.route" --every 0 "$dir/bad.db"
expect_error "bad.db" "$preprocess" views --out "$dir/x.route" "$dir/bad.db"
expect_error "frob" "$preprocess" frob

[ $failures -eq 0 ] || { echo "$failures bad-input cases failed"; exit 1; }
echo "every bad input was refused with a message naming it"
