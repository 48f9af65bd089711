#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Where one strategy's frames spend their time, by wall clock: the walkthrough
# under `perf record` (the software clock, cpu-clock: no hardware counters
# needed), then the samples per symbol of occu's own code and libc from the
# first frame on (the samples before the first sample in FIRST, default
# `occu::render_hierarchy`, the frames' drawing, are the program's setup: the
# scene, the hierarchy, the skins). Instruction counts (callgrind) say what
# code runs; this says where the time goes, cache and TLB misses included.
# libc's samples include GL's own (llvmpipe's draws and the frame's read-back
# call malloc, free and memmove); `perf record --call-graph dwarf` tells them
# apart from the strategy's.
# The strategy's line of the walkthrough's table is printed first; with
# `--clock thread` among the walkthrough's arguments its setup and test ms
# are the main thread's CPU time (less moved by other work on the machine).
# Usage: bench/perf-frames.sh STRATEGY [WALKTHROUGH ARGS...]
# Environment: OCCU_BUILD_DIR (default build/), FIRST, TOP (rows, 40),
#   GALLIUM_DRIVER (llvmpipe), OUT (perf's data and the walkthrough's output,
#   default a temporary directory, removed).
# Example: bench/perf-frames.sh skins-triangles --route dense --frames 60
set -euo pipefail
source "$(dirname "$0")/../tools/lib.sh"
[ $# -ge 1 ] || die "usage: bench/perf-frames.sh STRATEGY [WALKTHROUGH ARGS...]"
command -v perf >/dev/null || die "perf is not installed (apt-get install linux-perf)"
strategy=$1; shift
build=${OCCU_BUILD_DIR:-$OCCU_ROOT/build}
[ -x "$build/demos/walkthrough" ] || die "$build/demos/walkthrough is not built (tools/build.sh)"
first=${FIRST:-occu::render_hierarchy}
out=${OUT:-}
if [ -z "$out" ]; then out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
mkdir -p "$out"
GALLIUM_DRIVER=${GALLIUM_DRIVER:-llvmpipe} perf record -q -e cpu-clock -F 10000 -o "$out/perf.data" \
    "$build/demos/walkthrough" "$@" --strategies "$strategy" --oracle off --png-every 0 --report off \
    --out "$out/walkthrough" >"$out/walkthrough.log" 2>&1 || { tail -n 20 "$out/walkthrough.log" >&2; die "the walkthrough failed"; }
grep -m1 -- "^$strategy " "$out/walkthrough.log" >&2 || true
from=$(perf script -i "$out/perf.data" -F time,ip,sym 2>/dev/null | grep -m1 -F " $first" | awk '{print $1}' | tr -d :) || true
[ -n "$from" ] || die "no sample in $first: nothing to start from (FIRST=SYMBOL)"
perf report -i "$out/perf.data" --time "$from," --no-children -n --sort dso,symbol 2>/dev/null |
    grep -v '^#' | grep -v '^$' | grep -F -e 'walkthrough' -e 'libc' |
    awk '{s = $5; for (i = 6; i <= NF && $i != "-"; i++) s = s " " $i; printf "%6d  %s\n", $2, s}' | head -n "${TOP:-40}" || true
