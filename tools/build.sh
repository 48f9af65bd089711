#!/usr/bin/env bash
# Builds occu: installs what is missing, builds (or reuses) the patched Mesa,
# then configures and builds the meson project in build/.
# Prints the Mesa prefix on stdout; source "<prefix>/occu/env.sh" to run on it.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

"$OCCU_ROOT/tools/deps.sh" "${1:-build}"
prefix=$("$OCCU_ROOT/tools/mesa.sh")
source "$prefix/occu/env.sh"

build=$OCCU_ROOT/build
export PATH=/usr/bin:$PATH   # Debian's meson and python, whatever is first on PATH
if [ ! -f "$build/build.ninja" ] || [ "$(cat "$build/.occu-mesa-prefix" 2>/dev/null)" != "$prefix" ]; then
    say "configuring occu against $prefix"
    # pkg_config_path as an option: meson keeps the PKG_CONFIG_PATH of the first
    # setup across --reconfigure, which would leave the old Mesa's rpath behind.
    if [ -f "$build/build.ninja" ]; then
        meson setup --reconfigure "$build" "$OCCU_ROOT" -Dpkg_config_path="$prefix/lib/pkgconfig" >/dev/null
    else
        meson setup "$build" "$OCCU_ROOT" -Dpkg_config_path="$prefix/lib/pkgconfig" >/dev/null
    fi
    echo "$prefix" > "$build/.occu-mesa-prefix"
fi
say "building occu"
ninja -C "$build" >"$build/ninja.log" 2>&1 || { tail -n 40 "$build/ninja.log" >&2; die "occu build failed (log: $build/ninja.log)"; }
echo "$prefix"
