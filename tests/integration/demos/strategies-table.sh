#!/bin/sh
# SPDX-License-Identifier: MIT
# The strategies table of docs/strategies.md is the registry's: the lines
# between its two markers are exactly what `walkthrough --list-strategies
# --markdown` prints, so the table cannot drift from the families, their
# presets, papers and settings. With --write the script puts the program's table there instead
# of checking it.
# Usage: strategies-table.sh WALKTHROUGH PAGE [--write]
set -u
walkthrough=$1
page=$2
mode=${3:-check}
begin='<!-- strategies: walkthrough --list-strategies --markdown -->'
end='<!-- end of strategies -->'
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

for marker in "$begin" "$end"; do
    count=$(grep -c -F -x -e "$marker" "$page")
    if [ "$count" != 1 ]; then
        echo "FAIL: $page has the line '$marker' $count times, not once"
        exit 1
    fi
done
if [ "$(grep -n -F -x -e "$begin" "$page" | cut -d: -f1)" -gt "$(grep -n -F -x -e "$end" "$page" | cut -d: -f1)" ]; then
    echo "FAIL: $page's strategies table ends before it begins"
    exit 1
fi
if ! "$walkthrough" --list-strategies --markdown >"$dir/program.md"; then
    echo "FAIL: $walkthrough --list-strategies --markdown failed"
    exit 1
fi
if [ "$(wc -l <"$dir/program.md")" -lt 3 ]; then
    echo "FAIL: $walkthrough --list-strategies --markdown printed no table"
    exit 1
fi
# The page in three parts: up to the first marker, the table, from the second.
awk -v b="$begin" -v e="$end" -v dir="$dir" '
    $0 == e { part = 2 }
    { print > (dir "/part" (part + 0) ".md") }
    $0 == b { part = 1 }
' "$page"
touch "$dir/part1.md"

if [ "$mode" = --write ]; then
    cat "$dir/part0.md" "$dir/program.md" "$dir/part2.md" >"$dir/page.md" && cp "$dir/page.md" "$page"
    exit
fi
if ! diff -u "$dir/part1.md" "$dir/program.md"; then
    echo "FAIL: $page's strategies table (-) differs from the registry's (+);"
    echo "      tests/integration/demos/strategies-table.sh WALKTHROUGH $page --write puts the registry's there"
    exit 1
fi
echo "PASS: $page's strategies table is the registry's ($(($(wc -l <"$dir/program.md") - 2)) families)"
