#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Benchmark of the Occlusion Unit against ARB_occlusion_query, and of
# GL_RENDER on patched vs unpatched Mesa (same build options), in one run.
# Usage: bench/occlusion-unit.sh [softpipe|llvmpipe] [ROUNDS]
# Prints a markdown table of medians and ratios; nothing here is a test.
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"

driver=${1:-softpipe}
rounds=${2:-5}
patched=$("$OCCU_ROOT/tools/build.sh" bench)
unpatched=$("$OCCU_ROOT/tools/mesa.sh" --unpatched)
bench=$OCCU_ROOT/build/bench/occu-bench-ou

run_on() {  # prefix, args...
    local prefix=$1; shift
    LD_LIBRARY_PATH=$prefix/lib GALLIUM_DRIVER=$driver "$bench" --driver "$driver" "$@"
}

echo "## Occlusion Unit vs ARB_occlusion_query ($driver, 256x256, medians of 15)"
echo
echo "| case | N | brief pass (ms) | ARB queries (ms) | ratio |"
echo "|---|---|---|---|---|"
run_on "$patched" box tiles:1 tiles:4 tiles:16 tiles:64 mesh:1 mesh:16 vmesh:1 vmesh:16 |
    awk -F, '{printf "| %s | %s | %.3f | %.3f | %.3f |\n", $1, $4, $5, $6, $7}'

# Instructions of one brief pass vs one ARB query of the box (callgrind, one
# rasterizer thread): each variant alone, minus a run with a tenth of the
# iterations, which removes start-up and shader compilation.
box_instructions() {  # variant repeat
    LD_LIBRARY_PATH=$patched/lib GALLIUM_DRIVER=$driver LP_NUM_THREADS=0 valgrind --tool=callgrind \
        --callgrind-out-file=/dev/null "$bench" --driver "$driver" --only "$1" --repeat "$2" box 2>&1 |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
ou=$(( ($(box_instructions 0 15) - $(box_instructions 0 1)) / 280 ))
arb=$(( ($(box_instructions 1 15) - $(box_instructions 1 1)) / 280 ))
echo
echo "Instructions per box test (callgrind, LP_NUM_THREADS=0): brief pass $ou, ARB query $arb," \
     "ratio $(/usr/bin/python3 -c "print(f'{$ou / $arb:.3f}')")"

echo
echo "## A brief pass over a heavily shaded object vs drawing it ($driver)"
echo
echo "| case | brief pass (ms) | GL_RENDER draw (ms) | ratio |"
echo "|---|---|---|---|"
run_on "$patched" shaded | awk -F, '{printf "| %s | %.3f | %.3f | %.3f |\n", $1, $5, $6, $7}'

if [ "$driver" = llvmpipe ]; then
    echo
    echo "## Brief passes per second by rasterizer threads (16 tiles over the 20k-triangle mesh)"
    echo
    echo "| LP_NUM_THREADS | ms per pass | passes/s |"
    echo "|---|---|---|"
    for t in 1 2 4 8; do
        LP_NUM_THREADS=$t run_on "$patched" passes | awk -F, '{printf "| %s | %.3f | %.1f |\n", $4, $5, $6}'
    done
fi

echo
echo "## GL_RENDER frame, patched vs unpatched Mesa ($driver, $rounds alternating rounds)"
echo
# Wall time on a shared machine is noisy, so the script also counts the
# instructions of the frame loop with callgrind, which repeats exactly.
# One rasterizer thread (LP_NUM_THREADS=0): callgrind then sees all the work
# in the thread that runs the frame loop, and the count repeats exactly.
instructions() {  # prefix
    LD_LIBRARY_PATH=$1/lib GALLIUM_DRIVER=$driver LP_NUM_THREADS=0 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        --toggle-collect='*case_render*' "$bench" --driver "$driver" --repeat 1 render 2>&1 |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
p=(); u=()
for ((r = 0; r < rounds; r++)); do
    p+=("$(run_on "$patched" --repeat 5 render | cut -d, -f5)")
    u+=("$(run_on "$unpatched" --repeat 5 render | cut -d, -f5)")
done
ip=$(instructions "$patched"); iu=$(instructions "$unpatched")
/usr/bin/python3 - "${p[*]}" "${u[*]}" "$ip" "$iu" <<'PY'
import statistics, sys
p = [float(x) for x in sys.argv[1].split()]
u = [float(x) for x in sys.argv[2].split()]
ip, iu = int(sys.argv[3]), int(sys.argv[4])
print("| Mesa | frame (ms), min | median | instructions (2 frames, callgrind) |")
print("|---|---|---|---|")
print(f"| patched | {min(p):.2f} | {statistics.median(p):.2f} | {ip:,} |")
print(f"| unpatched | {min(u):.2f} | {statistics.median(u):.2f} | {iu:,} |")
print(f"\npatched / unpatched: min time {min(p) / min(u):.3f}, median time "
      f"{statistics.median(p) / statistics.median(u):.3f}, instructions {ip / iu:.4f}")
PY
