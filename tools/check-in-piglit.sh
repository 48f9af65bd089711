#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds occu's piglit-style tests of the GL_MESAX_occlusion_unit extensions
# inside a piglit source tree, on piglit's own framework (piglit-util-gl,
# PIGLIT_GL_TEST_CONFIG, waffle), runs them with piglit's runner on the
# patched Mesa, and compares every test's and subtest's result with occu's
# own build of the same sources (tests/piglit_util/, OSMesa) under the same
# runner: the piglit merge request's tests, checked (issue 42, item 5).
#
# Usage: tools/check-in-piglit.sh PIGLIT_TREE
#
# PIGLIT_TREE is a piglit source tree (a checkout of piglit's repository); it
# is not modified: the script copies it once to a scratch tree,
# $OCCU_PIGLIT_WORK/src (default: $OCCU_BUILD_DIR/piglit-check, OCCU_BUILD_DIR
# defaulting to build/), and copies into that copy:
#   tests/spec/mesax_occlusion_unit{,_async,_conservative}/  (sources, helpers,
#       CMakeLists.txt and CMakeLists.gl.txt; not meson.build)
#   tests/spec/mesax_occlusion_unit/GL/mesax_occlusion_unit.h  (include/GL/'s
#       header beside ou_util.h, which includes it; piglit's gl.xml has no tokens
#       of these extensions)
#   the upstream behaviour tests of tests/spec/arb_occlusion_query/,
#       arb_depth_clamp/, arb_shader_image_load_store/ and glsl-1.10/ into
#       piglit's folders of those features
#       (glsl-1.10/execution/), each added to that folder's CMakeLists.gl.txt
# adds the three folders to tests/spec/CMakeLists.txt and their tests to the
# profile tests/opengl.py (one group per extension, as piglit lists every
# other extension's), and the extensions' enums and commands to piglit's
# registry/gl.xml, from which its dispatch is generated. `diff -r PIGLIT_TREE $OCCU_PIGLIT_WORK/src` is then the
# merge request. Its build is $OCCU_PIGLIT_WORK/build (CMake, Ninja; only the
# tests' executables and what they link, nice'd, -j2), kept between runs.
#
# Mesa: OCCU_MESA_PREFIX as tools/build.sh takes it (an install made by
# tools/mesa.sh; without it tools/mesa.sh builds or finds one). occu's own
# build: $OCCU_BUILD_DIR, made by tools/build.sh when it has no test programs.
#
# Both builds run under GALLIUM_DRIVER=softpipe and =llvmpipe with piglit's
# runner of the tree (`piglit run -p surfaceless_egl`), piglit's from the
# patched profile, occu's from a profile of the same test names and
# arguments on occu's programs. Prints each driver's counts and every test or
# subtest whose result differs; exits 1 on a difference, 0 when all agree.
set -euo pipefail
source "$(dirname "$0")/lib.sh"

