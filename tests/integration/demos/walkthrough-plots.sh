#!/bin/sh
# SPDX-License-Identifier: MIT
# The walkthrough's pictures: a small run, then tools/plot-walkthrough.sh on
# its folder. The plots (frame time, triangles and culling efficiency per
# frame) must exist and be whole PNGs of a plausible size with something
# drawn on them; the top views must carry their title; without the oracle
# the efficiency plot is left out with a message; without gnuplot the script
# says so and fails, without a crash.
# Usage: walkthrough-plots.sh WALKTHROUGH PLOT-WALKTHROUGH
set -u
walkthrough=$1
plot=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# check_png FILE MIN-WIDTH MIN-HEIGHT MIN-COLOURS [title]: a whole PNG (every
# chunk's CRC right, the image data inflating to its rows), at least this
# large, with at least this many colours; with "title", dark pixels (text) in
# its top tenth.
check_png() {
    /usr/bin/python3 - "$@" <<'PY'
import struct, sys, zlib
path, min_w, min_h, min_colours = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
title = len(sys.argv) > 5
data = open(path, 'rb').read()
if data[:8] != b'\x89PNG\r\n\x1a\n':
    sys.exit(f'{path}: not a PNG')
pos, idat, ihdr = 8, b'', None
while pos < len(data):
    if pos + 12 > len(data):
        sys.exit(f'{path}: cut short')
    length, kind = struct.unpack('>I4s', data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    crc = data[pos + 8 + length:pos + 12 + length]
    if len(body) != length or len(crc) != 4 or zlib.crc32(kind + body) != struct.unpack('>I', crc)[0]:
        sys.exit(f'{path}: chunk {kind} cut short or damaged')
    if kind == b'IHDR':
        ihdr = struct.unpack('>IIBBBBB', body)
    elif kind == b'IDAT':
        idat += body
    pos += 12 + length
    if kind == b'IEND':
        break
else:
    sys.exit(f'{path}: no IEND')
width, height, depth, colour_type, _, _, interlace = ihdr
channels = {2: 3, 6: 4}.get(colour_type)
if depth != 8 or channels is None or interlace:
    sys.exit(f'{path}: not 8-bit RGB or RGBA without interlacing (depth {depth}, type {colour_type})')
if width < min_w or height < min_h:
    sys.exit(f'{path}: {width}x{height}, expected at least {min_w}x{min_h}')
raw = zlib.decompress(idat)
stride = width * channels
if len(raw) != height * (stride + 1):
    sys.exit(f'{path}: image data of {len(raw)} bytes for {width}x{height}')
rows, prev = [], bytearray(stride)
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = prev[i], (prev[i - channels] if i >= channels else 0)
        if kind == 1: line[i] = (line[i] + a) & 255
        elif kind == 2: line[i] = (line[i] + b) & 255
        elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        elif kind != 0: sys.exit(f'{path}: row {y} has filter {kind}')
    rows.append(line)
    prev = line
colours = {bytes(r[x:x + 3]) for r in rows for x in range(0, stride, channels)}
if len(colours) < min_colours:
    sys.exit(f'{path}: {len(colours)} colours, expected at least {min_colours} (blank?)')
if title:
    dark = sum(1 for r in rows[:height // 10] for x in range(0, stride, channels) if max(r[x:x + 3]) < 80)
    if dark < 20:
        sys.exit(f'{path}: no title in the top tenth ({dark} dark pixels)')
print(f'ok: {path}: {width}x{height}, {len(colours)} colours, {len(data)} bytes')
PY
}

# Three strategies, the baselines among them, 6 frames of 256 x 256.
if ! "$walkthrough" --route dense --frames 6 --size 256 --png-every 5 --strategies vfc,ideal,om-ps \
        --out "$dir/run" >"$dir/run.log" 2>&1; then
    cat "$dir/run.log"
    fail "the walkthrough failed"
fi
"$plot" "$dir/run" >"$dir/plots.txt" 2>"$dir/plots.err" || { cat "$dir/plots.err"; fail "$plot failed"; }
for name in frame-times triangles efficiency; do
    png=$dir/run/$name.png
    grep -qxF "$png" "$dir/plots.txt" || fail "$plot did not print $png"
    if [ ! -f "$png" ]; then
        fail "no $png"
    else
        check_png "$png" 400 300 4 || fail "$png"
    fi
done
for strategy in vfc ideal om-ps; do
    check_png "$dir/run/$strategy-top-0005.png" 256 256 4 title || fail "top view of $strategy"
done

# Without the oracle: no efficiency to plot. On the thread clock (--clock),
# which the CSVs' last column names and the plots read past.
"$walkthrough" --frames 3 --size 64 --png-every 0 --strategies vfc,om-ps --oracle off --clock thread \
    --out "$dir/no-oracle" >/dev/null 2>&1 || fail "the walkthrough failed with --oracle off --clock thread"
# The values of FILE's column culling_clock, one of each.
clocks() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "culling_clock") c = i; next } c { print $c }' "$1" | sort -u; }
for csv in summary frames; do
    [ "$(clocks "$dir/run/$csv.csv")" = wall ] || fail "$csv.csv's culling_clock is not wall by default"
    [ "$(clocks "$dir/no-oracle/$csv.csv")" = thread ] || fail "$csv.csv's culling_clock is not thread with --clock thread"
done
if "$plot" "$dir/no-oracle" >"$dir/plots.txt" 2>"$dir/plots.err"; then
    [ -f "$dir/no-oracle/frame-times.png" ] || fail "no frame-times.png with --oracle off"
    [ ! -f "$dir/no-oracle/efficiency.png" ] || fail "an efficiency.png with --oracle off"
    grep -q "oracle" "$dir/plots.err" || fail "no message about the missing efficiency plot: $(cat "$dir/plots.err")"
else
    cat "$dir/plots.err"
    fail "$plot failed on a run with --oracle off"
fi

# Without gnuplot on PATH: a message that names it, a failing status, no signal.
mkdir "$dir/bin"
for tool in sh bash env awk mktemp rm cat head; do
    found=$(command -v "$tool") && ln -s "$found" "$dir/bin/$tool"
done
PATH=$dir/bin "$plot" "$dir/run" >"$dir/nognu.out" 2>&1
status=$?
if [ $status -eq 0 ] || [ $status -gt 128 ]; then
    fail "without gnuplot: status $status"
elif ! grep -q "gnuplot is not installed" "$dir/nognu.out"; then
    fail "without gnuplot, the message does not say so: $(cat "$dir/nognu.out")"
else
    echo "ok: without gnuplot -> $(cat "$dir/nognu.out")"
fi

# A folder with no frames.csv: a message naming it.
if "$plot" "$dir" >/dev/null 2>"$dir/none.err" || ! grep -qF "$dir/frames.csv" "$dir/none.err"; then
    fail "no frames.csv: $(cat "$dir/none.err")"
fi

[ $failures -eq 0 ] || { echo "$failures failed"; exit 1; }
echo "the walkthrough's plots and captioned top views are whole PNGs"
