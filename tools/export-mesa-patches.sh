#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Developer tool: writes the cache's Mesa tree back into patches/mesa/.
# tools/mesa.sh commits each patch of the series on the pristine source
# (git am); change a patch by changing its commit (git commit --amend for
# the last one, git commit --fixup=<commit> and git rebase -i --autosquash
# for the others, a new commit for a new patch), then run this: it writes
# `git format-patch` of every commit after the pristine one, under the
# file names patches/mesa/series gives them in order; commits beyond the
# series keep format-patch's names and are appended to it.
# A patch that adds one specification under docs/_extra/specs/ (each part's
# first) is written from spec/ instead of from its commit: spec/ is the one
# source of the extensions' text, and Mesa's copy is made from it here
# (tools/mesa-spec-patch.py), whatever the tree's commit holds.
# Usage: tools/export-mesa-patches.sh [MESA_TREE]
#   MESA_TREE   a git worktree of that repository holding the series to export
#               (default: the cache's source/), e.g. one made with
#               `git -C <cache>/source worktree add <dir> -b <branch> master`
set -euo pipefail
source "$(dirname "$0")/lib.sh"

src=${1:-$OCCU_CACHE/mesa/$MESA_DEBIAN_VERSION/source}
[ -e "$src/.git" ] || die "no Mesa source tree at $src (run tools/mesa.sh first)"
cd "$src"
uncommitted=$(git status --porcelain | grep -v -E '^\?\? \.occu-(pristine|applied)$' || true)
[ -z "$uncommitted" ] || die "$src has changes in no commit; commit them into the patch they belong to first:
$uncommitted"
pristine=$(git rev-list --max-parents=0 HEAD)

names=()
series=$OCCU_ROOT/patches/mesa/series
while IFS= read -r name || [ -n "$name" ]; do
    name=${name%%#*}; name=$(echo "$name" | xargs)
    [ -n "$name" ] && names+=("$name")
done < "$series"
commits=$(git rev-list --count "$pristine..HEAD")
[ "$commits" -ge "${#names[@]}" ] ||
    die "the tree has $commits commits after pristine but the series names ${#names[@]} patches (run tools/mesa.sh?)"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
git format-patch -q --zero-commit --no-signature --no-stat -o "$out" "$pristine..HEAD"
k=0
for f in "$out"/*.patch; do
    if [ $k -lt ${#names[@]} ]; then
        name=${names[k]}
    else
        name=${f##*/}
        echo "$name" >> "$series"
        say "new patch $name appended to the series"
    fi
    mv "$f" "$OCCU_ROOT/patches/mesa/$name"
    if /usr/bin/python3 "$OCCU_ROOT/tools/mesa-spec-patch.py" --rewrite "$OCCU_ROOT/patches/mesa/$name"; then
        say "wrote $name (its specification from spec/)"
    else
        say "wrote $name"
    fi
    k=$((k + 1))
done
/usr/bin/python3 "$OCCU_ROOT/tools/mesa-patch-table.py"
say "wrote the patch table of docs/mesa.md"
