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
