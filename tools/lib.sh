# SPDX-License-Identifier: MIT
# Shared shell helpers for occu's tools (sourced, not run).
# Everything that is cached lives under $OCCU_CACHE, outside the work tree,
# so that a second run, a CI run or another clone on the same machine reuses it.

OCCU_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OCCU_CACHE=${OCCU_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/occu}

# The Mesa this project patches: Debian 12's source package, pinned.
MESA_UPSTREAM_VERSION=22.3.6
MESA_DEBIAN_VERSION=22.3.6-1+deb12u2

# Debian's own interpreter: it has python3-mako, the first python3 on PATH may not.
SYSTEM_PYTHON=/usr/bin/python3

say()  { printf '\033[1m[occu]\033[0m %s\n' "$*" >&2; }
die()  { printf '\033[1;31m[occu] error:\033[0m %s\n' "$*" >&2; exit 1; }

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi
}

# The build: gallium's software rasterizers only (softpipe, llvmpipe on LLVM 15),
# OSMesa, and EGL (surfaceless is always built with EGL) behind glvnd so that
# unmodified programs linked to libGL/libEGL reach this Mesa, and Mesa's own unit
# tests (tools/test runs those of src/mesa/main: the extension table's order, enum
# strings, formats). Nothing else.
MESA_OPTIONS=(
    --buildtype=release -Db_ndebug=true
    -Dplatforms= -Dgallium-drivers=swrast -Dvulkan-drivers=
    -Dllvm=enabled -Dshared-llvm=enabled -Ddraw-use-llvm=true
    -Dosmesa=true -Degl=enabled -Dglvnd=true -Dglx=disabled -Dgbm=disabled
    -Dgles1=disabled -Dgles2=enabled -Dopengl=true -Dshared-glapi=enabled
    -Ddri3=disabled -Dxlib-lease=disabled
    -Dgallium-vdpau=disabled -Dgallium-va=disabled -Dgallium-xa=disabled
    -Dgallium-omx=disabled -Dgallium-nine=false -Dgallium-opencl=disabled
    -Dgallium-rusticl=false -Dvideo-codecs=
    -Dmicrosoft-clc=disabled -Dintel-clc=disabled -Dspirv-to-dxil=false
    -Dvalgrind=disabled -Dlibunwind=disabled -Dlmsensors=disabled -Dselinux=false
    -Dbuild-tests=true -Dtools=
)

# Writes PREFIX/occu/env.sh, which a shell sources to run programs on the Mesa
# installed in PREFIX, and the glvnd vendor file it names (tools/mesa.sh,
# tools/check-mesa-series.sh). WHAT says which Mesa it is, in env.sh's comment.
# glvnd finds vendors through JSON files; programs are pointed at this one
# (absolute path, so that no system Mesa is picked instead) with
# __EGL_VENDOR_LIBRARY_FILENAMES.
write_mesa_env() {  # PREFIX WHAT
    local prefix=$1 what=$2
    mkdir -p "$prefix/occu"
    cat > "$prefix/occu/egl_vendor.json" <<JSON
{
    "file_format_version" : "1.0.0",
    "ICD" : { "library_path" : "$prefix/lib/libEGL_mesa.so.0" }
}
JSON
    cat > "$prefix/occu/env.sh" <<ENV
# Source this to run programs on occu's Mesa ($what).
export PKG_CONFIG_PATH="$prefix/lib/pkgconfig\${PKG_CONFIG_PATH:+:\$PKG_CONFIG_PATH}"
export LD_LIBRARY_PATH="$prefix/lib\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}"
export LIBGL_DRIVERS_PATH="$prefix/lib/dri"
export __EGL_VENDOR_LIBRARY_FILENAMES="$prefix/occu/egl_vendor.json"
ENV
}

# Configures occu's meson build directory BUILD against the Mesa installed in
# PREFIX, or again when it was configured against another (tools/build.sh;
# tools/check-mesa-series.sh, one build directory per part of the series).
occu_configure() {  # BUILD PREFIX
    local build=$1 prefix=$2
    [ -f "$prefix/lib/pkgconfig/osmesa.pc" ] || die "no Mesa installed in $prefix (no lib/pkgconfig/osmesa.pc)"
    if [ ! -f "$build/build.ninja" ] || [ "$(cat "$build/.occu-mesa-prefix" 2>/dev/null)" != "$prefix" ]; then
        say "configuring occu in $build against $prefix"
        # pkg_config_path as an option: meson keeps the PKG_CONFIG_PATH of the first
        # setup across --reconfigure, which would leave the old Mesa's rpath behind.
        if [ -f "$build/build.ninja" ]; then
            PATH=/usr/bin:$PATH meson setup --reconfigure "$build" "$OCCU_ROOT" \
                -Dpkg_config_path="$prefix/lib/pkgconfig" >/dev/null
        else
            PATH=/usr/bin:$PATH meson setup "$build" "$OCCU_ROOT" \
                -Dpkg_config_path="$prefix/lib/pkgconfig" >/dev/null
        fi
        echo "$prefix" > "$build/.occu-mesa-prefix"
    fi
}
