#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs the Debian packages occu needs, only those that are missing.
# Usage: tools/deps.sh [build|demo|test|bench|piglit|all]   (default: all)
set -euo pipefail
source "$(dirname "$0")/lib.sh"

# To build Mesa (gallium swrast, OSMesa, EGL surfaceless with glvnd) and occu.
BUILD_PACKAGES=(
    dpkg-dev            # apt-get source unpacks with dpkg-source
    git                 # the Mesa tree is a git repository (pristine commit, worktrees)
    meson ninja-build pkg-config ccache
    python3-mako        # for /usr/bin/python3, which runs Mesa's generators
    flex bison
    llvm-15-dev         # llvmpipe's JIT
    libdrm-dev libelf-dev zlib1g-dev libzstd-dev libexpat1-dev
    libglvnd-dev libglvnd-core-dev
    g++ libglm-dev libgtest-dev libpng-dev
    libassimp-dev       # user scenes (OBJ, glTF)
    libzip-dev          # Quake III levels inside pk3 archives (src/scene/pk3_archive.cpp)
    libstb-dev          # stb_image: a level's JPEG and TGA textures for its look (src/scene/quake3_look.cpp)
    libcgal-dev libpolyclipping-dev   # view cells (constrained Delaunay) and occluder shrinking (polygon offsets)
)
# To run the piglit regression run on the patched driver.
TEST_PACKAGES=(
    piglit
    assimp-testmodels   # real models the demos must refuse (BoxWithInfinites.glb: infinite vertices)
    openarena-data openarena-088-data   # Quake III levels (pk3 archives of IBSP files) the BSP reader's tests load
    clang libclang-rt-14-dev   # the fuzz targets: libFuzzer and the sanitizers' runtimes (tools/fuzz)
    chromium            # headless, renders the walkthrough's report page in its test (walkthrough-report.sh)
    # view-cells-slurm.sh starts a single-node Slurm cluster of its own (munged, slurmctld,
    # slurmd) to run tools/slurm/preprocess-view-cells.sh, and runs the GNU parallel script
    slurm-wlm slurmctld slurmd slurm-client munge parallel
)
# To plot the walkthrough's frames (tools/plot-walkthrough.sh; tools/demo and
# its test) and the benches' results, and to make the video of its route.
DEMO_PACKAGES=(
    gnuplot-nox
    ffmpeg              # tools/video-walkthrough.sh (tools/demo and its test)
)
# To build a piglit source tree with occu's tests in it and run them with its
# own runner (tools/check-in-piglit.sh); not needed by tools/test.
PIGLIT_PACKAGES=(
    cmake
    libwaffle-dev       # piglit's GL framework makes its contexts through waffle
    python3-numpy       # piglit's CMake requires it (its generated tests)
    python3-mako        # piglit's dispatch and profile generators
)
# To count instructions in benchmarks (wall time on shared machines is noisy).
BENCH_PACKAGES=(
    valgrind
)

what=${1:-all}
case $what in
    build) wanted=("${BUILD_PACKAGES[@]}") ;;
    demo) wanted=("${BUILD_PACKAGES[@]}" "${DEMO_PACKAGES[@]}") ;;
    test) wanted=("${BUILD_PACKAGES[@]}" "${TEST_PACKAGES[@]}" "${DEMO_PACKAGES[@]}") ;;
    bench) wanted=("${BUILD_PACKAGES[@]}" "${DEMO_PACKAGES[@]}" "${BENCH_PACKAGES[@]}") ;;
    piglit) wanted=("${BUILD_PACKAGES[@]}" "${PIGLIT_PACKAGES[@]}") ;;
    all) wanted=("${BUILD_PACKAGES[@]}" "${TEST_PACKAGES[@]}" "${DEMO_PACKAGES[@]}" "${BENCH_PACKAGES[@]}" "${PIGLIT_PACKAGES[@]}") ;;
    *) die "tools/deps.sh: unknown argument '$what' (expected build, demo, test, bench, piglit or all)" ;;
esac

# apt-get source needs a deb-src entry; derive one from the deb entries when none exists.
ensure_deb_src() {
    if grep -rqsE '^(Types:.*deb-src|deb-src )' /etc/apt/sources.list /etc/apt/sources.list.d/; then
        return 1
    fi
    local src=/etc/apt/sources.list.d/debian.sources
    [ -f "$src" ] || die "no deb-src entry and no $src to derive one from; add a deb-src line for Debian bookworm by hand"
    say "adding a deb-src entry derived from $src"
    sed -e 's/^Types:.*/Types: deb-src/' "$src" | as_root tee /etc/apt/sources.list.d/occu-deb-src.sources >/dev/null
    return 0
}

missing=()
for p in "${wanted[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done

need_update=0
ensure_deb_src && need_update=1
# A fresh machine has empty package lists.
compgen -G '/var/lib/apt/lists/*_Packages*' >/dev/null || need_update=1
compgen -G '/var/lib/apt/lists/*_Sources*' >/dev/null || need_update=1
[ ${#missing[@]} -gt 0 ] && need_update=1
if [ $need_update = 1 ]; then
    say "apt-get update"
    as_root apt-get update -qq
fi
if [ ${#missing[@]} -gt 0 ]; then
    say "installing: ${missing[*]}"
    as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
