#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Records tests/piglit/baseline.txt: the results of the regression list on
# Debian's own, unpatched Mesa of the same version (packages libegl-mesa0 and
# libgl1-mesa-dri), under softpipe and llvmpipe, run exactly as the regression
# run runs the patched one. Run it once, when the list changes; keep the
# reasons: an existing reason for the same test and result is carried over,
# a new non-pass gets 'REASON?', which compare.py rejects until it is written.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../../tools/lib.sh"

missing=()
for p in piglit libegl-mesa0 libgl1-mesa-dri; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] || as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
version=$(dpkg-query -W -f='${Version}' libegl-mesa0)
case $version in
    "$MESA_UPSTREAM_VERSION"-*) ;;
    *) die "Debian's libegl-mesa0 is $version, not Mesa $MESA_UPSTREAM_VERSION" ;;
esac

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 "$here/make_profile.py" "$work/regression.xml.gz" --drivers softpipe,llvmpipe \
    --debian-list "$here/regression.list"
# Debian's Mesa: none of occu's overrides.
env -u __EGL_VENDOR_LIBRARY_FILENAMES -u LIBGL_DRIVERS_PATH -u LD_LIBRARY_PATH \
    piglit run -p surfaceless_egl -l quiet "$work/regression.xml.gz" "$work/results" >/dev/null

/usr/bin/python3 - "$work/results" "$here/baseline.txt" "$version" "$here" <<'PY'
import bz2, json, os, sys
results_dir, out, version, here = sys.argv[1:]
sys.path.insert(0, here)
from compare import flatten   # a line per test and per subtest, as compare.py reads them
with bz2.open(os.path.join(results_dir, 'results.json.bz2'), 'rt') as f:
    results = flatten(json.load(f)['tests'])
reasons = {}
if os.path.exists(out):
    for line in open(out):
        body, sep, reason = line.strip().partition('#')
        if sep and body.strip():
            result, _, name = body.strip().partition(' ')
            reasons[(name.strip(), result)] = reason.strip()
with open(out, 'w') as f:
    f.write(f'''# Baseline of the piglit regression run: results of tests/piglit/regression.list on
# Debian's unpatched Mesa {version} (libegl-mesa0, libgl1-mesa-dri), surfaceless EGL, -auto -fbo.
# Made with tests/piglit/record-baseline.sh; checked by tests/piglit/compare.py, which fails a
# run of the patched Mesa on any result worse than the one here.
# Format: RESULT NAME [# reason]; every expected non-pass says why.
# A test that reports subtests also has a line per subtest, NAME@SUBTEST.
''')
    for name in sorted(results):
        r = results[name]
        line = f'{r:<5} {name}'
        if r != 'pass':
            line += '  # ' + reasons.get((name, r), 'REASON?')
        f.write(line + '\n')
PY
echo "wrote $here/baseline.txt"
