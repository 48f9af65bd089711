#!/usr/bin/env bash
# Frame time of the culling strategies against vfc on the four built-in routes
# (issue 5's table), llvmpipe 512x512, each route one run with every
# strategy side by side. The MOS database is the one bench/occluders.sh or
# tools/demo preprocessed (build/city-occluders-KEY.db, tools/lib.sh), made here if missing.
# Usage: bench/routes.sh [FRAMES]     Prints a markdown table.
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"
frames=${1:-120}
"$OCCU_ROOT/tools/build.sh" bench >/dev/null
db=$OCCU_ROOT/build/city-occluders-$(occluder_db_key).db
[ -s "$db" ] || "$OCCU_ROOT/build/demos/occu-preprocess" build --out "$db" >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
strategies=none,vfc,occu-hier,occu-hier-shared,om-ps,mos-om
echo "## Routes ($frames frames, llvmpipe, 512x512): mean ms (speed-up over vfc), culling efficiency"
echo
echo "| route | none | vfc | occu-hier | occu-hier-shared | om-ps | mos-om |"
echo "|---|---|---|---|---|---|---|"
for route in dense street medium open; do
    "$OCCU_ROOT/build/demos/walkthrough" --route "$route" --frames "$frames" --png-every 0 \
        --strategies "$strategies" --occluder-db "$db" --out "$out" |
        awk -v route="$route" '$1 ~ /^(none|vfc|occu-hier|occu-hier-shared|om-ps|mos-om)$/ {
                c[$1] = sprintf("%.2f (%s) %s", $2, $6, $7) }
            END { printf "| %s | %s | %s | %s | %s | %s | %s |\n", route, c["none"], c["vfc"], c["occu-hier"],
                  c["occu-hier-shared"], c["om-ps"], c["mos-om"] }'
done
