#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Fetches Debian's Mesa source, applies patches/mesa/series, builds and installs it
# into a cache outside the work tree; prints the install prefix on stdout.
#
# Usage: tools/mesa.sh [--unpatched | --sanitize | --sanitize-all]
#   --unpatched   build the same Mesa with the same options but an empty series
#                 (the reference for patched-vs-unpatched measurements)
#   --sanitize    the patched Mesa with the files the series changes built with
#                 AddressSanitizer and UndefinedBehaviorSanitizer, every other
#                 file as the plain build (tools/sanitizing-compiler: ccache hands
#                 those objects back, so it costs the changed files and the
#                 links). ASan's runtime replaces malloc and the string and memory
#                 functions everywhere; accesses are checked in the changed files.
#                 What tools/test runs the API walk on.
#   --sanitize-all  all of the patched Mesa built with both sanitizers (a cold
#                 build about as long as the plain one; bench/api-walk.sh --all,
#                 which also catches upstream Mesa's own errors on the walk's paths)
# Programs run on a sanitized Mesa with the sanitizers' runtimes in LD_PRELOAD.
#
# Cache layout under $OCCU_CACHE/mesa/<debian version>/:
#   source/                  the unpacked source package, a git repository whose first
#                            commit is pristine; each patch of the series is one commit
#                            on it (git am), as in a merge request's branch
#   source-unpatched/, source-sanitized-all/   work trees of that commit for the other
#                            variants (the sanitized one with the series applied)
#   sanitized/source/, sanitized/build-<options>/   the same for --sanitize, one
#                            level down so that meson spells every source path as the
#                            plain build does (../source/...), which ccache needs
#   build-<options>-<variant>/   meson build dir, reused so that a patch change
#                            rebuilds only what it touches
#   install-<options>-<patches>/ the installed Mesa, one per key; '.complete' marks it done
# The key is the Mesa version, the hash of the build options and the hash of the
# patch series (its 'series' file and every patch it names, in order).
set -euo pipefail
source "$(dirname "$0")/lib.sh"

variant=patched
options=("${MESA_OPTIONS[@]}")
case ${1:-} in
    "") ;;
    --unpatched) variant=unpatched ;;
    --sanitize)
        variant=sanitized
        # Identical compile options to the plain build (the wrapper adds the
        # sanitizers per file); shared libraries may then leave the
        # sanitizers' symbols undefined: the runtime comes from LD_PRELOAD.
        options+=(-Db_lundef=false) ;;
    --sanitize-all)
        variant=sanitized-all
        # Shared libraries with sanitizers: their runtime comes from the program
        # (LD_PRELOAD), so undefined symbols are allowed at link time. GCC 12
        # with ASan reports a null format string in util/log.c that cannot
        # happen (Mesa passes -Werror=format): kept a warning.
        # Mesa's own unit tests are not run on this build (tools/test runs them on
        # the plain one): compiling nir_tests, spirv_tests and the rest under ASan
        # was most of a cold run's time.
        options=("${options[@]/-Dbuild-tests=true/-Dbuild-tests=false}")
        options+=(-Db_sanitize=address,undefined -Db_lundef=false
                  -Dc_args=-Wno-error=format-overflow -Dcpp_args=-Wno-error=format-overflow) ;;
    *) die "tools/mesa.sh: unknown option '$1' (expected --unpatched, --sanitize, --sanitize-all or nothing)" ;;
esac


