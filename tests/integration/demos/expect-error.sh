# SPDX-License-Identifier: MIT
# Sourced by the demos' bad-input tests: a scratch directory $dir (removed
# at exit), a failure count, and
#   expect_error WHAT-THE-MESSAGE-NAMES COMMAND...
# which passes when the command fails (not by a signal: a crash is a
# failure too) with a message naming WHAT, and counts a failure otherwise.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0

expect_error() {
    named=$1
    shift
    status=0
    "$@" >"$dir/out" 2>&1 || status=$?
    if [ $status -eq 0 ] || [ $status -gt 128 ]; then
        echo "FAIL (status $status): $*"
        failures=$((failures + 1))
    elif ! grep -qF -- "$named" "$dir/out"; then
        echo "FAIL (message does not name '$named'): $*"
        sed 's/^/    /' "$dir/out"
        failures=$((failures + 1))
    else
        echo "ok: $* -> $(head -n 1 "$dir/out")"
    fi
}
