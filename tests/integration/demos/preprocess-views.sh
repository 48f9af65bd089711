#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-preprocess views: the route it writes holds the database's views with
# occluders at inner grid points, every K-th, each camera where
# preprocessing put it (grid point, heading d at 2 pi d / D from +x to +z).
# Usage: preprocess-views.sh OCCU-PREPROCESS
set -eu
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# 3 x 1 x 3 points 10 apart from (0, 2, 0), 4 headings. The inner point
# (1, 0, 1) is point 4: views 16..19. View 0 is outer, view 17 empty.
cat > "$dir/db.txt" <<'DB'
occu-database occluder-sets 1
algorithm minimum-occluder-set
settings resolution=128 grid-origin=0,2,0 grid-spacing=10,0,10 grid-points=3,1,3 headings=4
scene 0000000000000001 leaves=1 triangles=1
code 0123456789ab
mesa 22.3.6/test
view 0 5
view 16 1 2
view 17
view 18 3
view 19 4
end
DB
expect() {
    if [ "$1" != "$2" ]; then
        printf 'views %s:\n%s\nexpected:\n%s\n' "$3" "$1" "$2"
        exit 1
    fi
}
"$bin" views --out "$dir/all.route" "$dir/db.txt" >/dev/null
expect "$(cat "$dir/all.route")" "10.000000 2.000000 10.000000 11.000000 2.000000 10.000000  # view 16
10.000000 2.000000 10.000000 9.000000 2.000000 10.000000  # view 18
10.000000 2.000000 10.000000 10.000000 2.000000 9.000000  # view 19" "--every 1"
"$bin" views --out "$dir/every2.route" --every 2 "$dir/db.txt" >/dev/null
expect "$(sed 's/.*# //' "$dir/every2.route")" "view 16
view 19" "--every 2"
echo "views lists the inner views with occluders where preprocessing put them"
