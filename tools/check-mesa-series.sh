#!/usr/bin/env bash
# Developer tool: checks that each patch of patches/mesa/series builds on its
# own, in order, as a merge request's patches must: for k = 1..N, the pristine
# source with patches 1..k applied is built (not installed) with the options
# of tools/mesa.sh, in a work tree and build directory of its own.
# Run tools/mesa.sh once first (it fetches the source). Prints one line per
# patch; exits non-zero at the first patch that does not apply or build.
# Usage: tools/check-mesa-series.sh
set -euo pipefail
source "$(dirname "$0")/lib.sh"

top=$OCCU_CACHE/mesa/$MESA_DEBIAN_VERSION
[ -f "$top/source/.occu-pristine" ] || die "no Mesa source at $top/source (run tools/mesa.sh first)"
options_hash=$(printf '%s\n' "${MESA_OPTIONS[@]}" | sha256sum | cut -c1-12)
src=$top/source-series-check
build=$top/build-$options_hash-series-check
pristine=$(git -C "$top/source" rev-list --max-parents=0 HEAD)
[ -d "$src" ] || git -C "$top/source" worktree add -q --detach "$src" "$pristine"

patches=()
while IFS= read -r line || [ -n "$line" ]; do
    line=${line%%#*}; line=$(echo "$line" | xargs)
    [ -n "$line" ] && patches+=("$OCCU_ROOT/patches/mesa/$line")
done < "$OCCU_ROOT/patches/mesa/series"

export PATH=/usr/bin:$PATH
export CCACHE_DIR=${CCACHE_DIR:-$OCCU_CACHE/ccache}
for k in "${!patches[@]}"; do
    (cd "$src" && git checkout -q --detach "$pristine" && git reset -q --hard && git clean -q -fdx)
    for p in "${patches[@]:0:k+1}"; do
        (cd "$src" && git apply --whitespace=nowarn "$p") || die "${p##*/} does not apply on the patches before it"
    done
    if [ ! -f "$build/build.ninja" ]; then
        meson setup "$build" "$src" --prefix="$top/install-series-check" --libdir=lib "${MESA_OPTIONS[@]}" \
            >"$build.configure.log" 2>&1 || die "meson setup failed (log: $build.configure.log)"
    fi
    if ninja -C "$build" >"$build.log" 2>&1; then
        say "$((k + 1))/${#patches[@]} ${patches[k]##*/}: builds"
    else
        grep -E 'error|FAILED' "$build.log" | head -n 20 >&2
        die "$((k + 1))/${#patches[@]} ${patches[k]##*/}: does not build with the patches before it (log: $build.log)"
    fi
done
say "every patch of the series builds on the ones before it"
