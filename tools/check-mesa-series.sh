#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Developer tool: checks patches/mesa/series as a merge request's patches are
# checked, part by part.
#
# The series comes in parts, one per extension, each opened by a comment line
# of patches/mesa/series:
#     # part SUITE: WHAT
# e.g. '# part async: GL_MESAX_occlusion_unit_async'. SUITE is the meson test
# suite (tests/meson.build) of the tests that need the part; the first part's
# SUITE only names it. Patches before the first such line belong to a part
# 'base'.
#
# 1. Each patch builds on the ones before it: for k = 1..N, the pristine source
#    with patches 1..k applied (patch k applied to the tree of step k-1) is built with the options of tools/mesa.sh, in a
#    work tree and build directory of their own (not installed).
# 2. Each part passes the extension's tests on the parts before it alone: at
#    the last patch of a part, that build is installed into a prefix of its
#    own (<cache>/mesa/<version>/install-series-check-SUITE), occu's
#    piglit-style test programs are built against it in a build directory of
#    their own (build-series-check-SUITE/ in this tree) and run on softpipe and
#    llvmpipe with
#        meson test --suite piglit --no-suite S...
#    S being the suites of the parts after it: after the base part its tests
#    alone, after the last part every one.
# 0. Before building, the lines a patch adds that a later patch deletes or
#    rewrites (tools/series-churn.py), as one line:
#        series churn: N of M added lines deleted or rewritten by a later patch
# Prints one line per patch and one per part:
#     part SUITE (WHAT, patches I-J): N passed, N failed, N skipped, N known
# Exits non-zero at the first patch that does not apply or build, and at the
# end when a part's tests did not all pass or skip. The lines of the tests that
# failed are printed before the part's line; the whole log is in the part's
# build directory (meson-logs/testlog.txt).
# Run tools/mesa.sh once first (it fetches the source). One check at a time
# per cache (a lock): the work tree, build directory and prefixes are shared.
# Usage: tools/check-mesa-series.sh
set -euo pipefail
source "$(dirname "$0")/lib.sh"

top=$OCCU_CACHE/mesa/$MESA_DEBIAN_VERSION
[ -f "$top/source/.occu-pristine" ] || die "no Mesa source at $top/source (run tools/mesa.sh first)"
options_hash=$(printf '%s\n' "${MESA_OPTIONS[@]}" | sha256sum | cut -c1-12)
src=$top/source-series-check
build=$top/build-$options_hash-series-check

exec 9>"$top/.lock-series-check"
flock 9

