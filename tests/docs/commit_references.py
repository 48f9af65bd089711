#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Every commit README.md and docs/*.md cite exists in the repository.

A commit reference is a word of 7 to 40 lowercase hex digits with at least
one digit and one letter, not part of a path, a file name or a longer word
(so not the hash inside 'database-09e82e8777531e81.db' or 'install-...-71898cd110f1',
which name cache files, not commits). Each must name a commit:
'git cat-file -e HASH^{commit}'.

Exits 77 (meson's skip) outside a git work tree or in a shallow clone, where
the history the documents cite is not there to check; tests/expected-skips.txt
lists that skip under the condition no-git-history.

  commit_references.py SOURCE_ROOT
"""
import glob
import os
import re
import subprocess
import sys

SKIP = 77

# Hex words of the documents that are not commit references, each with why.
NOT_COMMITS = {
    '2147483647face': 'docs/fuzzing.md: a fuzzer input, the number 2147483647 run into the word "face"',
}

WORD = re.compile(r'(?<![\w./-])[0-9a-f]{7,40}(?![\w/-]|\.\w)')


def references(path):
    """(line number, hex word) of every commit reference in the file."""
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            for word in WORD.findall(line):
                if re.search('[0-9]', word) and re.search('[a-f]', word) and word not in NOT_COMMITS:
                    yield number, word


def git(root, *args):
    return subprocess.run(['git', '-C', root, *args], capture_output=True, text=True)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = sys.argv[1]
    try:
        inside = git(root, 'rev-parse', '--is-inside-work-tree').stdout.strip() == 'true'
    except OSError as e:
        print(f'SKIP: git cannot run ({e}), so the cited commits cannot be looked up')
        return SKIP
    if not inside:
        print(f'SKIP: {root} is not a git work tree, so the cited commits cannot be looked up')
        return SKIP
    if git(root, 'rev-parse', '--is-shallow-repository').stdout.strip() == 'true':
        print(f'SKIP: {root} is a shallow clone, without the history the documents cite')
        return SKIP
    files = [os.path.join(root, 'README.md')] + sorted(glob.glob(os.path.join(root, 'docs', '*.md')))
    checked, missing = set(), 0
    for path in files:
        for number, word in references(path):
            if git(root, 'cat-file', '-e', f'{word}^{{commit}}').returncode != 0:
                missing += 1
                print(f'{os.path.relpath(path, root)}:{number}: {word} names no commit of this repository')
            checked.add(word)
    if not checked:
        print('no commit reference found in README.md and docs/*.md: the extraction is broken')
        return 1
    print(f'{len(checked)} distinct commit references in {len(files)} files, {missing} missing')
    return 1 if missing else 0


if __name__ == '__main__':
    sys.exit(main())
