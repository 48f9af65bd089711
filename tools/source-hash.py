#!/usr/bin/python3
"""Writes a C header defining NAME as a short hash of the given source files.

Usage: source-hash.py OUTPUT NAME FILE...
       source-hash.py --list DIR     prints the C and C++ sources and headers below DIR
The build uses it to stamp what a precomputed database depends on, so that
a change to those sources gives cached databases a new name; --list gives
the build every source of the library without a hand-written list.
"""
import hashlib
import os
import sys

if sys.argv[1:2] == ['--list']:
    for root, dirs, names in sorted(os.walk(sys.argv[2])):
        dirs.sort()
        for n in sorted(names):
            if n.endswith(('.c', '.cpp', '.h')):
                print(os.path.join(root, n))
    sys.exit(0)

output, name, *files = sys.argv[1:]
digest = hashlib.sha256()
for path in sorted(files):
    with open(path, 'rb') as f:
        digest.update(path.rsplit('/src/', 1)[-1].encode() + b'\0' + f.read())
text = f'#pragma once\n#define {name} "{digest.hexdigest()[:12]}"\n'
try:
    with open(output) as f:
        if f.read() == text:
            sys.exit(0)
except FileNotFoundError:
    pass
with open(output, 'w') as f:
    f.write(text)