# --- the series and its parts ------------------------------------------------------
patches=()      # paths, in order
patch_part=()   # the part of each patch (an index into the next two)
part_suite=()
part_what=()
last_part=-1    # the part of the last patch read
series=$OCCU_ROOT/patches/mesa/series
while IFS= read -r line || [ -n "$line" ]; do
    if [[ $line =~ ^#[[:space:]]*part[[:space:]]+([A-Za-z0-9_-]+):[[:space:]]*(.*[^[:space:]])[[:space:]]*$ ]]; then
        [ ${#part_suite[@]} -eq 0 ] || [ $last_part -eq $((${#part_suite[@]} - 1)) ] ||
            die "$series: part '${part_suite[-1]}' has no patches"
        for s in "${part_suite[@]}"; do
            [ "$s" != "${BASH_REMATCH[1]}" ] || die "$series: two parts named '$s'"
        done
        part_suite+=("${BASH_REMATCH[1]}")
        part_what+=("${BASH_REMATCH[2]}")
        continue
    fi
    line=${line%%#*}; line=$(echo "$line" | xargs)
    [ -n "$line" ] || continue
    [ -f "$OCCU_ROOT/patches/mesa/$line" ] || die "$series names '$line', which does not exist"
    if [ ${#part_suite[@]} -eq 0 ]; then
        part_suite+=(base); part_what+=("the series")
    fi
    last_part=$((${#part_suite[@]} - 1))
    patches+=("$OCCU_ROOT/patches/mesa/$line")
    patch_part+=("$last_part")
done < "$series"
[ ${#patches[@]} -gt 0 ] || die "$series names no patch"
[ $last_part -eq $((${#part_suite[@]} - 1)) ] || die "$series: part '${part_suite[-1]}' has no patches"

# --- 2. a part's tests, on the build of its last patch ---------------------------------
part_failed=0
check_part() {  # PART FIRST_PATCH LAST_PATCH (1-based)
    local p=$1 first=$2 last=$3
    local suite=${part_suite[p]}
    local prefix=$top/install-series-check-$suite
    local occu_build=$OCCU_ROOT/build-series-check-$suite

    say "part $suite: installing Mesa with patches 1-$last into $prefix"
    rm -rf "$prefix"
    meson configure "$build" --prefix="$prefix" >/dev/null
    ninja -C "$build" install >"$build.install-$suite.log" 2>&1 ||
        die "part $suite: Mesa does not install (log: $build.install-$suite.log)"
    write_mesa_env "$prefix" "tools/check-mesa-series.sh: patches 1-$last of the series, part $suite"

    # Only the programs the piglit-style tests run: the rest of occu does not
    # depend on the part (and meson test --no-rebuild below builds nothing).
    occu_configure "$occu_build" "$prefix"
    # A build directory left by an earlier check is regenerated first, so that
    # the tests tests/meson.build declares now are the ones listed and run.
    ninja -C "$occu_build" build.ninja >"$occu_build/regenerate.log" 2>&1 ||
        die "part $suite: $occu_build does not regenerate (log: $occu_build/regenerate.log)"
    local programs
    programs=$(meson introspect --tests "$occu_build" | /usr/bin/python3 -c '
import json, os, sys
build = os.path.realpath(sys.argv[1])
programs = set()
for t in json.load(sys.stdin):
    if "piglit" in [s.split(":")[-1] for s in t["suite"]]:
        programs.add(os.path.relpath(os.path.realpath(t["cmd"][0]), build))
print("\n".join(sorted(programs)))' "$occu_build")
    [ -n "$programs" ] || die "part $suite: $occu_build declares no piglit-style test"
    # shellcheck disable=SC2086
    ninja -C "$occu_build" $programs >"$occu_build/ninja.log" 2>&1 ||
        { tail -n 40 "$occu_build/ninja.log" >&2; die "part $suite: occu's tests do not build (log: $occu_build/ninja.log)"; }

    local selection=(--suite piglit) later
    for later in "${part_suite[@]:p+1}"; do
        selection+=(--no-suite "$later")
    done
    say "part $suite: meson test ${selection[*]}"
    local status=0
    (source "$prefix/occu/env.sh" &&
     meson test -C "$occu_build" --no-rebuild --num-processes "$(nproc)" "${selection[@]}" >/dev/null 2>&1) ||
        status=$?
    local counts result
    counts=$(/usr/bin/python3 "$OCCU_ROOT/tools/count-results.py" meson "$occu_build" "$status" "${selection[@]}")
    grep -E '^FAIL ' <<<"$counts" >&2 || true
    result=$(tail -n 1 <<<"$counts")
    if [[ $result =~ ^meson:\ ([0-9]+)\ passed,\ ([0-9]+)\ failed ]] && [ "${BASH_REMATCH[1]}" -gt 0 ] &&
       [ "${BASH_REMATCH[2]}" -eq 0 ]; then
        :
    else
        part_failed=1
    fi
    say "part $suite (${part_what[p]}, patches $first-$last): ${result#meson: }"
}

# --- 0. lines a patch adds that a later patch takes out again --------------------------
# Printed, not checked: a series that shows its final design keeps this near 0
# (tools/series-churn.py --verbose lists the lines).
/usr/bin/python3 "$OCCU_ROOT/tools/series-churn.py" "$top/source" | tail -n 1 | while read -r line; do say "$line"; done

# --- 1. each patch on the ones before it ----------------------------------------------
pristine=$(git -C "$top/source" rev-list --max-parents=0 HEAD)
[ -d "$src" ] || git -C "$top/source" worktree add -q --detach "$src" "$pristine"

export PATH=/usr/bin:$PATH
export CCACHE_DIR=${CCACHE_DIR:-$OCCU_CACHE/ccache}
part_first=1
# The tree goes from pristine through each patch in turn, so that a step
# touches only the files of its patch and ninja rebuilds what depends on them,
# not every file some patch of the series changes.
(cd "$src" && git checkout -q --detach "$pristine" && git reset -q --hard && git clean -q -fdx)
for k in "${!patches[@]}"; do
    (cd "$src" && git apply --whitespace=nowarn "${patches[k]}") ||
        die "${patches[k]##*/} does not apply on the patches before it"
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
    if [ $((k + 1)) -eq ${#patches[@]} ] || [ "${patch_part[k+1]}" != "${patch_part[k]}" ]; then
        check_part "${patch_part[k]}" "$part_first" $((k + 1))
        part_first=$((k + 2))
    fi
done
[ $part_failed -eq 0 ] || die "a part of the series fails its tests (the 'part' lines above)"
say "every patch of the series builds on the ones before it, and every part passes its tests"
