#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The API walk (tests/spec/mesax_occlusion_unit/api-random-calls.c) at
# 1,000,000 calls per driver, from its fixed seed, on the patched Mesa with
# the files the series changes built with AddressSanitizer and
# UndefinedBehaviorSanitizer (tools/mesa.sh --sanitize, as tools/fuzz-api
# runs it at 30,000), with --all on all of Mesa built with both
# (tools/mesa.sh --sanitize-all: it also catches upstream Mesa's own errors on
# the walk's paths), or, with --plain, on the patched Mesa without them.
# A run passes when the walk reports pass and
# AddressSanitizer reports nothing (UBSan reports are counted: upstream
# Mesa 22.3.6 has its own, see tools/fuzz-api).
# Usage: bench/api-walk.sh [--plain | --all] [CALLS]      (default 1000000)
# Prints a markdown table: calls/s of wall and of CPU time (user + system),
# the walk's counters, and any failure with its log.
set -euo pipefail
source "$(dirname "$0")/lib.sh"
mesa=sanitized
case ${1:-} in
    --plain) mesa=plain; shift ;;
    --all) mesa=sanitized-all; shift ;;
esac
calls=${1:-1000000}
[[ $calls =~ ^[0-9]+$ ]] && [ "$calls" -ge 1000 ] || die "bench/api-walk.sh: CALLS must be a whole number of at least 1000, not '$calls'"
prefix=$("$OCCU_ROOT/tools/build.sh" bench)
walk=$OCCU_ROOT/build/tests/occu-mesax_occlusion_unit-api-random-calls
out=$OCCU_ROOT/build/bench-api-walk
mkdir -p "$out"
run_env=(LD_LIBRARY_PATH="$prefix/lib")
if [ $mesa != plain ]; then
    sanitized=$("$OCCU_ROOT/tools/mesa.sh" --${mesa/sanitized/sanitize})
    run_env=(LD_PRELOAD="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)"
             LD_LIBRARY_PATH="$sanitized/lib" ASAN_OPTIONS=detect_leaks=0:halt_on_error=1
             UBSAN_OPTIONS=halt_on_error=0:print_stacktrace=0)
fi

echo "## API walk, $calls calls per driver, $mesa Mesa (commit $(git -C "$OCCU_ROOT" rev-parse --short HEAD))"
echo
echo "| driver | result | wall s | calls/s (wall) | CPU s | calls/s (CPU) | passes | records | queries vs NOHC | empty passes | framebuffer changes refused | UBSan reports |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for driver in softpipe llvmpipe; do
    log=$out/$driver-$mesa-$calls.log
    times=$out/$driver-$mesa-$calls.time
    status=0
    /usr/bin/time -o "$times" -f '%e %U %S' env "${run_env[@]}" GALLIUM_DRIVER=$driver OU_RANDOM_CALLS=$calls \
        "$walk" -auto -fbo >"$log" 2>&1 || status=$?
    read -r wall user sys < <(tail -n 1 "$times")   # after "Command exited with non-zero status N"
    result=pass
    if [ $status -ne 0 ] || ! grep -q '"result": "pass"' "$log" || grep -qE 'ERROR: (Address|Leak)Sanitizer' "$log"; then
        result="FAIL (exit $status, $log)"
    fi
    /usr/bin/python3 - "$driver" "$result" "$calls" "$wall" "$user" "$sys" "$log" <<'PY'
import re, sys
driver, result, calls, wall, user, sys_s, log = sys.argv[1:]
calls, wall, cpu = int(calls), float(wall), float(user) + float(sys_s)
text = open(log, errors='replace').read()
def count(what):
    m = re.search(r'(\d+) ' + what, text)
    return m.group(1) if m else '-'
counters = [count(w) for w in ('passes ended', 'records checked', 'queries compared', 'empty passes',
                               'refused in a pass')]
# A failed run stops somewhere short of CALLS, which the walk does not print: no rates.
rates = [f"{calls / wall:,.0f}", f"{calls / cpu:,.0f}"] if result == 'pass' else ['-', '-']
cells = [driver, result, f"{wall:.0f}", rates[0], f"{cpu:.1f}", rates[1]] + counters
cells.append(str(text.count('runtime error:')))
print('| ' + ' | '.join(cells) + ' |')
PY
    [ "$result" = pass ] || grep -E 'ERROR:|^call|"fail"' "$log" | head -n 5 >&2
done