[ $# -eq 1 ] || die "usage: tools/check-in-piglit.sh PIGLIT_TREE"
tree=$(cd "$1" && pwd) || die "no directory $1"
[ -f "$tree/piglit" ] && [ -f "$tree/tests/opengl.py" ] && [ -f "$tree/tests/util/piglit-util-gl.h" ] ||
    die "$tree is not a piglit source tree (no piglit, tests/opengl.py, tests/util/piglit-util-gl.h)"

"$OCCU_ROOT/tools/deps.sh" piglit
if [ -n "${OCCU_MESA_PREFIX:-}" ]; then
    [ -f "$OCCU_MESA_PREFIX/occu/env.sh" ] || die "OCCU_MESA_PREFIX=$OCCU_MESA_PREFIX has no occu/env.sh (not a Mesa installed by tools/mesa.sh or tools/check-mesa-series.sh)"
    prefix=$(cd "$OCCU_MESA_PREFIX" && pwd)
else
    prefix=$("$OCCU_ROOT/tools/mesa.sh")
fi
source "$prefix/occu/env.sh"
export PATH=/usr/bin:$PATH   # Debian's python (numpy, mako) and meson, whatever is first on PATH

build=${OCCU_BUILD_DIR:-$OCCU_ROOT/build}
work=${OCCU_PIGLIT_WORK:-$build/piglit-check}
src=$work/src
mkdir -p "$work"
work=$(cd "$work" && pwd)
src=$work/src

exts=(mesax_occlusion_unit mesax_occlusion_unit_async mesax_occlusion_unit_conservative)
# The upstream behaviour the extensions' records follow (the series' fixes):
# occu's folder, and the folder of piglit's tree that tests that feature.
declare -A upstream=([arb_occlusion_query]=tests/spec/arb_occlusion_query
                     [arb_depth_clamp]=tests/spec/arb_depth_clamp
                     [arb_shader_image_load_store]=tests/spec/arb_shader_image_load_store
                     [glsl-1.10]=tests/spec/glsl-1.10/execution)
# The tree's files the script patches, kept as they were in $work/orig.
patched=(tests/opengl.py tests/spec/CMakeLists.txt registry/gl.xml)
for folder in "${upstream[@]}"; do patched+=("$folder/CMakeLists.gl.txt"); done

# --- occu's own build of the tests ---------------------------------------------
if [ ! -f "$build/build.ninja" ]; then
    OCCU_MESA_PREFIX=$prefix OCCU_BUILD_DIR=$build "$OCCU_ROOT/tools/build.sh" >/dev/null
fi
occu_targets=()
for ext in "${exts[@]}" "${!upstream[@]}"; do
    for c in "$OCCU_ROOT"/tests/spec/"$ext"/*.c; do
        occu_targets+=("tests/occu-$ext-$(basename "$c" .c)")
    done
done
say "building occu's test programs in $build"
nice ninja -C "$build" -j2 "${occu_targets[@]}" >"$work/occu-ninja.log" 2>&1 ||
    { tail -n 30 "$work/occu-ninja.log" >&2; die "occu's test programs did not build (log: $work/occu-ninja.log)"; }

# --- the scratch copy of the piglit tree, with the tests in it ---------------------
# Copied once per tree: again when its path, its git commit or the times of
# the files the script patches change. The files the script writes are
# replaced only when their content changes, so that the build stays
# incremental.
stamp="$tree $(git -C "$tree" rev-parse HEAD 2>/dev/null || true) $(cd "$tree" && stat -c %Y "${patched[@]}" | tr '\n' ' ')"
if [ "$(cat "$work/tree" 2>/dev/null)" != "$stamp" ] || [ ! -d "$src" ]; then
    say "copying $tree to $src"
    rm -rf "$src" "$work/build"
    mkdir -p "$src"
    (cd "$tree" && tar --exclude=./.git -cf - .) | (cd "$src" && tar -xf -)
    rm -rf "$work/orig"
    for f in "${patched[@]}"; do
        mkdir -p "$work/orig/$(dirname "$f")"
        cp "$src/$f" "$work/orig/$f"
    done
    echo "$stamp" >"$work/tree"
fi
put() {  # FILE DEST: copies FILE to DEST unless DEST has its content already
    cmp -s "$1" "$2" 2>/dev/null || { mkdir -p "$(dirname "$2")"; cp "$1" "$2"; }
}
for ext in "${exts[@]}"; do
    for f in "$OCCU_ROOT"/tests/spec/"$ext"/*.[ch] "$OCCU_ROOT"/tests/spec/"$ext"/CMakeLists*.txt; do
        put "$f" "$src/tests/spec/$ext/$(basename "$f")"
    done
done
put "$OCCU_ROOT/include/GL/mesax_occlusion_unit.h" "$src/tests/spec/mesax_occlusion_unit/GL/mesax_occlusion_unit.h"
for ext in "${!upstream[@]}"; do
    for f in "$OCCU_ROOT"/tests/spec/"$ext"/*.c; do
        put "$f" "$src/${upstream[$ext]}/$(basename "$f")"
    done
done
upstream_args=()
for ext in "${!upstream[@]}"; do upstream_args+=("$ext=${upstream[$ext]}"); done

# registry/gl.xml: the extensions' enums, commands and extension entries,
# read from include/GL/mesax_occlusion_unit.h (names as spec/*.txt spell
# them). piglit's dispatch resolves only the commands of its registry
# (a call of any other function skips the test); Khronos's gl.xml,
# from which piglit's is updated, has none of these extensions yet.
# tests/spec/CMakeLists.txt: the three folders, at its end (its list has no
# order to keep).
# tests/opengl.py: a group per extension, one test per piglit_add_executable of
# its CMakeLists.gl.txt, plus the registrations with arguments that
# tests/meson.build makes too (-tiles-4096, -base-extension-only).
# The upstream behaviour tests: each into piglit's folder of its feature, as
# <folder>-<test> in its CMakeLists.gl.txt and in that feature's group.
# $work/filters: the regular expressions of every test added (piglit run -t).
/usr/bin/python3 - "$work" "$src" "$OCCU_ROOT" "${exts[@]}" -- "${upstream_args[@]}" <<'EOF'
import os, re, sys
work, src, root = sys.argv[1], sys.argv[2], sys.argv[3]
sep = sys.argv.index('--')
exts, upstream = sys.argv[4:sep], dict(a.split('=', 1) for a in sys.argv[sep + 1:])

def orig(path):
    return open(os.path.join(work, 'orig', path)).read()

def put(path, text):
    old = open(path).read() if os.path.exists(path) else None
    if old != text:
        with open(path, 'w') as f:
            f.write(text)

header = open(os.path.join(root, 'include/GL/mesax_occlusion_unit.h')).read()
camel = {}
for spec in sorted(os.listdir(os.path.join(root, 'spec'))):
    for word in re.findall(r'\b([A-Za-z]+MESAX)\(', open(os.path.join(root, 'spec', spec)).read()):
        word = word[2:] if word.startswith('gl') else word
        camel['GL' + word.upper()] = 'gl' + word
enums, commands, extensions = [], [], []
for ext, body in re.findall(r'#ifndef (GL_MESAX_\w+)\n#define \1 1\n(.*?)\n#endif', header, re.S):
    required = []
    for name, value in re.findall(r'^#define (GL_\w+)\s+(0x[0-9A-Fa-f]+)', body, re.M):
        enums.append('        <enum value="%s" name="%s"/>\n' % (value, name))
        required.append('                <enum name="%s"/>\n' % name)
    for ret, pfn, params in re.findall(r'typedef (\w+) \(APIENTRYP PFN(\w+)PROC\)\(([^;]*)\);', body):
        name = camel[pfn]
        xml = ['        <command>\n', '            <proto>%s <name>%s</name></proto>\n' % (ret, name)]
        for param in re.split(r'\s*,\s*', ' '.join(params.split())):
            if param in ('', 'void'):
                continue
            m = re.match(r'(.*?)(\w+)$', param)
            xml.append('            <param>%s <name>%s</name></param>\n' % (m.group(1).strip(), m.group(2)))
        xml.append('        </command>\n')
        commands.append((name, ''.join(xml)))
        required.append('                <command name="%s"/>\n' % name)
    extensions.append('        <extension name="%s" supported="gl">\n            <require>\n%s'
                      '            </require>\n        </extension>\n' % (ext, ''.join(required)))
registry = orig('registry/gl.xml')
anchor = '    <!-- SECTION: GL command definitions. -->'
assert anchor in registry and '    </commands>' in registry and '    </extensions>' in registry
registry = registry.replace(anchor, '    <enums namespace="GL" group="MESAX_occlusion_unit" vendor="MESAX" '
                            'comment="tokens of GL_MESAX_occlusion_unit*, in no vendor\'s block yet">\n'
                            + ''.join(enums) + '    </enums>\n\n' + anchor, 1)
# In the registry's (strcmp) order: piglit's dispatch looks names up by bsearch
# in the order of the file.
for name, xml in commands:
    start = registry.index('    <commands namespace="GL">')
    end = registry.index('    </commands>', start)
    at = end
    for m in re.finditer(r'        <command>\s*<proto>[^\n]*?<name>(\w+)</name>', registry[start:end]):
        if m.group(1) > name:
            at = start + m.start()
            break
    registry = registry[:at] + xml + registry[at:]
registry = registry.replace('    </extensions>', ''.join(extensions) + '    </extensions>', 1)
put(os.path.join(src, 'registry/gl.xml'), registry)

lines = orig('tests/spec/CMakeLists.txt').splitlines(keepends=True)
for ext in exts:
    entry = 'add_subdirectory (%s)\n' % ext
    if entry in lines:
        continue
    lines.append(entry)
put(os.path.join(src, 'tests/spec/CMakeLists.txt'), ''.join(lines))

# Registrations with arguments: test -> [(name suffix, arguments)].
variants = {
    ('mesax_occlusion_unit', 'limits'): [('-tiles-4096', ['-tiles-4096'])],
    ('mesax_occlusion_unit', 'out-of-memory-fault-injection'): [('-tiles-4096', ['-tiles-4096'])],
    ('mesax_occlusion_unit', 'api-random-calls'): [('-base-extension-only', ['-base-extension-only'])],
}
block = []
for ext in exts:
    cmake = open(os.path.join(root, 'tests/spec', ext, 'CMakeLists.gl.txt')).read()
    group = ext[:5].upper() + ext[5:]   # MESAX_occlusion_unit, as piglit names ARB_depth_clamp
    block.append('\n# Group %s\n' % group)
    block.append('with profile.test_list.group_manager(\n'
                 '        PiglitGLTest,\n'
                 "        grouptools.join('spec', '%s')) as g:\n" % group)
    for exe, source in re.findall(r'^piglit_add_executable \((\S+) (\S+)\.c\)', cmake, re.M):
        name = exe[len(ext) + 1:]
        block.append("    g(['%s'], '%s')\n" % (exe, name))
        for suffix, args in variants.get((ext, name), []):
            block.append("    g(['%s', %s], '%s%s')\n" % (exe, ', '.join("'%s'" % a for a in args), name, suffix))
filters = ['^spec@%s@' % ext for ext in exts]
groups = {'arb_occlusion_query': "'spec', 'ARB_occlusion_query'", 'arb_depth_clamp': "'spec', 'ARB_depth_clamp'",
          'arb_shader_image_load_store': "'spec', 'arb_shader_image_load_store'",
          'glsl-1.10': "'spec', 'glsl-1.10', 'execution'"}
for ext, folder in sorted(upstream.items()):
    names = sorted(f[:-2] for f in os.listdir(os.path.join(root, 'tests/spec', ext)) if f.endswith('.c'))
    cmake = orig(os.path.join(folder, 'CMakeLists.gl.txt'))
    tail = ''.join('piglit_add_executable (%s-%s %s.c)\n' % (ext, n, n) for n in names)
    anchor = '\n# vim: ft=cmake:'
    cmake = cmake.replace(anchor, '\n' + tail + anchor, 1) if anchor in cmake else cmake + tail
    put(os.path.join(src, folder, 'CMakeLists.gl.txt'), cmake)
    block.append('\nwith profile.test_list.group_manager(\n'
                 '        PiglitGLTest,\n'
                 '        grouptools.join(%s)) as g:\n' % groups[ext])
    for n in names:
        block.append("    g(['%s-%s'], '%s')\n" % (ext, n, n))
        filters.append('^%s@%s$' % (groups[ext].replace("'", '').replace(', ', '@').lower(), re.escape(n)))
with open(os.path.join(work, 'filters'), 'w') as f:
    f.write('\n'.join(filters) + '\n')
opengl = orig('tests/opengl.py')
anchor = "\nif platform.system() == 'Windows':"
assert anchor in opengl, 'tests/opengl.py: no "%s" to add the groups before' % anchor.strip()
opengl = opengl.replace(anchor, ''.join(block) + anchor, 1)
put(os.path.join(src, 'tests/opengl.py'), opengl)
EOF

# --- piglit's build -----------------------------------------------------------------
mkdir -p "$work/build"
if [ ! -f "$work/build/build.ninja" ]; then
    say "configuring piglit in $work/build"
    (cd "$work/build" && cmake -G Ninja "$src" -Wno-dev -DCMAKE_BUILD_TYPE=Release \
        -DPYTHON_EXECUTABLE=/usr/bin/python3 \
        -DPIGLIT_BUILD_GL_TESTS=ON -DPIGLIT_USE_WAFFLE=ON \
        -DPIGLIT_BUILD_GLES1_TESTS=OFF -DPIGLIT_BUILD_GLES2_TESTS=OFF -DPIGLIT_BUILD_GLES3_TESTS=OFF \
        -DPIGLIT_BUILD_CL_TESTS=OFF -DPIGLIT_BUILD_VK_TESTS=OFF -DPIGLIT_BUILD_GLX_TESTS=OFF \
        -DPIGLIT_BUILD_WGL_TESTS=OFF -DPIGLIT_BUILD_DMA_BUF_TESTS=OFF \
        -DPIGLIT_USE_WAYLAND=OFF -DPIGLIT_USE_GBM=OFF) >"$work/cmake.log" 2>&1 ||
        { tail -n 30 "$work/cmake.log" >&2; die "piglit's CMake failed (log: $work/cmake.log)"; }
fi
piglit_targets=()
for ext in "${exts[@]}"; do
    while read -r exe; do piglit_targets+=("$exe"); done < <(
        sed -n 's/^piglit_add_executable (\([^ ]*\) .*/\1/p' "$src/tests/spec/$ext/CMakeLists.gl.txt")
done
for ext in "${!upstream[@]}"; do
    for c in "$OCCU_ROOT"/tests/spec/"$ext"/*.c; do piglit_targets+=("$ext-$(basename "$c" .c)"); done
done
filter=()
while read -r f; do filter+=(-t "$f"); done <"$work/filters"
say "building ${#piglit_targets[@]} tests and piglit's util libraries in $work/build"
nice ninja -C "$work/build" -j2 "${piglit_targets[@]}" >"$work/ninja.log" 2>&1 ||
    { grep -E 'error|FAILED' "$work/ninja.log" | head -n 30 >&2; die "piglit's build failed (log: $work/ninja.log)"; }

# --- the runs -------------------------------------------------------------------------
# occu's profile: the piglit profile's test names and arguments, each on
# occu's program of the same source (tests/occu-<ext>-<test>).
export PIGLIT_BUILD_DIR=$work/build
commands=$work/piglit-commands.txt
/usr/bin/python3 "$src/piglit-print-commands.py" "${filter[@]}" opengl >"$commands"
/usr/bin/python3 - "$commands" "$build/tests" "$work/occu-profile.xml.gz" <<'EOF'
import gzip, os, shlex, sys
import xml.etree.ElementTree as et
commands, occu_bin, out = sys.argv[1:]
root = et.Element('PiglitTestList', name='occu-same-as-piglit')
n = 0
for line in open(commands):
    name, sep, command = line.rstrip('\n').partition(' ::: ')
    if not sep:
        continue
    argv = shlex.split(command)
    program = os.path.join(occu_bin, 'occu-' + os.path.basename(argv[0]))
    if not os.path.exists(program):
        sys.exit('no occu program %s for piglit test %s' % (program, name))
    t = et.SubElement(root, 'Test', type='gl', name=name)
    et.SubElement(t, 'option', name='command', value=repr([program] + argv[1:]))
    et.SubElement(t, 'option', name='run_concurrent', value='True')
    n += 1
root.set('count', str(n))
with gzip.open(out, 'wt') as f:
    f.write(et.tostring(root, encoding='unicode'))
EOF
count=$(grep -c ' ::: ' "$commands")
[ "$count" -gt 0 ] || die "the patched tests/opengl.py lists none of the tests added"

results=$work/results
rm -rf "$results"
mkdir -p "$results"
for driver in softpipe llvmpipe; do
    for side in piglit occu; do
        profile=opengl
        filters=("${filter[@]}")
        if [ $side = occu ]; then profile=$work/occu-profile.xml.gz; filters=(); fi
        say "$side's build under $driver: piglit run ($count tests)"
        GALLIUM_DRIVER=$driver nice /usr/bin/python3 "$src/piglit" run -p surfaceless_egl -c -j 2 \
            --timeout 300 -l dummy ${filters[@]+"${filters[@]}"} "$profile" "$results/$side-$driver" >"$results/$side-$driver.log" 2>&1 ||
            { tail -n 20 "$results/$side-$driver.log" >&2; die "piglit run failed (log: $results/$side-$driver.log)"; }
    done
done

# --- the comparison --------------------------------------------------------------------
/usr/bin/python3 - "$results" <<'EOF'
import bz2, gzip, json, os, sys
results = sys.argv[1]

def load(d):
    for name, opener in (('results.json.bz2', bz2.open), ('results.json.gz', gzip.open),
                         ('results.json.xz', None), ('results.json', open)):
        p = os.path.join(d, name)
        if os.path.exists(p):
            if opener is None:
                import lzma
                opener = lzma.open
            with opener(p, 'rt') as f:
                data = json.load(f)
            out = {}
            for test, r in data['tests'].items():
                out[test] = r['result']
                for sub, s in (r.get('subtests') or {}).items():
                    out[test + ' : ' + sub] = s
            return out
    sys.exit('no results in %s' % d)

differences = 0
for driver in ('softpipe', 'llvmpipe'):
    p, o = load(os.path.join(results, 'piglit-' + driver)), load(os.path.join(results, 'occu-' + driver))
    tests = sorted(n for n in p if ' : ' not in n)
    subtests = sorted(n for n in set(p) | set(o) if ' : ' in n)
    def counts(r):
        c = {}
        for n, s in r.items():
            if ' : ' not in n:
                c[s] = c.get(s, 0) + 1
        return ', '.join('%s %d' % kv for kv in sorted(c.items()))
    print('%s: %d tests, %d subtests' % (driver, len(tests), len(subtests)))
    print('  piglit framework: %s' % counts(p))
    print('  occu framework:   %s' % counts(o))
    skipped = [n for n in tests if p[n] == 'skip' and o.get(n) == 'skip']
    if skipped:
        print('  skipped by both: %s' % ', '.join(n.split('@', 1)[1] for n in skipped))
    for n in sorted(set(p) | set(o)):
        a, b = p.get(n, 'not run'), o.get(n, 'not run')
        if a != b:
            differences += 1
            print('  DIFFERENT %s: piglit %s, occu %s' % (n, a, b))
if differences:
    print('%d results differ between piglit\'s framework and occu\'s (results: %s)' % (differences, results))
    sys.exit(1)
print('every test and subtest has the same result on piglit\'s framework and occu\'s, under both drivers')
EOF
