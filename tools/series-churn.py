#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Lines a patch of the Mesa series adds that a later patch deletes or rewrites.

A series that shows the final design adds each line once: a line one patch
adds and a later one takes out again is a design the reviewer reads twice.
This commits the series, patch by patch, on the pristine source (in a
scratch index and detached commits of the cache's Mesa repository: no work
tree changes), then for every patch and file it touches:

  - the lines the patch adds (git blame of the patch's own commit: the lines
    it is the author of there);
  - of those, the ones the final tree no longer has where the patch put them
    (git blame --reverse from the patch to the last one: the last patch in
    which each line still existed; the patch after that one took it out or
    rewrote it).

Prints one line per patch with churn, 'file: N by PATCH, ...', and a total:
    series churn: N of M added lines deleted or rewritten by a later patch
Usage: tools/series-churn.py [--verbose] [MESA_REPO]
  MESA_REPO   the git repository whose root commit is the pristine source
              (default: the cache's source/, as tools/mesa.sh leaves it)
  --verbose   also prints each such line
"""
import os
import re
import subprocess
import sys
import tempfile
from collections import defaultdict

import mesa_series

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def git(repo, *args, env=None, input=None):
    return subprocess.run(["git", "-C", repo, *args], check=True, capture_output=True, text=True,
                          env=env, input=input).stdout


def series_patches():
    return [name for name, _ in mesa_series.patches(os.path.join(ROOT, "patches", "mesa"))]


def commit_series(repo, patches):
    """Commits of the patches on the pristine root, in a scratch index."""
    pristine = git(repo, "rev-list", "--max-parents=0", "HEAD").split()[0]
    commits = []
    with tempfile.TemporaryDirectory() as tmp:
        env = dict(os.environ, GIT_INDEX_FILE=os.path.join(tmp, "index"),
                   GIT_AUTHOR_NAME="series-churn", GIT_AUTHOR_EMAIL="series-churn@localhost",
                   GIT_COMMITTER_NAME="series-churn", GIT_COMMITTER_EMAIL="series-churn@localhost")
        git(repo, "read-tree", pristine, env=env)
        parent = pristine
        for name in patches:
            path = os.path.join(ROOT, "patches/mesa", name)
            try:
                git(repo, "apply", "--cached", "--whitespace=nowarn", path, env=env)
            except subprocess.CalledProcessError as e:
                sys.exit(f"series-churn: {name} does not apply on the patches before it: {e.stderr.strip()}")
            tree = git(repo, "write-tree", env=env).strip()
            parent = git(repo, "commit-tree", tree, "-p", parent, "-m", name, env=env).strip()
            commits.append(parent)
    return pristine, commits


def added_files(repo, commit):
    """Files the commit adds lines to."""
    out = git(repo, "diff-tree", "--no-commit-id", "--numstat", "-r", commit)
    files = []
    for line in out.splitlines():
        added, _, path = line.split("\t", 2)
        if added != "-" and int(added) > 0:
            files.append(path)
    return files


BLAME_HEADER = re.compile(r"^([0-9a-f]{40}) (\d+) (\d+)")


def blame(repo, *args):
    """(commit, final line number, text) per line of git blame --porcelain."""
    out = git(repo, "blame", "--porcelain", *args)
    lines, current = [], None
    for line in out.splitlines():
        if line.startswith("\t"):
            lines.append((current[0], current[1], line[1:]))
            continue
        m = BLAME_HEADER.match(line)
        if m:
            current = (m.group(1), int(m.group(3)))
    return lines


def main():
    args = sys.argv[1:]
    verbose = "--verbose" in args
    args = [a for a in args if a != "--verbose"]
    if args:
        repo = args[0]
    else:
        cache = os.environ.get("OCCU_CACHE", os.path.expanduser("~/.cache/occu"))
        repo = os.path.join(cache, "mesa", os.environ.get("MESA_DEBIAN_VERSION", "22.3.6-1+deb12u2"), "source")
    if not os.path.isdir(repo):
        sys.exit(f"series-churn: no Mesa repository at {repo} (run tools/mesa.sh first, or name one)")
    patches = series_patches()
    _, commits = commit_series(repo, patches)
    index = {c: k for k, c in enumerate(commits)}
    last = commits[-1]
    total_added = total_churn = 0
    for k, commit in enumerate(commits):
        removed = defaultdict(lambda: defaultdict(int))   # file -> later patch -> lines
        shown = []
        added = 0
        for path in added_files(repo, commit):
            own = {n for c, n, _ in blame(repo, commit, "--", path) if c == commit}
            added += len(own)
            if k == len(commits) - 1:
                continue
            # The last commit in which each line of this version still existed.
            for c, n, text in blame(repo, "--reverse", f"{commit}..{last}", "--", path):
                if n in own and c != last:
                    by = patches[index[c] + 1] if c in index else patches[k + 1]
                    removed[path][by] += 1
                    shown.append(f"    {path}:{n} (taken out by {by[:4]}): {text.strip()[:100]}")
        churn = sum(sum(v.values()) for v in removed.values())
        total_added += added
        total_churn += churn
        if churn:
            parts = "; ".join(f"{p}: " + ", ".join(f"{n} by {b[:4]}" for b, n in sorted(v.items()))
                              for p, v in sorted(removed.items()))
            print(f"{patches[k]}: {churn} of {added} added lines deleted or rewritten later ({parts})")
            if verbose:
                print("\n".join(shown))
    print(f"series churn: {total_churn} of {total_added} added lines deleted or rewritten by a later patch")


if __name__ == "__main__":
    main()
