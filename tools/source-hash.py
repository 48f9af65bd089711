#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes a C header defining NAME as a short hash of the sources below DIRs.

Usage: source-hash.py OUTPUT NAME DIR...

Every C and C++ source and header (.c, .cpp, .h) and meson.build below each
DIR counts, found when the build runs (src/meson.build runs this at every
build), so a file added to the library changes the hash without a list
anyone keeps. Each file counts by its path below DIR's parent and its
contents: the hash does not depend on where the checkout is. The header is
rewritten only when the hash changes, so that what includes it is rebuilt
only then. The build stamps the databases it makes with this hash
(culling/database_file.h): a change to the library's code gives them a new
provenance.
"""
import hashlib
import os
import sys

output, name, *dirs = sys.argv[1:]
if not dirs:
    sys.exit('usage: source-hash.py OUTPUT NAME DIR...')
digest = hashlib.sha256()
for top in dirs:
    top = os.path.normpath(top)
    base = os.path.dirname(top)
    found = []
    for root, subdirs, names in os.walk(top):
        found += [os.path.join(root, n) for n in names if n.endswith(('.c', '.cpp', '.h')) or n == 'meson.build']
    if not found:
        sys.exit(f'source-hash.py: no sources below {top}')
    for path in sorted(found):
        with open(path, 'rb') as f:
            digest.update(os.path.relpath(path, base).encode() + b'\0' + f.read() + b'\0')
text = f'#pragma once\n#define {name} "{digest.hexdigest()[:12]}"\n'
try:
    with open(output) as f:
        if f.read() == text:
            sys.exit(0)
except FileNotFoundError:
    pass
with open(output, 'w') as f:
    f.write(text)
