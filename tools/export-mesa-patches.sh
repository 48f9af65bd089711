#!/usr/bin/env bash
# Developer tool: after editing Mesa in the cache's source tree (the tree
# tools/mesa.sh patched), writes the changes back into patches/mesa/.
# Each patch keeps its header and the files it already touches; a changed
# file that no patch touches is reported, not guessed.
# Usage: tools/export-mesa-patches.sh
set -euo pipefail
source "$(dirname "$0")/lib.sh"

src=$OCCU_CACHE/mesa/$MESA_DEBIAN_VERSION/source
[ -d "$src/.git" ] || die "no Mesa source tree at $src (run tools/mesa.sh first)"
cd "$src"
git add -N src docs include 2>/dev/null || true

claimed=()
while IFS= read -r name || [ -n "$name" ]; do
    name=${name%%#*}; name=$(echo "$name" | xargs)
    [ -n "$name" ] || continue
    patch=$OCCU_ROOT/patches/mesa/$name
    mapfile -t files < <(sed -n 's|^diff --git a/\([^ ]*\) b/.*|\1|p' "$patch")
    [ ${#files[@]} -gt 0 ] || die "$name touches no file; edit it by hand"
    header=$(sed -n '/^diff --git /q;p' "$patch")
    { printf '%s\n\n' "$header"; git diff -- "${files[@]}"; } > "$patch.new"
    mv "$patch.new" "$patch"
    claimed+=("${files[@]}")
    say "wrote $name (${#files[@]} files)"
done < "$OCCU_ROOT/patches/mesa/series"

mapfile -t changed < <(git diff --name-only)
for f in "${changed[@]}"; do
    printf '%s\n' "${claimed[@]}" | grep -qxF "$f" || say "warning: $f changed but no patch touches it"
done
