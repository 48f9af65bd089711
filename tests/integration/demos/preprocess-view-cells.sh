#!/bin/sh
# SPDX-License-Identifier: MIT
# occu-preprocess view-cells (Wonka et al.): a range of cells made in two
# shards and merged is byte for byte the range made in one process; the
# Occlusion Unit and the read-back find the same sets (--test both fails
# otherwise); merge refuses a shard twice and shards of other options; a
# loaded scene and bad options are refused, named; the walkthrough takes
# the database and its summary says where the eye was in no cell or in one
# the database lacks. (Frames against unculled ones:
# tests/integration/view_cells_frames_test.cpp.)
# Usage: preprocess-view-cells.sh OCCU-PREPROCESS WALKTHROUGH
set -eu
bin=$1
walkthrough=$2
. "$(dirname "$0")/expect-error.sh"
fail() { echo "FAIL: $*"; exit 1; }

opts="--cells 0-23 --leaf-triangles 1024"
"$bin" view-cells $opts --test both --out "$dir/whole.pvs" >"$dir/whole.log" 2>&1 || { cat "$dir/whole.log"; fail "one process"; }
grep -q "every cell's sets equal" "$dir/whole.log" || { cat "$dir/whole.log"; fail "no comparison of the two tests"; }
"$bin" view-cells $opts --shard 1/2 --out "$dir/s1.pvs" >/dev/null 2>&1 || fail "shard 1"
"$bin" view-cells $opts --shard 2/2 --out "$dir/s2.pvs" >/dev/null 2>&1 || fail "shard 2"
"$bin" merge --out "$dir/merged.pvs" "$dir/s2.pvs" "$dir/s1.pvs" >/dev/null 2>&1 || fail "merge"
cmp "$dir/whole.pvs" "$dir/merged.pvs" || fail "merged shards differ from the whole"
[ "$(grep -c '^pvs ' "$dir/whole.pvs")" -eq 24 ] || fail "not 24 sets"
if "$bin" merge --out "$dir/twice.pvs" "$dir/s1.pvs" "$dir/s1.pvs" 2>/dev/null; then fail "merge took a shard twice"; fi
"$bin" view-cells $opts --epsilon 2 --shard 2/2 --out "$dir/other.pvs" >/dev/null 2>&1 || fail "other options"
if "$bin" merge --out "$dir/mixed.pvs" "$dir/s1.pvs" "$dir/other.pvs" 2>"$dir/mixed.log"; then
    fail "merge took shards of other options"
fi
grep -q "epsilon=1" "$dir/mixed.log" || { cat "$dir/mixed.log"; fail "the refusal does not name the difference"; }

# Bad input: named, refused, no crash.
touch "$dir/scene.obj"
expect_error "2.5D occluders" "$bin" view-cells --scene "$dir/scene.obj" --out "$dir/x.pvs"
expect_error "sqrt(2)" "$bin" view-cells --epsilon 0.5 --pixel 1 --cells 0-0 --out "$dir/x.pvs"
expect_error "--epsilon" "$bin" view-cells --epsilon nan --out "$dir/x.pvs"
expect_error "--clearance" "$bin" view-cells --clearance -1 --out "$dir/x.pvs"
expect_error "--cells" "$bin" view-cells --cells 5 --out "$dir/x.pvs"
expect_error "--test" "$bin" view-cells --test sometimes --out "$dir/x.pvs"
sed 's/^cell 3 .*/cell 3 1 2 3 4 5 nan/' "$dir/whole.pvs" > "$dir/bad.pvs"
expect_error "bad.pvs:11: cell: z is 'nan', not a finite number" "$bin" merge --out "$dir/x.pvs" "$dir/bad.pvs"
[ "$failures" -eq 0 ] || fail "$failures bad inputs not refused as they should be"

# The walkthrough culls with it (a camera in one of the cells made: the
# first cells lie along the city's south edge, where the dense route starts).
"$walkthrough" --route dense --frames 3 --size 96 --png-every 0 --leaf-triangles 1024 --strategies none,vfc,pvs \
    --set pvs-database="$dir/whole.pvs" --out "$dir/walk" >"$dir/walk.log" 2>&1 || { cat "$dir/walk.log"; fail "walkthrough"; }
grep -q "^pvs: .* frames with the eye in no view cell" "$dir/walk.log" || { cat "$dir/walk.log"; fail "no note from pvs"; }
echo "view-cell shards merge to the whole; the unit and the read-back agree; bad input refused; the walkthrough culls with it"