series_file=$OCCU_ROOT/patches/mesa/series
patches=()
if [ $variant != unpatched ] && [ -f "$series_file" ]; then
    while IFS= read -r line || [ -n "$line" ]; do
        line=${line%%#*}; line=$(echo "$line" | xargs)
        [ -n "$line" ] || continue
        [ -f "$OCCU_ROOT/patches/mesa/$line" ] || die "patches/mesa/series names '$line', which does not exist"
        patches+=("$OCCU_ROOT/patches/mesa/$line")
    done < "$series_file"
fi

wrapper_hash=$(sha256sum "$OCCU_ROOT/tools/sanitizing-compiler" | cut -c1-12)
options_hash=$( { printf '%s\n' "${options[@]}"
                  [ $variant != sanitized ] || echo "sanitize changed files, wrapper $wrapper_hash"; } |
               sha256sum | cut -c1-12)
# The series as it is now, copied: another build of the cache may hold the lock
# below for minutes, and the patches applied after it must be the ones hashed.
snapshot=$(mktemp -d)
trap 'rm -rf "$snapshot"' EXIT
if [ ${#patches[@]} -gt 0 ]; then
    cp "${patches[@]}" "$snapshot/"
    patches=("${patches[@]/#$OCCU_ROOT\/patches\/mesa/$snapshot}")
fi
patches_hash=$( { printf '%s\n' "${patches[@]##*/}"; for p in "${patches[@]}"; do cat "$p"; done; } | sha256sum | cut -c1-12)

top=$OCCU_CACHE/mesa/$MESA_DEBIAN_VERSION
src=$top/source
build=$top/build-$options_hash-$variant
[ $variant != sanitized ] || build=$top/sanitized/build-$options_hash
prefix=$top/install-$options_hash-$patches_hash
if [ $variant = sanitized ]; then
    # meson keeps the compiler's absolute path in the build directory and runs
    # it again when it reconfigures: the wrapper is a copy in the cache, named
    # by its content, which outlives the tree (a clone, a worktree) that
    # configured the build. cc and c++, as meson names them for the plain
    # build: ccache's key holds the compiler's name.
    wrapper=$top/sanitized/sanitizing-compiler-$wrapper_hash
    if [ ! -x "$wrapper" ]; then
        mkdir -p "$top/sanitized"
        cp "$OCCU_ROOT/tools/sanitizing-compiler" "$wrapper.tmp.$$" && chmod 755 "$wrapper.tmp.$$" &&
            mv "$wrapper.tmp.$$" "$wrapper"
    fi
    export CC="$wrapper cc" CXX="$wrapper c++"
fi

if [ -f "$prefix/.complete" ]; then
    echo "$prefix"; exit 0
fi

mkdir -p "$top"
# One build at a time per variant (each has its own tree and build dir);
# others wait, then reuse. The fetch below has a lock of its own.
exec 9>"$top/.lock-$variant"
flock 9
if [ -f "$prefix/.complete" ]; then
    echo "$prefix"; exit 0
fi

"$OCCU_ROOT/tools/deps.sh" build

# --- fetch: Debian's source package at the pinned version -----------------------------
exec 8>"$top/.lock-fetch"
flock 8
if [ ! -f "$src/.occu-pristine" ]; then
    dl=$OCCU_CACHE/mesa/download
    mkdir -p "$dl"
    apt_version=$(apt-cache showsrc mesa 2>/dev/null | sed -n 's/^Version: //p' | sort -V | tail -n1)
    [ -n "$apt_version" ] || die "apt knows no source package 'mesa' (is there a deb-src entry? run 'apt-get update')"
    if [ "$apt_version" != "$MESA_DEBIAN_VERSION" ]; then
        die "apt would fetch mesa $apt_version, but occu is pinned to $MESA_DEBIAN_VERSION (tools/lib.sh). \
Check that patches/mesa still applies to $apt_version, then change MESA_DEBIAN_VERSION."
    fi
    say "fetching Debian's mesa $MESA_DEBIAN_VERSION source package"
    (cd "$dl" && apt-get source -qq --download-only "mesa=$MESA_DEBIAN_VERSION" 2>&1 | grep -v 'unsandboxed' >&2 || true)
    dsc=$dl/mesa_$MESA_DEBIAN_VERSION.dsc
    [ -f "$dsc" ] || die "apt-get source did not produce $dsc"
    rm -rf "$src" "$src.tmp"
    say "unpacking (Debian's own patches applied)"
    dpkg-source --no-check -x "$dsc" "$src.tmp" >/dev/null
    (cd "$src.tmp" && git init -q && git add -A -f . && \
        git -c user.name=occu -c user.email=occu@localhost commit -q -m "Debian mesa $MESA_DEBIAN_VERSION, pristine")
    echo "$MESA_DEBIAN_VERSION" > "$src.tmp/.git/occu-version"
    mv "$src.tmp" "$src"
    touch "$src/.occu-pristine"
fi
flock -u 8

# The unpatched and sanitized variants build from work trees of their own,
# made from the pristine commit, so that building one variant never touches
# the files of another's build, nor a Mesa developer's edits in source/.
if [ $variant != patched ]; then
    tree=$top/source-$variant
    [ $variant != sanitized ] || tree=$top/sanitized/source
    if [ ! -d "$tree" ]; then
        mkdir -p "${tree%/*}"
        git -C "$src" worktree add -q --detach "$tree" "$(git -C "$src" rev-list --max-parents=0 HEAD)"
    fi
    src=$tree
fi

# --- patch: reset the tree to pristine, commit the series on it in order ---------------
# One commit per patch, author, date and message taken from the patch (git am), so
# that tools/export-mesa-patches.sh gets the series back with git format-patch.
applied=$(cat "$src/.occu-applied" 2>/dev/null || true)
if [ "$applied" != "$patches_hash" ]; then
    say "applying patches/mesa/series (${#patches[@]} patches)"
    pristine=$(git -C "$src" rev-list --max-parents=0 HEAD)
    (cd "$src" && { git am --abort >/dev/null 2>&1 || true; } && git reset -q --hard "$pristine" &&
        git clean -q -fd -e .occu-pristine -e .occu-applied)
    rm -f "$src/.occu-applied"
    for p in "${patches[@]}"; do
        if ! (cd "$src" && GIT_COMMITTER_NAME=occu GIT_COMMITTER_EMAIL=occu@localhost \
                git am -q --whitespace=nowarn --committer-date-is-author-date "$p" 2>&1 >&2); then
            (cd "$src" && git am --abort >/dev/null 2>&1 || true)
            die "patch ${p#$OCCU_ROOT/} does not apply to mesa $MESA_DEBIAN_VERSION"
        fi
    done
    echo "$patches_hash" > "$src/.occu-applied"
fi

# --- build and install --------------------------------------------------------------
# Mesa's generators need mako, which Debian's python has; put /usr/bin first so that
# meson's find_installation('python3') picks it.
export PATH=/usr/bin:$PATH
export CCACHE_DIR=${CCACHE_DIR:-$OCCU_CACHE/ccache}
if [ ! -f "$build/build.ninja" ]; then
    say "configuring Mesa (options $options_hash, $variant)"
    rm -rf "$build"
    meson setup "$build" "$src" --prefix="$prefix" --libdir=lib "${options[@]}" >"$top/configure-$variant.log" 2>&1 \
        || { tail -n 30 "$top/configure-$variant.log" >&2; die "Mesa's meson setup failed (log: $top/configure-$variant.log)"; }
else
    meson configure "$build" --prefix="$prefix" >/dev/null
fi
if [ $variant = sanitized ]; then
    # The files tools/sanitizing-compiler instruments: the series' C and C++
    # sources, as meson names them (relative to the build directory).
    git -C "$src" diff --name-only "$(git -C "$src" rev-list --max-parents=0 HEAD)" HEAD -- '*.c' '*.cpp' |
        sed 's|^|../source/|' >"$build/occu-sanitize-sources"
    [ -s "$build/occu-sanitize-sources" ] || die "the series changes no C source to sanitize"
fi
say "building Mesa into $prefix (log: $top/build-$variant.log)"
start=$(date +%s)
# What is installed, and of Mesa's own tests only main_test (tools/test runs
# it from the plain build): nir_tests, spirv_tests, util_tests and the rest
# are about a tenth of the build's objects and some of its slowest to compile.
mapfile -t targets < <(meson introspect --targets "$build" | /usr/bin/python3 -c '
import json, os, sys
build, variant = sys.argv[1:]
for t in json.load(sys.stdin):
    if t["installed"] or (t["name"] == "main_test" and variant == "patched"):
        for f in t["filename"]:
            print(os.path.relpath(f, build))' "$build" $variant)
[ ${#targets[@]} -gt 0 ] || die "meson lists no installed targets in $build"
if ! { ninja -C "$build" "${targets[@]}" && meson install -C "$build" --no-rebuild --quiet; } \
        >"$top/build-$variant.log" 2>&1; then
    grep -E 'error|FAILED' "$top/build-$variant.log" | head -n 30 >&2
    die "Mesa build failed (log: $top/build-$variant.log)"
fi

# Mesa's own unit tests of src/mesa/main (extension table order, enum strings,
# formats), kept with the install they were built with: tools/test runs them.
mkdir -p "$prefix/occu/tests"
if [ -x "$build/src/mesa/main/tests/main_test" ]; then
    cp "$build/src/mesa/main/tests/main_test" "$prefix/occu/tests/mesa_main_test"
fi

write_mesa_env "$prefix" "$variant, series $patches_hash"
touch "$prefix/.complete"
say "Mesa built in $(( $(date +%s) - start ))s"
echo "$prefix"
