#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Writes DIR/index.html, a self-contained report of a walkthrough run
# (build/demos/walkthrough --out DIR): the summary table (DIR/summary.csv),
# the plots tools/plot-walkthrough.sh made (frame-times.png, triangles.png,
# efficiency.png, those present), a link to the video
# tools/video-walkthrough.sh made (route.mp4, if present), and for up to
# six frames spread along the route every strategy's frame and top view
# side by side (<strategy>-NNNN.png, <strategy>-top-NNNN.png). No network:
# inline CSS, images by relative path (they sit in DIR). Every text taken
# from the files is HTML-escaped. Prints the path of index.html.
# tools/demo runs it after the plots.
# Usage: tools/report-walkthrough.sh DIR
set -euo pipefail

me=report-walkthrough.sh
die() { printf '%s: %s\n' "$me" "$*" >&2; exit 1; }

[ $# -eq 1 ] || die "usage: $me DIR (a walkthrough's --out directory, holding summary.csv)"
dir=$1
[ -f "$dir/summary.csv" ] || die "no $dir/summary.csv (make it with: build/demos/walkthrough --out $dir)"

exec /usr/bin/python3 - "$dir" <<'PY'
import csv, html, os, re, sys
from urllib.parse import quote

out = sys.argv[1]
esc = lambda s: html.escape(str(s), quote=True)
src = lambda name: esc(quote(name))   # a file in the same folder, by relative path

with open(os.path.join(out, 'summary.csv'), newline='') as f:
    rows = list(csv.reader(f))
if not rows or len(rows) < 2:
    sys.exit(f'report-walkthrough.sh: {out}/summary.csv holds no strategies')
header, body = rows[0], rows[1:]
col = {name: i for i, name in enumerate(header)}
def cell(row, name):
    i = col.get(name)
    return row[i] if i is not None and i < len(row) else ''

# The walkthrough's file_name(): ':', '/' and '=' become '_'.
file_name = lambda label: re.sub(r'[:/=]', '_', label)
strategies = [cell(r, 'strategy') for r in body if cell(r, 'strategy')]

# Frames with images: <name>-NNNN.png and <name>-top-NNNN.png, for any strategy.
files = set(os.listdir(out))
frames = set()
for s in strategies:
    pattern = re.compile(re.escape(file_name(s)) + r'-(\d{4,})\.png$')
    for name in files:
        m = pattern.match(name)
        if m:
            frames.add(m.group(1))
run_frames = cell(body[0], 'frames')
if run_frames.isdigit():   # not a longer earlier run's images left in the folder
    frames = {n for n in frames if int(n) < int(run_frames)}
frames = sorted(frames, key=int)
if len(frames) > 6:   # six spread along the route, first and last among them
    frames = [frames[round(i * (len(frames) - 1) / 5)] for i in range(6)]

route, size = cell(body[0], 'route'), cell(body[0], 'size')
# The walkthrough's size: "512" for square frames, "1280x720" otherwise.
pixels = size if 'x' in size else f'{size}x{size}'
title = 'occu walkthrough' + (f': the {route} route' if route else '') + (f', {pixels} pixels' if size else '')
numeric = re.compile(r'^-?[0-9.]+(e[-+]?[0-9]+)?$|^-$')

p = []
w = p.append
w('<!DOCTYPE html>\n<html lang="en">\n<head>\n<meta charset="utf-8">\n')
w(f'<title>{esc(title)}</title>\n')
w('''<style>
body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fafafa; }
h1 { font-size: 1.5em; } h2 { font-size: 1.2em; margin-top: 1.5em; } h3 { font-size: 1em; }
table { border-collapse: collapse; font-size: 0.85em; }
th, td { border: 1px solid #ccc; padding: 0.2em 0.5em; }
th { background: #eee; } td.n { text-align: right; font-variant-numeric: tabular-nums; }
tr:nth-child(even) td { background: #f2f2f2; }
img { max-width: 100%; border: 1px solid #ccc; background: #fff; }
.plots img { display: block; margin: 0.5em 0; }
.pair { display: flex; gap: 0.5em; align-items: flex-start; margin-bottom: 0.8em; }
.pair figure { margin: 0; } .pair figcaption { font-size: 0.85em; }
.missing { color: #a00; }
</style>
</head>
<body>
''')
w(f'<h1>{esc(title)}</h1>\n')
w('<p>Made by <code>tools/report-walkthrough.sh</code> from <a href="summary.csv">summary.csv</a> '
  'and <a href="frames.csv">frames.csv</a>; docs/walkthrough.md in occu\'s tree says what each column means.</p>\n')
if 'route.mp4' in files:
    w('<p>The route as a video (frame and top view side by side): <a href="route.mp4">route.mp4</a>.</p>\n')

w('<h2>Summary</h2>\n<table id="summary">\n<tr>')
w(''.join(f'<th>{esc(h)}</th>' for h in header))
w('</tr>\n')
for r in body:
    w('<tr>' + ''.join(f'<td class="n">{esc(v)}</td>' if numeric.match(v) else f'<td>{esc(v)}</td>' for v in r) + '</tr>\n')
w('</table>\n')

plots = [(n, t) for n, t in (('frame-times.png', 'Frame time per frame (log scale)'),
                             ('triangles.png', 'Triangles drawn per frame'),
                             ('efficiency.png', 'Culling efficiency per frame'))
         if n in files]
w('<h2>Plots</h2>\n<div class="plots">\n')
for n, t in plots:
    w(f'<h3>{esc(t)}</h3>\n<img src="{src(n)}" alt="{esc(t)}">\n')
if not plots:
    w('<p>No plots (run <code>tools/plot-walkthrough.sh</code> on this folder).</p>\n')
w('</div>\n')

w('<h2>Frames</h2>\n')
if not frames:
    w('<p>No frames (the walkthrough ran with <code>--png-every 0</code>).</p>\n')
for number in frames:
    w(f'<h3>Frame {esc(int(number))}</h3>\n')
    for s in strategies:
        pair = [n for n in (f'{file_name(s)}-{number}.png', f'{file_name(s)}-top-{number}.png') if n in files]
        if not pair:
            continue
        w('<div class="pair">\n')
        for n in pair:
            w(f'<figure><img src="{src(n)}" alt="{esc(n)}">'
              f'<figcaption>{esc(n)}</figcaption></figure>\n')
        w('</div>\n')
w('</body>\n</html>\n')

path = os.path.join(out, 'index.html')
with open(path + '.tmp', 'w', encoding='utf-8') as f:
    f.write(''.join(p))
os.replace(path + '.tmp', path)
print(path)
PY
