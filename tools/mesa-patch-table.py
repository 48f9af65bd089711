#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The table of the Mesa series' patches in docs/mesa.md, made from the series.

One row per patch of patches/mesa/series, in order: its number, the part it
belongs to (the series' '# part SUITE: WHAT' lines), its subject, the files it
adds and how many it changes, and its added and deleted lines. The table sits
between the lines
    <!-- patch table: tools/mesa-patch-table.py writes it -->
    <!-- end of the patch table -->
of docs/mesa.md; tools/export-mesa-patches.sh rewrites it after each export.

Usage:
  tools/mesa-patch-table.py           rewrites the table in docs/mesa.md
  tools/mesa-patch-table.py --check   exits 1 when docs/mesa.md's table is not
                                      the series' (names the first row that
                                      differs)
"""
import os
import re
import sys

import mesa_series

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SERIES_DIR = os.path.join(ROOT, "patches", "mesa")
DOC = os.path.join(ROOT, "docs", "mesa.md")
BEGIN = "<!-- patch table: tools/mesa-patch-table.py writes it -->"
END = "<!-- end of the patch table -->"


def subject(text):
    """The patch's subject without its '[PATCH n/m]' prefix, unfolded."""
    m = re.search(r"^Subject: (.*(?:\n [^\n]*)*)", text, re.M)
    if not m:
        return None
    return re.sub(r"^\[PATCH[^\]]*\]\s*", "", re.sub(r"\n ", " ", m.group(1)))


def diff_counts(text):
    """(files changed, new files, lines added, lines deleted) of a patch."""
    files, new, added, deleted, path = 0, [], 0, 0, None
    in_hunks = False
    for line in text.split("\n"):
        if line.startswith("diff --git "):
            files += 1
            path = line.split(" b/", 1)[1]
            in_hunks = False
        elif line.startswith("new file mode") and path:
            new.append(path)
        elif line.startswith("@@ "):
            in_hunks = True
        elif line == "-- ":
            break
        elif in_hunks and line.startswith("+"):
            added += 1
        elif in_hunks and line.startswith("-"):
            deleted += 1
    return files, new, added, deleted


def table():
    rows = ["| # | part | patch | files | lines |", "|---|---|---|---|---|"]
    for number, (name, part) in enumerate(mesa_series.patches(SERIES_DIR), 1):
        with open(os.path.join(SERIES_DIR, name), encoding="utf-8") as p:
            text = p.read()
        summary = subject(text)
        if summary is None:
            sys.exit(f"patches/mesa/{name}: no Subject line")
        files, new, added, deleted = diff_counts(text)
        added_files = ", ".join(f"`{os.path.basename(n)}`" for n in new)
        what = f"{files}" + (f"; adds {added_files}" if added_files else "")
        rows.append(f"| {number:04d} | {part} | {summary.replace('|', '/')} | {what} | "
                    f"+{added} -{deleted} |")
    return "\n".join(rows) + "\n"


def main():
    with open(DOC, encoding="utf-8") as f:
        doc = f.read()
    if BEGIN not in doc or END not in doc:
        sys.exit(f"{DOC}: no '{BEGIN}' ... '{END}' lines")
    head, rest = doc.split(BEGIN, 1)
    old, tail = rest.split(END, 1)
    new = "\n" + table()
    if len(sys.argv) == 2 and sys.argv[1] == "--check":
        if old == new:
            print("docs/mesa.md: the patch table is the series'")
            return 0
        old_rows, new_rows = old.strip().split("\n"), new.strip().split("\n")
        for i in range(max(len(old_rows), len(new_rows))):
            a = old_rows[i] if i < len(old_rows) else "(none)"
            b = new_rows[i] if i < len(new_rows) else "(none)"
            if a != b:
                print(f"docs/mesa.md: the patch table is not the series' (run "
                      f"tools/mesa-patch-table.py):\n  table:  {a}\n  series: {b}", file=sys.stderr)
                break
        return 1
    if len(sys.argv) != 1:
        sys.exit(__doc__)
    with open(DOC, "w", encoding="utf-8") as f:
        f.write(head + BEGIN + new + END + tail)
    return 0


if __name__ == "__main__":
    sys.exit(main())
