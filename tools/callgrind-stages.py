#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Developer tool: instructions per frame by stage, from two callgrind runs
of the same command that differ only in their frame count.

Usage: tools/callgrind-stages.py SHORT.out LONG.out FRAMES
  SHORT.out, LONG.out  callgrind outputs of N and N + FRAMES frames
Prints a Markdown table: per stage, the exclusive instructions of its
functions in LONG less those in SHORT, over FRAMES, in millions, and the
stage's share. Functions are grouped by name and object (llvmpipe's JIT
code has neither a name nor an object), as docs/occlusion-unit-llvmpipe.md's
per-stage tables are.
"""
import re
import subprocess
import sys

STAGES = [
    ("JIT code (fragment and vertex shaders)", lambda f, o: o == "???"),
    ("occu library and program", lambda f, o: "/build" in o),
    ("libc", lambda f, o: "libc.so" in o or "libgcc" in o or "libstdc++" in o or "libm.so" in o),
    ("LLVM (compiling shaders)", lambda f, o: "libLLVM" in o),
    ("llvmpipe coarse depth test and bin drops (bounds, plane, decisions)",
     lambda f, o: re.match(r"(build16|build_bin|rejected_over_bin|rejects|rejects_range|whole16_rejected|"
                           r"decide|set_plane|minmax_\w+|run_jit|open_pass|lp_occlusion_coarse_\w+)$", f)),
    ("llvmpipe occlusion unit bookkeeping (sums, block counts, folds)",
     lambda f, o: re.match(r"(lp_occlusion_unit_\w+|fold_\w+|u_occlusion_\w+|lp_occlusion_pass_\w+)$", f)),
    ("llvmpipe rasterizer (triangle walk, block dispatch, clears)",
     lambda f, o: re.match(r"(lp_rast_\w+|block_full_\w+|rasterize_\w+|util_fill_\w+|do_block_\w+|"
                           r"checked_rasterize_bin|thread_function|lp_linear_\w+|lp_fs_linear_\w+)$", f)),
    ("llvmpipe setup and binning",
     lambda f, o: re.match(r"(lp_setup_\w+|do_triangle_ccw|triangle_\w+|lp_scene_\w+|try_update_scene_state|"
                           r"set_scene_state|begin_binning|execute_clears|lp_setup|setup_\w+|retry_\w+|"
                           r"calc_\w+|subpixel_snap|lp_rect_cw)$", f)),
    ("draw module (vertex fetch, shading, clipping)",
     lambda f, o: re.match(r"(draw_\w+|vbuf_\w+|\w*clip\w*|cull_tri|interp|pipe_run_linear|"
                           r"fetch_\w+|llvm_middle_end_\w+|vsplit_\w+|emit\w*|fse_\w+|"
                           r"util_format_\w+|tri|point|line)$", f)),
    ("Mesa, state tracker, llvmpipe context", lambda f, o: "libOSMesa" in o or "mesa" in o),
]


def functions(path):
    text = subprocess.run(["callgrind_annotate", "--threshold=100", path],
                          capture_output=True, text=True, check=True).stdout
    out = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \([ \d.]+%\)\s+(\S+):(.*?) \[(.*)\]\s*$", line)
        if not m:
            continue
        count = int(m.group(1).replace(",", ""))
        name = re.sub(r"\(.*", "", m.group(3)).strip() or m.group(3)
        key = (m.group(2), name, m.group(4))
        out[key] = out.get(key, 0) + count
    return out


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    short, long_, frames = functions(sys.argv[1]), functions(sys.argv[2]), int(sys.argv[3])
    totals = {name: 0.0 for name, _ in STAGES}
    totals["other"] = 0.0
    for key in set(short) | set(long_):
        diff = (long_.get(key, 0) - short.get(key, 0)) / frames
        _, name, obj = key
        for stage, rule in STAGES:
            if rule(name, obj):
                totals[stage] += diff
                break
        else:
            totals["other"] += diff
    total = sum(totals.values())
    print("| stage | M | share |")
    print("|---|---|---|")
    for stage, value in sorted(totals.items(), key=lambda kv: -kv[1]):
        if abs(value) >= 0.05e6:
            print(f"| {stage} | {value / 1e6:.1f} | {100 * value / total:.0f}% |")
    print(f"| total | {total / 1e6:.1f} | |")


main()
