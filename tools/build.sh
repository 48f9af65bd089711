#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds occu: installs what is missing, builds (or reuses) the patched Mesa,
# then configures and builds the meson project in build/.
# Prints the Mesa prefix on stdout; source "<prefix>/occu/env.sh" to run on it.
# Usage: tools/build.sh [build|test|...]   (the packages tools/deps.sh installs)
# Environment:
#   OCCU_MESA_PREFIX  build against the Mesa installed there (it needs
#                     lib/pkgconfig/osmesa.pc and occu/env.sh, as tools/mesa.sh
#                     and tools/check-mesa-series.sh install it) instead of
#                     building the series with tools/mesa.sh
#   OCCU_BUILD_DIR    the build directory (default: build/ of this tree)
set -euo pipefail
source "$(dirname "$0")/lib.sh"

"$OCCU_ROOT/tools/deps.sh" "${1:-build}"
if [ -n "${OCCU_MESA_PREFIX:-}" ]; then
    [ -f "$OCCU_MESA_PREFIX/occu/env.sh" ] || die "OCCU_MESA_PREFIX=$OCCU_MESA_PREFIX has no occu/env.sh (not a Mesa installed by tools/mesa.sh or tools/check-mesa-series.sh)"
    prefix=$(cd "$OCCU_MESA_PREFIX" && pwd)
else
    prefix=$("$OCCU_ROOT/tools/mesa.sh")
fi
source "$prefix/occu/env.sh"

build=${OCCU_BUILD_DIR:-$OCCU_ROOT/build}
export PATH=/usr/bin:$PATH   # Debian's meson and python, whatever is first on PATH
occu_configure "$build" "$prefix"
say "building occu"
ninja -C "$build" >"$build/ninja.log" 2>&1 || { tail -n 40 "$build/ninja.log" >&2; die "occu build failed (log: $build/ninja.log)"; }
echo "$prefix"
