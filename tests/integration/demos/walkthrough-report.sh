#!/bin/sh
# SPDX-License-Identifier: MIT
# The walkthrough's report page: a small run (4 frames of 128 x 128, images
# every 2 frames, three strategies), tools/plot-walkthrough.sh, then
# tools/report-walkthrough.sh on its folder. Every <img> of index.html must
# name a file of the folder that is a whole PNG (checked from the HTML with a
# parser); headless Chromium must load it without a console message, its DOM
# must hold the summary table and every image, and its screenshot must be a
# PNG of the requested size. Text from the files is HTML-escaped; a page whose
# image was removed fails the check.
# Usage: walkthrough-report.sh WALKTHROUGH PLOT-WALKTHROUGH REPORT-WALKTHROUGH
set -u
walkthrough=$1
plot=$2
report=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() {
    echo "FAIL: $*"
    failures=$((failures + 1))
}

# check_images HTML: every <img src> is a file next to HTML and a whole PNG
# (signature, every chunk's CRC, IHDR first, IEND last); prints the count.
check_images() {
    /usr/bin/python3 - "$1" <<'PY'
import os, struct, sys, zlib
from html.parser import HTMLParser
from urllib.parse import unquote, urlsplit
page = sys.argv[1]
class Images(HTMLParser):
    def __init__(self):
        super().__init__()
        self.srcs = []
    def handle_starttag(self, tag, attrs):
        if tag == 'img':
            self.srcs.append(dict(attrs).get('src'))
parser = Images()
parser.feed(open(page, encoding='utf-8').read())
bad = []
for src in parser.srcs:
    if not src or urlsplit(src).scheme or src.startswith('/'):
        bad.append(f'{src!r}: not a relative path')
        continue
    path = os.path.join(os.path.dirname(page), unquote(src))
    try:
        data = open(path, 'rb').read()
    except OSError as e:
        bad.append(f'{src}: {e.strerror}')
        continue
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        bad.append(f'{src}: not a PNG')
        continue
    pos, kinds = 8, []
    while pos + 12 <= len(data):
        length, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body, crc = data[pos + 8:pos + 8 + length], data[pos + 8 + length:pos + 12 + length]
        if len(body) != length or len(crc) != 4 or zlib.crc32(kind + body) != struct.unpack('>I', crc)[0]:
            break
        kinds.append(kind)
        pos += 12 + length
    if not kinds or kinds[0] != b'IHDR' or kinds[-1] != b'IEND' or pos != len(data):
        bad.append(f'{src}: a damaged PNG')
for b in bad:
    print(f'{page}: image {b}')
if bad:
    sys.exit(1)
print(len(parser.srcs))
PY
}

if ! "$walkthrough" --route dense --frames 4 --size 128 --png-every 2 --strategies vfc,ideal,om-ps \
        --out "$dir/run" >"$dir/run.log" 2>&1; then
    cat "$dir/run.log"
    fail "the walkthrough failed"
fi
"$plot" "$dir/run" >/dev/null 2>"$dir/plots.err" || { cat "$dir/plots.err"; fail "$plot failed"; }
page=$dir/run/index.html
printed=$("$report" "$dir/run" 2>"$dir/report.err") || { cat "$dir/report.err"; fail "$report failed"; }
[ "$printed" = "$page" ] || fail "$report printed '$printed', expected $page"

# 3 plots and, for frames 0 and 2, three strategies' frame and top view.
images=$(check_images "$page") || { echo "$images"; fail "index.html names a missing or damaged image"; }
[ "$images" = 15 ] || fail "index.html has $images images, expected 15"
for name in frame-times.png triangles.png efficiency.png vfc-0000.png vfc-top-0000.png om-ps-top-0002.png; do
    grep -qF "src=\"$name\"" "$page" || fail "index.html does not show $name"
done
grep -q 'https\?:' "$page" && fail "index.html refers to the network"

# Headless Chromium: the page loads without a console message, the DOM holds
# the table and every image, the screenshot is a 1200 x 2000 PNG.
if ! command -v chromium >/dev/null; then
    fail "chromium is not installed (Debian: apt-get install chromium; tools/deps.sh test installs it)"
else
    browse() {
        timeout 120 chromium --headless --no-sandbox --disable-gpu --user-data-dir="$dir/profile" \
            --enable-logging=stderr --v=0 "$@" "file://$page"
    }
    browse --screenshot="$dir/shot.png" --window-size=1200,2000 >/dev/null 2>"$dir/shot.err" ||
        { cat "$dir/shot.err"; fail "chromium --screenshot failed"; }
    browse --dump-dom >"$dir/dom.html" 2>"$dir/dom.err" || { cat "$dir/dom.err"; fail "chromium --dump-dom failed"; }
    if grep -h 'CONSOLE' "$dir/shot.err" "$dir/dom.err"; then
        fail "console messages while loading index.html"
    fi
    grep -q '<table id="summary">' "$dir/dom.html" || fail "the DOM has no summary table"
    for strategy in vfc ideal om-ps; do
        grep -q "<td>$strategy</td>" "$dir/dom.html" || fail "the summary table has no row for $strategy"
    done
    [ "$(grep -o '<img ' "$dir/dom.html" | wc -l)" = 15 ] || fail "the DOM does not hold 15 images"
    /usr/bin/python3 - "$dir/shot.png" <<'PY' || fail "no screenshot of 1200 x 2000"
import struct, sys
data = open(sys.argv[1], 'rb').read()
assert data[:8] == b'\x89PNG\r\n\x1a\n' and data[12:16] == b'IHDR', 'not a PNG'
size = struct.unpack('>II', data[16:24])
assert size == (1200, 2000), f'{size}'
print(f'ok: screenshot {size[0]}x{size[1]}, {len(data)} bytes')
PY
fi

# Text from the files is escaped: a strategy named with markup stays text.
mkdir "$dir/escaped"
cp "$dir/run/frames.csv" "$dir/escaped/"
sed '2s/^vfc,/a<b>\&"c,/' "$dir/run/summary.csv" >"$dir/escaped/summary.csv"
"$report" "$dir/escaped" >/dev/null || fail "$report failed on a strategy named with markup"
grep -qF '<td>a&lt;b&gt;&amp;&quot;c</td>' "$dir/escaped/index.html" || fail "the strategy's name is not escaped"
grep -qF '<b>' "$dir/escaped/index.html" && fail "raw markup from summary.csv in index.html"

# The check fails on a missing image.
rm "$dir/run/om-ps-top-0002.png"
if out=$(check_images "$page"); then
    fail "an index.html naming a removed image passed the check"
elif ! echo "$out" | grep -qF 'om-ps-top-0002.png'; then
    fail "the check did not name the removed image: $out"
else
    echo "ok: a removed image fails the check ($out)"
fi

[ $failures -eq 0 ] || { echo "$failures failed"; exit 1; }
echo "the walkthrough's report page shows its table and every image in headless Chromium"
