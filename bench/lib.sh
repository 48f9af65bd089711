# SPDX-License-Identifier: MIT
# Shared helpers of the bench scripts (sourced, not run): the walkthrough's
# results are read from its summary.csv by column name.
source "$(dirname "${BASH_SOURCE[0]}")/../tools/lib.sh"

# field SUMMARY STRATEGY COLUMN: one value of the walkthrough's summary.csv.
field() {
    awk -F, -v strategy="$2" -v column="$3" '
        NR == 1 { for (i = 1; i <= NF; i++) at[$i] = i
                  if (!(column in at)) { print "no column " column > "/dev/stderr"; exit 1 } next }
        $1 == strategy { print $at[column]; found = 1 }
        END { if (!found) print "-" }' "$1"
}

# The minimum-occluder-set database for the given occu-preprocess build
# options, made once into build/occluders/ (its path on stdout).
occluder_db() {
    "$OCCU_ROOT/build/demos/occu-preprocess" build --cache "$OCCU_ROOT/build/occluders" "$@"
}

# The walkthrough's arguments that have every database a strategy reads
# and was not given made once into build/databases/ (by the walkthrough's
# database provider, named by everything it depends on) and found there
# afterwards, so that no frame time includes making one.
databases=(--databases "$OCCU_ROOT/build/databases" --make-databases all)
