# SPDX-License-Identifier: MIT
# Sourced after expect-error.sh ($dir, $failures) by the tests that read a
# walkthrough's summary.csv:
#   walk LABEL OUT ARGS...   runs "$walkthrough" ARGS --out OUT (its output
#                            in OUT.out); on a non-zero status or no
#                            OUT/summary.csv prints FAIL with LABEL and the
#                            output, counts a failure and returns 1
#   column NAME FILE         the number of summary.csv's column NAME
walk() {
    label=$1
    out=$2
    shift 2
    status=0
    "$walkthrough" "$@" --out "$out" >"$out.out" 2>&1 || status=$?
    if [ $status -ne 0 ] || [ ! -f "$out/summary.csv" ]; then
        echo "FAIL (status $status): $label"
        sed 's/^/    /' "$out.out"
        failures=$((failures + 1))
        return 1
    fi
}

column() { head -n 1 "$2" | tr ',' '\n' | grep -nx "$1" | cut -d: -f1; }
