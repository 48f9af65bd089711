#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Writes a piglit test profile (gzipped XML, the format of Debian's piglit
profiles) that runs each test once per gallium driver.

Test names get the driver as their first group, so piglit's summary reads
'softpipe@spec@...' and 'llvmpipe@spec@...'. Every test runs with -auto -fbo
(piglit adds both to concurrent GL tests).

  make_profile.py OUT --drivers softpipe,llvmpipe --debian-list tests/piglit/regression.list
      [--llvmpipe-threads 0,1,2,8 [--threads-list LIST]]
  make_profile.py OUT --drivers softpipe,llvmpipe --program NAME=PATH [--program ...]

--llvmpipe-threads runs the Debian tests again on llvmpipe at each rasterizer
thread count given (LP_NUM_THREADS), named 'llvmpipe-threads-N@...';
--threads-list names the tests that do (default: all of --debian-list).
tests/piglit/compare.py checks them against the baseline of 'llvmpipe@...'.
"""
import argparse
import ast
import gzip
import sys
import xml.etree.ElementTree as et

DEBIAN_PROFILE = '/usr/lib/x86_64-linux-gnu/piglit/tests/opengl.xml.gz'


def read_list(path):
    names = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.split('#', 1)[0].strip()
            if line:
                names.append((line, number))
    return names


def debian_commands(path, wanted):
    """Command lines of the wanted test names in Debian's profile."""
    found = {}
    with gzip.open(path, 'rt') as f:
        for _, e in et.iterparse(f):
            if e.tag == 'Test':
                if e.attrib['name'] in wanted:
                    opts = {o.attrib['name']: o.attrib['value'] for o in e.findall('option')}
                    found[e.attrib['name']] = ast.literal_eval(opts['command'])
                e.clear()
    return found


def add_test(root, name, command, driver, threads=None):
    group = driver if threads is None else f'{driver}-threads-{threads}'
    t = et.SubElement(root, 'Test', type='gl', name=f'{group}@{name}')
    et.SubElement(t, 'option', name='command', value=repr(list(command)))
    et.SubElement(t, 'option', name='run_concurrent', value='True')
    env = et.SubElement(t, 'environment')
    et.SubElement(env, 'env', name='GALLIUM_DRIVER', value=driver)
    if threads is not None:
        et.SubElement(env, 'env', name='LP_NUM_THREADS', value=threads)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('out')
    ap.add_argument('--drivers', required=True)
    ap.add_argument('--debian-list')
    ap.add_argument('--debian-profile', default=DEBIAN_PROFILE)
    ap.add_argument('--program', action='append', default=[], metavar='NAME=PATH')
    ap.add_argument('--name', default='occu')
    ap.add_argument('--llvmpipe-threads', default='', metavar='N,N,...')
    ap.add_argument('--threads-list', metavar='LIST')
    args = ap.parse_args()

    tests = []
    if args.debian_list:
        listed = read_list(args.debian_list)
        commands = debian_commands(args.debian_profile, {n for n, _ in listed})
        for name, number in listed:
            if name not in commands:
                sys.exit(f'{args.debian_list}:{number}: no test named "{name}" in {args.debian_profile}')
            tests.append((name, commands[name]))
    debian_tests = list(tests)
    for p in args.program:
        name, sep, path = p.partition('=')
        if not sep or not name or not path:
            sys.exit(f'--program wants NAME=PATH, got "{p}"')
        tests.append((name, [path]))

    threads = [n for n in args.llvmpipe_threads.split(',') if n]
    threaded = debian_tests if threads else []
    if threads and args.threads_list:
        wanted = read_list(args.threads_list)
        known = {n for n, _ in threaded}
        for name, number in wanted:
            if name not in known:
                sys.exit(f'{args.threads_list}:{number}: "{name}" is not a test of {args.debian_list}')
        wanted_names = {n for n, _ in wanted}
        threaded = [t for t in threaded if t[0] in wanted_names]

    drivers = [d for d in args.drivers.split(',') if d]
    root = et.Element('PiglitTestList', name=args.name,
                      count=str(len(tests) * len(drivers) + len(threaded) * len(threads)))
    for driver in drivers:
        for name, command in tests:
            add_test(root, name, command, driver)
    for n in threads:
        for name, command in threaded:
            add_test(root, name, command, 'llvmpipe', n)
    with gzip.open(args.out, 'wt') as f:
        f.write(et.tostring(root, encoding='unicode'))


if __name__ == '__main__':
    main()
