#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Checks a piglit run against tests/piglit/baseline.txt.

A test of Debian's piglit fails the check when its result is worse than the
baseline's (Debian's unpatched Mesa of the same version on the same test).
A test that reports subtests is checked per subtest too, as 'TEST@SUBTEST':
a test whose baseline is a fail for one subtest still guards the others.
occu's own tests (group 'occu@') have no baseline: they must pass or skip,
but for those tests/known-defects.txt lists as failing on a driver until
their fix, which must fail there (a listed test that passes fails the check:
its line must go).
The runs of llvmpipe at a set rasterizer thread count ('llvmpipe-threads-N@',
tests/piglit/make_profile.py --llvmpipe-threads) are checked against the
baseline of 'llvmpipe@' (the unpatched driver at its default thread count),
taken to stand for every count: an unpatched result that depended on the
count would show as a failure here, to be looked into.
Each check is counted as what it is: a pass as passed, a skip as skipped, a
fail or warn that the baseline also has as known (failing as on unpatched
Mesa), anything worse than the baseline as failed. Prints one line per failed
check and ends with 'piglit: N passed, N failed, N skipped, N known'.

  compare.py RESULTS_DIR BASELINE
"""
import bz2
import json
import os
import re
import sys

# Worse is larger. A skip is worse than a pass (a feature went missing).
RANK = {'pass': 0, 'warn': 1, 'skip': 2, 'notrun': 2, 'fail': 3,
        'crash': 4, 'timeout': 4, 'incomplete': 4, 'dmesg-warn': 1, 'dmesg-fail': 3}


def flatten(tests):
    """Result per test, and per subtest as 'TEST@SUBTEST'."""
    results = {}
    for name, test in tests.items():
        results[name] = test['result']
        for sub, result in (test.get('subtests') or {}).items():
            if sub != '__type__':
                results[f'{name}@{sub}'] = result
    return results


def load_results(path):
    for name, opener in (('results.json.bz2', bz2.open), ('results.json', open)):
        full = os.path.join(path, name)
        if os.path.exists(full):
            with opener(full, 'rt') as f:
                return flatten(json.load(f)['tests'])
    sys.exit(f'compare.py: no results.json(.bz2) in {path}')


def load_baseline(path):
    """Lines: RESULT NAME [# reason]. Every non-pass needs a reason."""
    base, problems = {}, []
    with open(path) as f:
        for number, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line.startswith('#'):
                continue
            body, _, reason = line.partition('#')
            result, _, name = body.strip().partition(' ')
            name = name.strip()
            if result not in RANK or not name:
                problems.append(f'{path}:{number}: expected "RESULT NAME [# reason]", got "{line}"')
                continue
            if result != 'pass' and not reason.strip():
                problems.append(f'{path}:{number}: expected {result} of "{name}" has no reason')
            base[name] = result
    return base, problems


def baseline_name(name):
    """The baseline line a result is checked against."""
    return re.sub(r'^llvmpipe-threads-\d+@', 'llvmpipe@', name)


def load_known_defects(path):
    """Lines 'DRIVER TEST # defect': the result names 'DRIVER@TEST'."""
    known = set()
    with open(path) as f:
        for number, raw in enumerate(f, 1):
            words = raw.partition('#')[0].split()
            if len(words) == 2:
                known.add(f'{words[0]}@{words[1]}')
            elif words:
                sys.exit(f'{path}:{number}: expected "DRIVER TEST # defect", got "{raw.strip()}"')
    return known


def known_defect(name, known):
    """The listed test a result (a test's, or a subtest's 'TEST@SUBTEST') belongs to."""
    return next((k for k in known if name == k or name.startswith(k + '@')), None)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    results = load_results(sys.argv[1])
    baseline, problems = load_baseline(sys.argv[2])
    known_defects = load_known_defects(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                    '..', 'known-defects.txt'))
    passed, failed, skipped, known = 0, len(problems), 0, 0
    for p in problems:
        print(f'FAIL baseline: {p}')
    for name in sorted(results):
        got = results[name]
        own = '@occu@' in name
        if own and baseline_name(name) in known_defects:
            ok, why = got == 'fail', 'a known defect (tests/known-defects.txt) must fail until its fix removes the line'
        elif own and known_defect(baseline_name(name), known_defects):
            ok, why = True, 'a subtest of a known defect'
        elif own:
            ok, why = got in ('pass', 'skip'), 'occu tests must pass or skip'
        elif baseline_name(name) in baseline:
            want = baseline[baseline_name(name)]
            ok, why = RANK[got] <= RANK[want], f'baseline is {want}'
            if RANK[got] < RANK[want]:
                print(f'note: {name}: {got}, better than the baseline ({want}); re-record the baseline')
        else:
            ok, why = False, 'not in the baseline (re-record it: tests/piglit/record-baseline.sh)'
        if ok and got == 'pass':
            passed += 1
        elif ok and got in ('skip', 'notrun'):
            skipped += 1
        elif ok:
            known += 1
        else:
            failed += 1
            print(f'FAIL {name}: {got} ({why})')
    for name in sorted(set(baseline) - set(results)):
        failed += 1
        test = next((t for t in results if name.startswith(t + '@') and t in baseline), None)
        if test:
            print(f'FAIL {name}: subtest not reported (its test: {results[test]})')
        else:
            print(f'FAIL {name}: in the baseline but not run (regression.list and baseline.txt disagree)')
    print(f'piglit: {passed} passed, {failed} failed, {skipped} skipped, {known} known')
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
