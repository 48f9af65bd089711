#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The Mesa series' specification patches, made from spec/.

Each part of patches/mesa/series opens with a patch that adds the part's
extension specification to Mesa's docs/_extra/specs/, as a new extension's
specification is submitted to Mesa. spec/ is the one source of that text:
tools/export-mesa-patches.sh writes such a patch's diff from spec/ (this
script, --rewrite), and occu's tests check that every such patch of the
series holds spec/'s text (--check).

A specification patch is one whose diff adds exactly one file,
docs/_extra/specs/NAME.txt, with spec/NAME.txt existing.

Usage:
  tools/mesa-spec-patch.py --rewrite PATCH   rewrites PATCH's diff from spec/
      (exit 0) or leaves a patch that is not a specification patch alone
      (exit 1)
  tools/mesa-spec-patch.py --check [SERIES_DIR]   exits 1, naming each, when a
      specification patch differs from spec/, or when an extension of spec/
      has no specification patch in the series
"""
import os
import re
import sys

import mesa_series

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPEC_DIR = os.path.join(ROOT, "spec")
TARGET = re.compile(r"^diff --git a/docs/_extra/specs/(\S+\.txt) b/docs/_extra/specs/\1$", re.M)


def split_patch(text):
    """(header up to the first diff, list of diffs, trailer) of a git
    format-patch file."""
    first = text.find("\ndiff --git ")
    if first < 0:
        return text, [], ""
    header, rest = text[:first + 1], text[first + 1:]
    end = re.search(r"^-- \n", rest, re.M)
    trailer = ""
    if end:
        rest, trailer = rest[:end.start()], rest[end.start():]
    diffs = re.split(r"(?=^diff --git )", rest, flags=re.M)
    return header, [d for d in diffs if d], trailer


def spec_name(diffs):
    """The specification a patch adds, or None."""
    if len(diffs) != 1:
        return None
    m = TARGET.match(diffs[0])
    if not m or "\nnew file mode " not in diffs[0]:
        return None
    name = m.group(1)
    return name if os.path.isfile(os.path.join(SPEC_DIR, name)) else None


def spec_diff(name):
    with open(os.path.join(SPEC_DIR, name), encoding="utf-8") as f:
        text = f.read()
    if not text.endswith("\n"):
        sys.exit(f"spec/{name}: the last line has no newline; a patch could not hold it as it is")
    lines = text.splitlines(keepends=True)
    path = f"docs/_extra/specs/{name}"
    return (f"diff --git a/{path} b/{path}\nnew file mode 100644\n--- /dev/null\n+++ b/{path}\n"
            f"@@ -0,0 +1,{len(lines)} @@\n" + "".join("+" + line for line in lines))


def added_text(diff):
    body = diff.split("\n@@ ", 1)[1].split("\n", 1)[1]
    return "".join(line[1:] + "\n" for line in body.split("\n") if line.startswith("+"))


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--rewrite":
        path = sys.argv[2]
        with open(path, encoding="utf-8") as f:
            header, diffs, trailer = split_patch(f.read())
        name = spec_name(diffs)
        if not name:
            return 1
        with open(path, "w", encoding="utf-8") as f:
            f.write(header + spec_diff(name) + trailer)
        return 0
    if len(sys.argv) in (2, 3) and sys.argv[1] == "--check":
        series_dir = sys.argv[2] if len(sys.argv) == 3 else os.path.join(ROOT, "patches", "mesa")
        found, failures = set(), []
        for patch, _ in mesa_series.patches(series_dir):
            with open(os.path.join(series_dir, patch), encoding="utf-8") as f:
                _, diffs, _ = split_patch(f.read())
            name = spec_name(diffs)
            if not name:
                continue
            found.add(name)
            with open(os.path.join(SPEC_DIR, name), encoding="utf-8") as f:
                if added_text(diffs[0]) != f.read():
                    failures.append(f"{patch}: its docs/_extra/specs/{name} is not spec/{name} "
                                    "(run tools/export-mesa-patches.sh)")
        for name in sorted(os.listdir(SPEC_DIR)):
            if name.endswith(".txt") and name not in found:
                failures.append(f"spec/{name}: no patch of the series adds it to docs/_extra/specs/")
        for line in failures:
            print(line, file=sys.stderr)
        print(f"{len(found)} specification patches, {len(failures)} problems")
        return 1 if failures else 0
    sys.exit(__doc__)


if __name__ == "__main__":
    sys.exit(main())
