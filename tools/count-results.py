#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Counts one stage of tools/test from what the stage itself wrote, never from
what it was expected to write, and prints one line:

    STAGE: N passed, N failed, N skipped, N known

(known: a failure declared with its reason, should_fail in tests/meson.build,
or failing as on Debian's unpatched Mesa, per tests/piglit/baseline.txt)

A stage whose results are missing, unreadable or fewer than the tests it
declares counts as failed (one failure per missing result), so that the last
line of tools/test cannot say '0 failed' for tests that did not run.

  count-results.py meson BUILD_DIR MESON_STATUS [SELECTION...]
      BUILD_DIR/meson-logs/testlog.json against `meson test --list
      SELECTION` (the tests the suite declares, counted by meson itself;
      SELECTION: the --suite and --no-suite options the run was given, as
      tools/check-mesa-series.sh gives them); a non-zero exit
      status of `meson test` with no failed result is a failure of its own.
      A GoogleTest program that passes with skipped test cases is counted
      as passed, and each skipped case is counted as skipped and named
      (its reason from the program's XML report).
  count-results.py piglit RESULTS_DIR PROFILE...
      the runner's results against the tests in the profiles; the per-test
      verdicts come from tests/piglit/compare.py's last line.
"""
import bz2
import gzip
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as et


def line(stage, passed, failed, skipped, known=0):
    print(f'{stage}: {passed} passed, {failed} failed, {skipped} skipped, {known} known')


def gtest_skips(build, report):
    """(case, reason) of every skipped case in the program's XML report."""
    path = os.path.join(build, report)
    try:
        root = et.parse(path).getroot()
    except (OSError, et.ParseError) as e:
        return None, f'{path}: {e}'
    skips = []
    for case in root.iter('testcase'):
        skipped = case.find('skipped')
        if skipped is not None or case.attrib.get('result') == 'skipped':
            reason = (skipped.attrib.get('message') or skipped.text or '') if skipped is not None else ''
            skips.append((f"{case.attrib.get('classname')}.{case.attrib.get('name')}",
                          reason.strip().splitlines()[-1] if reason.strip() else 'no reason given'))
    return skips, None


def meson(build, status, selection=()):
    declared = subprocess.run(['meson', 'test', '-C', build, '--list', '--no-rebuild', *selection],
                              capture_output=True, text=True)
    names = [n.strip() for n in declared.stdout.splitlines() if n.strip()]
    if declared.returncode != 0 or not names:
        print(f'meson test --list gave no tests (exit {declared.returncode}): {declared.stderr.strip()}')
        line('meson', 0, 1, 0)
        return
    # Both name a test 'project:suites / name'; one name may be declared twice.
    declared_names = set(names)
    passed = failed = skipped = known = 0
    seen = set()
    log = os.path.join(build, 'meson-logs', 'testlog.json')
    try:
        entries = [json.loads(l) for l in open(log) if l.strip()]
    except (OSError, ValueError) as e:
        print(f'{log}: {e}')
        entries = []
    for r in entries:
        name, result = r['name'], r['result']
        seen.add(name)
        if result == 'OK':
            passed += 1
        elif result == 'SKIP':
            skipped += 1
            print(f'skip {name}')
        elif result == 'EXPECTEDFAIL':
            # should_fail in tests/meson.build, with its reason there
            known += 1
            print(f'known failure {name}')
        else:
            failed += 1
            print(f'FAIL {name}: {result}')
        report = next((a.split(':', 1)[1] for a in r.get('command') or []
                       if a.startswith('--gtest_output=xml:')), None)
        if report and result == 'OK':
            skips, problem = gtest_skips(build, report)
            if problem:
                failed += 1
                print(f'FAIL {name}: no readable GoogleTest report ({problem})')
                continue
            for case, reason in skips:
                skipped += 1
                print(f'skip {name}: {case}: {reason}')
    for name in sorted(declared_names - seen):
        failed += 1
        print(f'FAIL {name}: declared by the suite but no result recorded')
    if status != 0 and failed == 0:
        failed += 1
        print(f'FAIL meson test exited with status {status} though every result it recorded passed')
    line('meson', passed, failed, skipped, known)


def profile_tests(path):
    with gzip.open(path, 'rt') as f:
        return {e.attrib['name'] for _, e in et.iterparse(f) if e.tag == 'Test'}


def piglit(results_dir, profiles):
    root = os.path.dirname(os.path.abspath(__file__))
    declared = set()
    for p in profiles:
        declared |= profile_tests(p)
    tests = None
    for name, opener in (('results.json.bz2', bz2.open), ('results.json', open)):
        full = os.path.join(results_dir, name)
        if os.path.exists(full):
            with opener(full, 'rt') as f:
                tests = json.load(f)['tests']
    if tests is None:
        print(f'no results in {results_dir}')
        line('piglit', 0, max(len(declared), 1), 0)
        return
    missing = declared - set(tests)
    for name in sorted(missing):
        print(f'FAIL {name}: in the profile but no result')
    compare = subprocess.run(['/usr/bin/python3', os.path.join(root, '..', 'tests', 'piglit', 'compare.py'),
                              results_dir, os.path.join(root, '..', 'tests', 'piglit', 'baseline.txt')],
                             capture_output=True, text=True)
    sys.stdout.write(compare.stdout)
    last = (compare.stdout.strip().splitlines()[-1:] or [''])[0]
    m = re.fullmatch(r'piglit: (\d+) passed, (\d+) failed, (\d+) skipped, (\d+) known', last)
    if not m:
        print(f'compare.py printed no count (exit {compare.returncode}): {compare.stderr.strip()}')
        line('piglit', 0, len(missing) + 1, 0)
        return
    passed, failed, skipped, known = map(int, m.groups())
    if compare.returncode != 0 and failed == 0:
        failed = 1
    line('piglit', passed, failed + len(missing), skipped, known)


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == 'meson':
        meson(sys.argv[2], int(sys.argv[3]), sys.argv[4:])
    elif len(sys.argv) >= 4 and sys.argv[1] == 'piglit':
        piglit(sys.argv[2], sys.argv[3:])
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
