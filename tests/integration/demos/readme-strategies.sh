#!/bin/sh
# README's strategies table is the registry's: the lines between its two
# markers are exactly what `walkthrough --list-strategies --markdown` prints,
# so the table cannot drift from the families, their presets, papers and
# settings. With --write the script puts the program's table there instead
# of checking it.
# Usage: readme-strategies.sh WALKTHROUGH README [--write]
set -u
walkthrough=$1
readme=$2
mode=${3:-check}
begin='<!-- strategies: walkthrough --list-strategies --markdown -->'
end='<!-- end of strategies -->'
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

for marker in "$begin" "$end"; do
    count=$(grep -c -F -x -e "$marker" "$readme")
    if [ "$count" != 1 ]; then
        echo "FAIL: $readme has the line '$marker' $count times, not once"
        exit 1
    fi
done
if [ "$(grep -n -F -x -e "$begin" "$readme" | cut -d: -f1)" -gt "$(grep -n -F -x -e "$end" "$readme" | cut -d: -f1)" ]; then
    echo "FAIL: $readme's strategies table ends before it begins"
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
# The README in three parts: up to the first marker, the table, from the second.
awk -v b="$begin" -v e="$end" -v dir="$dir" '
    $0 == e { part = 2 }
    { print > (dir "/part" (part + 0) ".md") }
    $0 == b { part = 1 }
' "$readme"
touch "$dir/part1.md"

if [ "$mode" = --write ]; then
    cat "$dir/part0.md" "$dir/program.md" "$dir/part2.md" >"$dir/readme.md" && cp "$dir/readme.md" "$readme"
    exit
fi
if ! diff -u "$dir/part1.md" "$dir/program.md"; then
    echo "FAIL: README's strategies table (-) differs from the registry's (+);"
    echo "      tests/integration/demos/readme-strategies.sh WALKTHROUGH README.md --write puts the registry's there"
    exit 1
fi
echo "PASS: README's strategies table is the registry's ($(($(wc -l <"$dir/program.md") - 2)) families)"
