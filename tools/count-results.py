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

Every skip must be expected: tests/expected-skips.txt lists each one with its
reason. A skip it does not list counts as failed, not skipped (a driver that
lost a feature turns tests into skips, which must not read as '0 failed'), and
a listed skip that now passes or fails, or no longer runs, is one failure more,
whose message says to remove it from the list.

  count-results.py meson BUILD_DIR MESON_STATUS [SELECTION...]
      BUILD_DIR/meson-logs/testlog.json against `meson test --list
      SELECTION` (the tests the suite declares, counted by meson itself;
      SELECTION: the --suite and --no-suite options the run was given, as
      tools/check-mesa-series.sh gives them); a non-zero exit
      status of `meson test` with no failed result is a failure of its own.
      A GoogleTest program that passes with skipped test cases is counted
      as passed, and each skipped case is counted as skipped and named
      (its reason from the program's XML report), as 'TEST: CASE'; so is
      each skipped subtest of a piglit-style program that passes (its
      'PIGLIT: {"subtest": ...}' lines), as 'TEST: SUBTEST'.
  count-results.py piglit RESULTS_DIR PROFILE...
      the runner's results against the tests in the profiles; the per-test
      verdicts come from tests/piglit/compare.py's last line. A skipped test
      is checked against the list as 'TEST'; a skipped subtest of a test that
      did not skip as a whole, as 'TEST@SUBTEST'.
  count-results.py check-list
      only reads tests/expected-skips.txt and reports its malformed lines.
"""
import bz2
import gzip
import json
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as et


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXPECTED_SKIPS = os.path.join(ROOT, 'tests', 'expected-skips.txt')


def _cpu_lacks_avx2():
    try:
        with open('/proc/cpuinfo') as f:
            return not any(l.startswith('flags') and ' avx2' in l for l in f)
    except OSError:
        return True


def _no_git_history():
    """As tests/docs/commit_references.py decides to skip: no git work tree, or a shallow one."""
    def ask(*args):
        return subprocess.run(['git', '-C', ROOT, 'rev-parse', *args], capture_output=True, text=True).stdout.strip()
    try:
        return ask('--is-inside-work-tree') != 'true' or ask('--is-shallow-repository') == 'true'
    except OSError:
        return True


# Conditions a line of the list may carry (STAGE:CONDITION): the skip is
# expected only where the condition holds; elsewhere the test must run.
CONDITIONS = {'no-avx2': _cpu_lacks_avx2, 'no-git-history': _no_git_history}


class ExpectedSkips:
    """tests/expected-skips.txt: lines 'STAGE[:CONDITION] NAME  # reason'."""

    def __init__(self, path=EXPECTED_SKIPS):
        self.path = path
        self.entries = {}      # (stage, name) -> ("FILE:LINE", reason), of the lines whose condition holds
        self.problems = []
        try:
            lines = open(path).read().splitlines()
        except OSError as e:
            self.problems.append(f'{path}: {e}')
            return
        for number, raw in enumerate(lines, 1):
            text = raw.strip()
            if not text or text.startswith('#'):
                continue
            body, sep, reason = text.partition(' # ')
            stage, _, name = body.strip().partition(' ')
            stage, _, condition = stage.partition(':')
            name = name.strip()
            where = f'{os.path.relpath(path, ROOT)}:{number}'
            if stage not in ('meson', 'piglit') or not name:
                self.problems.append(f'{where}: expected "STAGE[:CONDITION] NAME  # reason" '
                                     f'(STAGE meson or piglit), got "{text}"')
            elif not sep or not reason.strip():
                self.problems.append(f'{where}: the skip of "{name}" has no reason')
            elif condition and condition not in CONDITIONS:
                self.problems.append(f'{where}: unknown condition "{condition}" '
                                     f'(known: {", ".join(sorted(CONDITIONS))})')
            elif (stage, name) in self.entries:
                self.problems.append(f'{where}: "{name}" listed twice')
            elif not condition or CONDITIONS[condition]():
                self.entries[(stage, name)] = (where, reason.strip())

    def check_skip(self, stage, name):
        """None when the skip is listed, else the failure's message."""
        if (stage, name) in self.entries:
            return None
        return (f'FAIL {name}: skipped, and {os.path.relpath(self.path, ROOT)} does not list it '
                f'(a missing feature; an expected skip is listed there with its reason)')

    def stale(self, stage, name, what):
        """The failure's message for a listed skip that did not skip."""
        where, reason = self.entries[(stage, name)]
        return (f'FAIL {name}: {where} lists it as a skip ({reason}), but it {what}; '
                f'remove it from the list')

    def listed(self, stage):
        return sorted(n for s, n in self.entries if s == stage)


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


def bare(name):
    """A meson test's name without 'project:suites / '."""
    return name.split(' / ', 1)[-1]


SUBTEST_LINE = re.compile(r'^PIGLIT: \{"subtest": \{"(.*)" : "(\w+)"\}\}$', re.M)


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
    # The list names a test without 'project:suites / ': its suites may change.
    declared_tests = {bare(n) for n in declared_names}
    expected = ExpectedSkips()
    for p in expected.problems:
        print(f'FAIL {p}')
    passed, failed, skipped, known = 0, len(expected.problems), 0, 0
    seen = set()
    outcome = {}    # what each test, case and subtest did: 'passed', 'failed', 'skipped'
    log = os.path.join(build, 'meson-logs', 'testlog.json')
    try:
        entries = [json.loads(l) for l in open(log) if l.strip()]
    except (OSError, ValueError) as e:
        print(f'{log}: {e}')
        entries = []

    def skip(name, why):
        nonlocal skipped, failed
        problem = expected.check_skip('meson', name)
        if problem:
            failed += 1
            print(f'{problem}: {why}')
        else:
            skipped += 1
            print(f'skip {name}: {why}')

    for r in entries:
        name, result = r['name'], r['result']
        seen.add(name)
        if result == 'OK':
            passed += 1
            outcome[bare(name)] = 'passed'
        elif result == 'SKIP':
            outcome[bare(name)] = 'skipped'
            skip(bare(name), 'exit status 77')
        elif result == 'EXPECTEDFAIL':
            # should_fail in tests/meson.build, with its reason there
            known += 1
            outcome[bare(name)] = 'failed as expected'
            print(f'known failure {name}')
        else:
            failed += 1
            outcome[bare(name)] = 'failed'
            print(f'FAIL {name}: {result}')
        # A piglit-style program's subtests, from its result lines.
        for sub, sub_result in SUBTEST_LINE.findall(r.get('stdout') or ''):
            key = f'{bare(name)}: {sub}'
            outcome[key] = {'pass': 'passed', 'skip': 'skipped'}.get(sub_result, 'failed')
            if sub_result == 'skip' and result == 'OK':
                skip(key, 'a skipped subtest')
        report = next((a.split(':', 1)[1] for a in r.get('command') or []
                       if a.startswith('--gtest_output=xml:')), None)
        if report and result == 'OK':
            skips, problem = gtest_skips(build, report)
            if problem:
                failed += 1
                print(f'FAIL {name}: no readable GoogleTest report ({problem})')
                continue
            for case, reason in skips:
                outcome[f'{bare(name)}: {case}'] = 'skipped'
                skip(f'{bare(name)}: {case}', reason)
    for name in sorted(declared_names - seen):
        failed += 1
        print(f'FAIL {name}: declared by the suite but no result recorded')
    # Listed skips that did not skip, among the tests this run declared (a
    # selection leaves the others out); without a selection every listed
    # test must exist.
    for name in expected.listed('meson'):
        test = name.split(': ', 1)[0]
        if test not in declared_tests and selection:
            continue
        what = outcome.get(name)
        if what == 'skipped':
            continue
        if what is None:
            what = ('is not declared by the suite' if test not in declared_tests else
                    f'was not reported (its test {outcome.get(test, "did not run")})')
        failed += 1
        print(expected.stale('meson', name, what))
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
    # Every skip against the list: a test that skipped as a whole as 'TEST'
    # (its subtests skipped with it), a subtest of one that did not as
    # 'TEST@SUBTEST'. compare.py counted them as skipped; an unlisted one is
    # a failure instead.
    expected = ExpectedSkips()
    for p in expected.problems:
        print(f'FAIL {p}')
    failed += len(expected.problems)
    compare_failed = {l for l in compare.stdout.splitlines() if l.startswith('FAIL ')}

    def unlisted(name):
        nonlocal skipped, failed
        problem = expected.check_skip('piglit', name)
        if problem:
            print(problem)
            # compare.py counted it as skipped, unless it failed it already.
            if not any(l.startswith(f'FAIL {name}: ') for l in compare_failed):
                skipped -= 1
                failed += 1

    outcome = {}
    for name, test in tests.items():
        outcome[name] = test['result']
        whole = test['result'] in ('skip', 'notrun')
        if whole:
            unlisted(name)
        for sub, result in (test.get('subtests') or {}).items():
            if sub == '__type__':
                continue
            outcome[f'{name}@{sub}'] = result
            if result in ('skip', 'notrun'):
                if whole:
                    continue
                unlisted(f'{name}@{sub}')
    for name in expected.listed('piglit'):
        got = outcome.get(name)
        if got in ('skip', 'notrun'):
            continue
        failed += 1
        print(expected.stale('piglit', name, f'gave {got}' if got else 'did not run'))
    line('piglit', passed, failed + len(missing), skipped, known)


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == 'meson':
        meson(sys.argv[2], int(sys.argv[3]), sys.argv[4:])
    elif len(sys.argv) >= 4 and sys.argv[1] == 'piglit':
        piglit(sys.argv[2], sys.argv[3:])
    elif sys.argv[1:] == ['check-list']:
        problems = ExpectedSkips().problems
        for p in problems:
            print(p)
        sys.exit(1 if problems else 0)
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
